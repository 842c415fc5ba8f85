#!/usr/bin/env bash
# The Slurm job script (input/batch/udar.slurm) under stand-ins for sbatch,
# scontrol and squeue: each job is stopped by a wall-time limit, resubmits
# itself from its checkpoint until the run is complete, and the chain ends
# bitwise equal to one straight run.
#   slurm_chain.sh EXE
source "$(dirname "$0")/common.sh" "$1"
case=taylor_ofhc_baseline
mkdir -p "$W/fake" "$W/run"
# sbatch runs the job at once (nested); it records its options. With
# FAKE_SIGNALS=1 it also plays the batch system's SIGUSR1: to the first job
# at once (its start-up), to the next two after 0.3-1.1 s; the fourth runs
# to the end.
cat > "$W/fake/sbatch" <<'SH'
#!/bin/bash
echo "sbatch $*" >> "$FAKE_LOG"
n=1; args=()
for a in "$@"; do
  case $a in --ntasks=*) n=${a#--ntasks=} ;; --*) ;; *) args+=("$a") ;; esac
done
SLURM_NTASKS=$n SLURM_JOB_ID=$RANDOM bash "${args[@]}" &
job=$!
n_job=${UDAR_JOB_NUMBER:-1}
if [ "${FAKE_SIGNALS:-0}" = 1 ] && [ "$n_job" -le 3 ]; then
  delay=0.02; [ "$n_job" -gt 1 ] && delay=$(awk -v r=$RANDOM 'BEGIN { printf "%.2f", 0.3 + 0.8*r/32767 }')
  sleep "$delay"; kill -USR1 $job 2>/dev/null && echo "USR1 after $delay s" >> "$FAKE_LOG.signals"
fi
wait $job; rc=$?
while kill -0 $job 2>/dev/null; do wait $job; rc=$?; done
exit $rc
SH
printf '#!/bin/bash\necho "   Command=%s/input/batch/udar.slurm"\n' "$ROOT" > "$W/fake/scontrol"
printf '#!/bin/bash\necho 1:00:00\n' > "$W/fake/squeue"
chmod +x "$W/fake/"*
cp "$ROOT/tests/regression/$case/$case.msh" "$ROOT/tests/regression/$case/$case.nml" "$W/run/"
sed -i 's/^\( *\)t_end = .*/\1t_end = 30.0e-6/' "$W/run/$case.nml"
# the straight run, for reference
(cd "$W/run" && timeout 600 "$EXE" $case.nml > straight.log 2>&1) || { cat "$W/run/straight.log"; bad "straight run"; exit 1; }
mv "$W/run/out" "$W/straight"
export PATH=$W/fake:$PATH FAKE_LOG=$W/sbatch.log UDAR=$EXE MPIRUN="timeout 600 mpirun" UDAR_ARGS="--wall-limit 1.5"
(cd "$W" && SLURM_SUBMIT_DIR=$W SLURM_NTASKS=2 SLURM_JOB_ID=1 bash "$ROOT/input/batch/udar.slurm" run/$case.nml > job.log 2>&1)
rc=$?
grep '^udar' "$W/job.log"
jobs=$(grep -c '^udar job [0-9]* of' "$W/job.log")
echo "MEASURED $jobs jobs; resubmissions: $(wc -l < "$W/sbatch.log" 2>/dev/null || echo 0)"
if [ $rc = 0 ] && grep -q 'run complete' "$W/job.log" && [ "$jobs" -ge 2 ]; then ok "chain_completes_over_${jobs}_jobs"
else tail -20 "$W/job.log"; bad "chain_completes (exit $rc, $jobs jobs)"; fi
grep -q -- '--ntasks=2 --time=1:00:00' "$W/sbatch.log" && ok "resubmission_keeps_tasks_and_time" || bad "resubmission_keeps_tasks_and_time"
if cmp -s "$W/straight/${case}_history.csv" "$W/run/out/${case}_history.csv" && \
   h5diff --exclude-path /provenance "$W/straight/$case.h5" "$W/run/out/$case.h5"; then ok "chain_bitwise_equals_straight_run"
else bad "chain_bitwise_equals_straight_run"; fi

# The signal path for real: the batch system's SIGUSR1 reaches the job
# script at random moments (the first job's while it is still starting:
# before its trap, the script used to die silently), the script passes it
# to udar through mpirun, udar checkpoints, the job resubmits itself, and
# the chain ends bitwise equal to the straight run.
rm -rf "$W/run/out"; : > "$W/sbatch.log"
export MPIRUN=mpirun UDAR_ARGS= FAKE_SIGNALS=1   # timeout(1) would take the signal meant for mpirun
( sleep 300; pkill -9 -f "$EXE run/$case.nml"; pkill -9 -f "$EXE --restart auto" ) > /dev/null 2>&1 &
watchdog=$!
(cd "$W" && SLURM_SUBMIT_DIR=$W SLURM_NTASKS=2 SLURM_JOB_ID=1 "$W/fake/sbatch" --ntasks=2 "$ROOT/input/batch/udar.slurm" run/$case.nml > signal_job.log 2>&1)
rc=$?
kill $watchdog 2>/dev/null
jobs=$(grep -c '^udar job [0-9]* of' "$W/signal_job.log")
asked=$(grep -c 'asking udar to checkpoint' "$W/signal_job.log")
echo "MEASURED signal chain: $jobs jobs, $asked signals acted on; $(tr '\n' ';' < "$W/sbatch.log.signals")"
if [ $rc = 0 ] && grep -q 'run complete' "$W/signal_job.log" && [ "$jobs" -ge 2 ] && [ "$asked" -ge 1 ] && \
   grep -q "udar job 1: exit code 0, status 'checkpointed'" "$W/signal_job.log"; then ok "signal_chain_completes_over_${jobs}_jobs"
else tail -20 "$W/signal_job.log"; bad "signal_chain (exit $rc, $jobs jobs)"; fi
if cmp -s "$W/straight/${case}_history.csv" "$W/run/out/${case}_history.csv" && \
   h5diff --exclude-path /provenance "$W/straight/$case.h5" "$W/run/out/$case.h5"; then ok "signal_chain_bitwise_equals_straight_run"
else bad "signal_chain_bitwise_equals_straight_run"; fi
[ $fails -eq 0 ]
