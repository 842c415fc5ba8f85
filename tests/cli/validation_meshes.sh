#!/usr/bin/env bash
# The meshes behind doc/validation.md are still the ones gmsh makes from the
# .geo files: every "small" row of doc/validation/meshes.csv is remeshed and
# compared (counts and hash, tests/tools/mesh_digest.py); the large rows are
# left to make validate. The .msh files already beside the .geo are checked
# too. Negative controls: a .geo whose h was changed, and a
# mesh with one node moved by 1e-6 (same counts), must both be caught.
set -u
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
cd "$ROOT"
PYTHON=${PYTHON:-/usr/bin/python3}
MANIFEST=doc/validation/meshes.csv
DIGEST=tests/tools/mesh_digest.py
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
fails=0 n=0 t0=$SECONDS
rows=$($PYTHON -c '
import csv, sys
for r in csv.DictReader(l for l in open(sys.argv[1]) if not l.startswith("#")):
    print("|".join([r["deck"], r["geo"], r["gmsh_options"], r["size"]]))' $MANIFEST)
while IFS='|' read -r deck geo opts size; do
  [ "$size" = small ] || { echo "skipped (large): $deck"; continue; }
  n=$((n+1))
  # word splitting of $opts is wanted: "-setnumber h 0.4"
  if gmsh -3 -format msh41 -v 0 $opts "$geo" -o "$W/$deck.msh" > "$W/$deck.log" 2>&1 &&
     $PYTHON $DIGEST "$W/$deck.msh" --manifest $MANIFEST --geo "$geo" --options "$opts"; then
    echo "PASS mesh_$deck"
  else
    cat "$W/$deck.log"; echo "FAIL mesh_$deck"; fails=$((fails+1))
  fi
done <<< "$rows"
[ $n -ge 20 ] && echo "PASS small_rows_found ($n)" || { echo "FAIL only $n small rows read from $MANIFEST"; fails=$((fails+1)); }
echo "gmsh and hashing of $n meshes: $((SECONDS-t0)) s"

# the .msh files beside the .geo (made by make meshes, used by the
# regressions and make run) must be these meshes too: make does not remake a
# .msh newer than its .geo, and such a stale one once stood for the wrong
# mesh (validation.md 4j)
while IFS='|' read -r deck geo opts size; do
  msh=${geo%.geo}.msh
  [ -z "$opts" ] && [ -f "$msh" ] || continue
  if $PYTHON $DIGEST "$msh" --manifest $MANIFEST --geo "$geo" > "$W/beside.txt"; then echo "PASS file_$deck"
  else cat "$W/beside.txt"; echo "FAIL $msh is not the mesh $geo gives: remove it and run make meshes"; fails=$((fails+1)); fi
done <<< "$rows"

# negative control 1: the Wilkins-Guinan .geo with h 0.6 -> 0.59 mm must not
# pass for the documented mesh
sed 's/h = {0.6, Name/h = {0.59, Name/' tests/regression/taylor_wg/taylor_wg.geo > "$W/taylor_wg.geo"
grep -q 'h = {0.59' "$W/taylor_wg.geo" || { echo "FAIL could not edit h"; fails=$((fails+1)); }
gmsh -3 -format msh41 -v 0 "$W/taylor_wg.geo" -o "$W/changed_h.msh"
$PYTHON $DIGEST "$W/changed_h.msh" --manifest $MANIFEST --geo tests/regression/taylor_wg/taylor_wg.geo > "$W/neg1.txt"
rc=$?; cat "$W/neg1.txt"
if [ $rc = 1 ] && grep -q 'MESH DIFFERS.*taylor_wg' "$W/neg1.txt"; then echo "PASS changed_h_detected"
else echo "FAIL a changed h was not detected (exit $rc)"; fails=$((fails+1)); fi

# negative control 2: one node of the plate-impact column moved by 1e-6 m;
# the counts are the same, only the hash can see it
$PYTHON - tests/regression/plate_impact/plate_impact.geo "$W/moved.msh" <<'PY'
import subprocess, sys
subprocess.run(['gmsh', '-3', '-format', 'msh41', '-v', '0', sys.argv[1], '-o', sys.argv[2]], check=True)
lines = open(sys.argv[2]).read().split('\n')
i = lines.index('$Nodes') + 2   # after the summary line
while True:                      # the first block with nodes: tags, then coordinates
    n = int(lines[i].split()[3]); i += 1
    if n:
        break
x = lines[i + n].split(); x[0] = repr(float(x[0]) + 1e-6); lines[i + n] = ' '.join(x)
open(sys.argv[2], 'w').write('\n'.join(lines))
PY
$PYTHON $DIGEST "$W/moved.msh" --manifest $MANIFEST --geo tests/regression/plate_impact/plate_impact.geo > "$W/neg2.txt"
rc=$?; cat "$W/neg2.txt"
if [ $rc = 1 ] && grep -q 'expected 1809 nodes, 4800 tetrahedra' "$W/neg2.txt"; then echo "PASS moved_node_detected"
else echo "FAIL a moved node was not detected (exit $rc)"; fails=$((fails+1)); fi
[ $fails -eq 0 ]
