# Sourced by the CLI tests: the binary under test ($1), the project root, a
# scratch folder removed on exit, and PASS/FAIL bookkeeping.
set -u
EXE=$(realpath "$1")
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
PYTHON=${PYTHON:-/usr/bin/python3}
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
fails=0
ok()  { echo "PASS $1"; }
bad() { echo "FAIL $1"; fails=$((fails+1)); }
# mpirun as root (CI machines) and more ranks than cores
if [ "$(id -u)" = 0 ]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
export OMPI_MCA_rmaps_base_oversubscribe=1
# Restart checks: run DECK (in $W, with its mesh there) straight on 1 rank,
# keeping its history and fields; then restart it from checkpoint 1 on N
# ranks and check both bitwise against the straight run.
#   straight_run CASE      (exit 1 if the run fails)
#   restart_matches_straight CASE N
straight_run() {
  (cd "$W" && timeout 600 "$EXE" $1.nml > straight.log 2>&1) || { cat "$W/straight.log"; bad "straight run"; exit 1; }
  mkdir -p "$W/straight" && cp "$W/out/${1}_history.csv" "$W/out/$1.h5" "$W/straight/"
}
restart_matches_straight() {
  (cd "$W" && timeout 600 mpirun -np $2 "$EXE" --restart out/${1}_ckpt1.h5 $1.nml > restart.log 2>&1) \
    || { cat "$W/restart.log"; bad "restart on $2 ranks"; exit 1; }
  grep 'restart from' "$W/restart.log"
  if cmp -s "$W/straight/${1}_history.csv" "$W/out/${1}_history.csv"; then ok "history_restart_equals_straight"
  else bad "history_restart_equals_straight"; fi
  if h5diff --exclude-path /provenance "$W/straight/$1.h5" "$W/out/$1.h5" > "$W/h5diff.txt" 2>&1; then
    ok "fields_restart_equal_straight"
  else bad "fields_restart_equal_straight"; head "$W/h5diff.txt"; fi
}
