# Sourced by the validation scripts: the project root, the Python with
# numpy/h5py, the work folder $W (build/validate/NAME, or under
# $VALIDATE_WORK), JOBS runs at a time, and a copy of bin/udar in $W (a
# rebuild during the runs must not change them).
#   source tests/validate_common.sh NAME
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
ROOT=$PWD
PYTHON=${PYTHON:-/usr/bin/python3}
W=${VALIDATE_WORK:-$ROOT/build/validate}/$1
JOBS=${JOBS:-2}
mkdir -p "$W" doc/validation
# by a new name and a rename: a run of another script may still be using the old copy
cp bin/udar "$W/udar.new.$$" && mv -f "$W/udar.new.$$" "$W/udar"

# Mesh a .geo and compare the mesh with its row of doc/validation/meshes.csv
# (the mesh the documented numbers were computed on): a different gmsh or an
# edited .geo must stop make validate before anything runs, not change the
# numbers silently. Options with no row (a mesh study) get a warning.
#   mesh_checked OUT.msh GEO [gmsh options...]
MANIFEST=doc/validation/meshes.csv
mesh_checked() {
  local out=$1 geo=$2 rc=0; shift 2
  gmsh -3 -format msh41 -v 0 "$@" "$geo" -o "$out"
  $PYTHON tests/tools/mesh_digest.py "$out" --manifest $MANIFEST --geo "$geo" --options "$*" || rc=$?
  case $rc in
    0) ;;
    2) echo "warning: numbers from this mesh are not those of doc/validation.md" ;;
    *) echo "stopped: $geo${*:+ $*} does not give the mesh of $MANIFEST; nothing was run"; exit 1 ;;
  esac
}
# MESHES_ONLY=1: check the meshes and stop (make validate checks every
# script's meshes before its first run)
meshes_checked() {
  if [ "${MESHES_ONLY:-0}" = 1 ]; then exit 0; fi
}

# With EPS_CONVERT set, every `eroded = 'particles'` material of deck FILE
# (the group's line ending so) converts its strained intact elements at
# EPS_CONVERT; stops unless exactly N lines then say so. Nothing without it.
#   with_eps_convert FILE N
with_eps_convert() {
  [ -n "${EPS_CONVERT:-}" ] || return 0
  sed -i "s|eroded = 'particles'\$|eroded = 'particles', eps_convert = $EPS_CONVERT|" "$1"
  [ "$(grep -c "eps_convert = $EPS_CONVERT" "$1")" = "$2" ] || { echo "deck edit failed: eps_convert in $1"; exit 1; }
}

# A figure of a finished run from its log: the mesh line's tetrahedra, or
# from udar's summary line ("udar: done: N cycles to t = ..., energy error
# E, W s wall (...)"), so no other line that says "done:" or "energy
# error" can be read instead.
#   log_value LOG tets|cycles|energy_error|wall_s
log_value() {
  local line
  case $2 in
    tets) grep -o '[0-9]* tetrahedra\|[0-9]* triangles' "$1" | head -1 | cut -d' ' -f1; return ;;
  esac
  line=$(grep '^udar: done: ' "$1" | tail -1)
  case $2 in
    cycles) sed -n 's/^udar: done: \([0-9]*\) cycles.*/\1/p' <<< "$line" ;;
    energy_error) sed -n 's/.*energy error *\([-+0-9.E]*\),.*/\1/p' <<< "$line" ;;
    wall_s) sed -n 's/.* \([0-9.]*\) s wall.*/\1/p' <<< "$line" ;;
  esac
}
