#!/usr/bin/env bash
# Checkpoint and restart: a run stopped at a checkpoint and resumed on a
# different number of ranks ends bitwise equal to the straight run (history,
# fields, final checkpoint); a wall-time limit and SIGUSR1 stop a run with a
# checkpoint (exit 0); missing, truncated and foreign checkpoints are refused
# with exit 3 and nothing is written.
#   restart.sh EXE
source "$(dirname "$0")/common.sh" "$1"
case=taylor_ofhc_baseline
src=$ROOT/tests/regression/$case
# Every run happens in the one folder W/run (the resolved deck stored in the
# outputs names the mesh by its absolute path); outputs are moved aside.
latest() {   # folder: its checkpoint with the highest cycle
  local best=-1 f c
  for f in "$1"/${case}_ckpt*.h5; do
    c=$(h5dump -a /cycle "$f" | sed -n 's/.*(0): \([0-9]*\).*/\1/p')
    [ "$c" -gt "$best" ] && { best=$c; latest_file=$f; }
  done
  echo "$latest_file"
}
same() {   # name, folder a, folder b: history, fields and last checkpoint bitwise equal
  local name=$1 a=$2 b=$3 fine=1
  cmp -s "$a/${case}_history.csv" "$b/${case}_history.csv" || { echo "history differs"; fine=0; }
  h5diff --exclude-path /provenance "$a/$case.h5" "$b/$case.h5" > "$W/diff.txt" 2>&1 || { head "$W/diff.txt"; fine=0; }
  h5diff --exclude-path /provenance "$(latest "$a")" "$(latest "$b")" > "$W/diff.txt" 2>&1 || { head "$W/diff.txt"; fine=0; }
  if [ $fine = 1 ]; then ok "$name"; else bad "$name"; fi
}
run() {   # ranks, udar arguments...
  local n=$1; shift
  (cd "$W/run" && timeout 900 mpirun -np "$n" "$EXE" "$@" >> run.log 2>&1)
}
status() { sed -n 's/^status = //p' "$W/run/out/$case.status"; }
mkdir -p "$W/run"
cp "$src/$case.msh" "$src/$case.nml" "$W/run/"
# 30 us of the Taylor impact with a checkpoint every 15 us (and at the end)
sed -i 's/^\( *\)t_end = .*/\1t_end = 30.0e-6/; s/^\( *\)dt_field = .*/\1dt_field = 10.0e-6, dt_checkpoint = 15.0e-6/' \
  "$W/run/$case.nml"
grep -q 'dt_checkpoint = 15.0e-6' "$W/run/$case.nml" || { bad "deck edit"; exit 1; }
run 1 $case.nml || { cat "$W/run/run.log"; bad "straight run"; exit 1; }
cp -r "$W/run/out" "$W/straight"
cycles=$(h5dump -a /cycle "$W/straight/${case}_ckpt1.h5" | sed -n 's/.*(0): \([0-9]*\).*/\1/p')
echo "MEASURED straight run: checkpoint 1 at cycle $cycles"

# 1. restart from the mid-run checkpoint on 3 ranks (the outputs of the straight run in place)
: > "$W/run/run.log"
run 3 --restart out/${case}_ckpt1.h5 $case.nml || { cat "$W/run/run.log"; bad "restart on 3 ranks"; }
grep -q "restart from out/${case}_ckpt1.h5 at cycle $cycles" "$W/run/run.log" && ok "restart_logged" || bad "restart_logged"
same restart_1_to_3_ranks_bitwise "$W/straight" "$W/run/out"

# 2. stopped by a wall-time limit on 2 ranks, resumed with --restart auto on 4 (limit 120 s: a
# loaded machine must not make the chain endless)
rm -rf "$W/run/out"; : > "$W/run/run.log"
run 2 --wall-limit 1.5 $case.nml || { cat "$W/run/run.log"; bad "wall-limit run"; }
if [ "$(status)" = checkpointed ] && grep -q 'stopped by the wall-time limit' "$W/run/run.log"; then
  ok "wall_limit_stops_with_checkpoint"
else
  tail -5 "$W/run/run.log"; bad "wall_limit_stops_with_checkpoint (status '$(status)')"
