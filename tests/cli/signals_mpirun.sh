#!/usr/bin/env bash
# The documented signals work through mpirun (Open MPI): SIGUSR1 to mpirun
# stops the run with a checkpoint and exit 0; SIGTERM and SIGINT to mpirun
# reach the ranks, which checkpoint and stop (mpirun itself reports 1);
# SIGTERM to the udar processes themselves (scancel --signal) stops with
# exit 0; a signal during set-up is kept and acted on at cycle 10; a second
# SIGTERM ends the program at once and leaves the status file ('running').
#   signals_mpirun.sh EXE
source "$(dirname "$0")/common.sh" "$1"
case=taylor_ofhc_baseline
mkdir -p "$W/run"
cp "$ROOT/tests/regression/$case/$case.msh" "$ROOT/tests/regression/$case/$case.nml" "$W/run/"
sed -i 's/^\( *\)t_end = .*/\1t_end = 200.0e-6/' "$W/run/$case.nml"   # far longer than any test waits
status() { sed -n 's/^status = //p' "$W/run/out/$case.status" 2>/dev/null; }
started() { for i in $(seq 1 1000); do grep -q '^start:' "$W/run/run.log" 2>/dev/null && return 0; sleep 0.01; done; return 1; }
launch() {   # ranks: mpirun in the background, its pid in $pid
  rm -rf "$W/run/out"; : > "$W/run/run.log"
  (cd "$W/run" && exec mpirun -np "$1" "$EXE" $case.nml > run.log 2>&1) &
  pid=$!
  # no timeout(1) in between: it would take the signals meant for mpirun
  ( sleep 120; kill -9 $pid ) > /dev/null 2>&1 &
}
rank_pids() { pgrep -f -- "$EXE $case.nml" | grep -v "^$pid\$" | while read -r p; do
  [ "$(cat /proc/$p/comm 2>/dev/null)" = "$(basename "$EXE" | cut -c1-15)" ] && echo "$p"; done; }
check_stop() {   # name, wanted mpirun exit code, rc
  local name=$1 want=$2 rc=$3
  if [ "$rc" = "$want" ] && [ "$(status)" = checkpointed ] && grep -q 'stopped by a termination signal' "$W/run/run.log" && \
     [ -f "$W/run/out/${case}_ckpt1.h5" ]; then ok "$name (mpirun exit $rc, status checkpointed)"
  else bad "$name: mpirun exit $rc, status '$(status)'"; tail -5 "$W/run/run.log"; fi
}
for sig in USR1 TERM INT; do
  launch 2; started || { bad "run did not start"; continue; }
  sleep 0.3; kill -$sig $pid; wait $pid; rc=$?
  want=0; [ $sig != USR1 ] && want=1
  check_stop "sig${sig}_to_mpirun" $want $rc
done
# SIGTERM to the ranks themselves
launch 2; started
sleep 0.3; kill -TERM $(rank_pids); wait $pid; rc=$?
check_stop "sigterm_to_the_ranks" 0 $rc
# a signal during set-up (before the first cycle): kept, acted on at cycle 10
launch 2
for i in $(seq 1 1000); do [ "$(rank_pids | wc -l)" = 2 ] && break; sleep 0.005; done
ranks=$(rank_pids)
for i in $(seq 1 2000); do grep -q '^mesh ' "$W/run/run.log" && break; sleep 0.002; done
kill -USR1 $ranks 2>/dev/null
grep -q '^start:' "$W/run/run.log" && echo "note: the run had started before the signal"
wait $pid; rc=$?
if [ $rc = 0 ] && [ "$(status)" = checkpointed ] && grep -q 'stopped by a termination signal at cycle 10,' "$W/run/run.log"; then
  ok "signal_during_setup_kept (stopped at cycle 10)"
else bad "signal during set-up: exit $rc, status '$(status)'"; tail -3 "$W/run/run.log"; fi
# a second SIGTERM while the first is served: the program ends at once, the status file stays
launch 1; started
sleep 0.2; p=$(rank_pids); kill -TERM $p; kill -TERM $p; wait $pid; rc=$?
st=$(status)
if [ -n "$st" ]; then ok "second_sigterm_leaves_status ('$st', mpirun exit $rc)"; else bad "no status file after a second SIGTERM"; fi
[ $fails -eq 0 ]