fi
for k in 1 2 3 4 5 6; do
  [ "$(status)" = complete ] && break
  run 4 --restart auto --wall-limit 120 $case.nml || { bad "resume $k"; break; }
done
echo "MEASURED wall-limit chain: $(grep -c '^restart from' "$W/run/run.log") restarts, status $(status)"
same wall_limit_chain_bitwise "$W/straight" "$W/run/out"

# 3. SIGUSR1 to mpirun (what the Slurm script sends): checkpoint, exit 0, resume
rm -rf "$W/run/out"; : > "$W/run/run.log"
(cd "$W/run" && exec mpirun -np 2 "$EXE" $case.nml > run.log 2>&1) &
pid=$!
for i in $(seq 1 400); do grep -q '^start:' "$W/run/run.log" 2>/dev/null && break; sleep 0.02; done
kill -USR1 $pid
wait $pid; rc=$?
echo "MEASURED signal: exit $rc, status $(status), $(grep 'stopped by' "$W/run/run.log")"
if [ $rc = 0 ] && [ "$(status)" = checkpointed ]; then
  ok "sigusr1_stops_with_checkpoint"
  # the last picture is the last state: a field step and a history row at the stop
  stop_cycle=$(sed -n 's/.*stopped by .* at cycle \([0-9]*\),.*/\1/p' "$W/run/run.log")
  last=$($PYTHON -c "import h5py,sys; s=h5py.File(sys.argv[1])['steps']; print(s[sorted(s)[-1]].attrs['cycle'])" "$W/run/out/$case.h5")
  row=$(tail -1 "$W/run/out/${case}_history.csv" | cut -d, -f2)
  if [ -n "$stop_cycle" ] && [ "$last" = "$stop_cycle" ] && [ "$row" = "$stop_cycle" ]; then ok "stop_writes_last_state (cycle $stop_cycle)"
  else bad "stop_writes_last_state: stopped at cycle '$stop_cycle', last field step at $last, last history row at $row"; fi
  run 1 --restart auto $case.nml || bad "resume after signal"
  same signal_resume_bitwise "$W/straight" "$W/run/out"
else
  tail -5 "$W/run/run.log"; bad "sigusr1_stops_with_checkpoint"
fi

# 4. refused checkpoints: exit 3, outputs untouched
mkdir -p "$W/refuse"
cp "$W/run/$case.nml" "$W/run/$case.msh" "$W/refuse/"
cp -r "$W/straight" "$W/refuse/out"
before=$(cd "$W/refuse/out" && md5sum $case.h5 ${case}_history.csv)
refuse() {   # name, expected message, udar arguments...
  local name=$1 msg=$2; shift 2
  (cd "$W/refuse" && timeout 300 mpirun -np 2 "$EXE" "$@" > refuse.log 2>&1); local rc=$?
  after=$(cd "$W/refuse/out" && md5sum $case.h5 ${case}_history.csv)
  if [ $rc = 3 ] && grep -q "$msg" "$W/refuse/refuse.log" && [ "$before" = "$after" ]; then ok "$name"
  else echo "exit $rc"; cat "$W/refuse/refuse.log"; bad "$name"; fi
}
refuse refuse_missing_checkpoint 'does not exist' --restart out/nothing.h5 $case.nml
head -c 20000 "$W/refuse/out/${case}_ckpt1.h5" > "$W/refuse/out/truncated.h5"
refuse refuse_truncated_checkpoint 'truncated' --restart out/truncated.h5 $case.nml
sed 's/jc_b = 292.0e6/jc_b = 293.0e6/' "$W/refuse/$case.nml" > "$W/refuse/other.nml"
sed -i "s/^&output/\&output case_name = '$case',/" "$W/refuse/other.nml"
refuse refuse_checkpoint_of_other_deck 'belongs to another deck' --restart out/${case}_ckpt1.h5 other.nml
# the same mesh scaled by 1.0001: same counts, other coordinates
sed "s/scale = 1.0e-3/scale = 1.0001e-3/" "$W/refuse/$case.nml" > "$W/refuse/othermesh.nml"
sed -i "s/^&output/\&output case_name = '$case',/" "$W/refuse/othermesh.nml"
refuse refuse_checkpoint_of_other_mesh 'belongs to another mesh' --restart out/${case}_ckpt1.h5 othermesh.nml
[ $fails -eq 0 ]
