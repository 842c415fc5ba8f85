#!/usr/bin/env bash
# The Slurm job script under a real Slurm (Debian's slurm-wlm 22.05, a
# private one-node cluster started here: its own munge key, ports and
# state folder). The batch system's SIGUSR1 reaches the job script through
# `scancel --signal=USR1 --batch` at the worst moments: the first job in
# the first fraction of a second of its life (before the script's trap in
# 0.4.0: the job died silently, JobState FAILED), the second mid-run. Each
# job checkpoints, exits 0 (JobState COMPLETED) and resubmits itself with
# the real sbatch; the third job, left alone, completes the run, bitwise
# equal to a straight run.
# Skipped (with the reason) when Slurm is not installed or cannot start.
#   slurm_real.sh EXE
source "$(dirname "$0")/common.sh" "$1"
for c in munged slurmctld slurmd sbatch scancel squeue scontrol; do
  command -v $c > /dev/null || { echo "SKIP: $c not installed (make deps installs slurm-wlm and munge)"; exit 0; }
done
S=$W/slurm
mkdir -p "$S"/{state,spool,log,munge}
chmod 700 "$S/munge"
head -c 1024 /dev/urandom > "$S/munge/munge.key"; chmod 400 "$S/munge/munge.key"
host=$(hostname)
port=$((20000 + RANDOM % 20000))
cat > "$S/slurm.conf" <<CONF
ClusterName=udartest
SlurmctldHost=$host
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$S/munge/munge.socket
SlurmUser=$(id -un)
SlurmdUser=$(id -un)
StateSaveLocation=$S/state
SlurmdSpoolDir=$S/spool
SlurmctldPidFile=$S/slurmctld.pid
SlurmdPidFile=$S/slurmd.pid
SlurmctldLogFile=$S/log/slurmctld.log
SlurmdLogFile=$S/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SwitchType=switch/none
MpiDefault=none
ReturnToService=2
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
KillWait=5
MinJobAge=600
NodeName=$host CPUs=$(nproc) RealMemory=1000 State=UNKNOWN
PartitionName=udar Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$S/slurm.conf
stop_slurm() {
  scancel --full --quiet -u "$(id -un)" 2>/dev/null
  for f in slurmd slurmctld munge/munged; do [ -f "$S/$f.pid" ] && kill "$(cat "$S/$f.pid")" 2>/dev/null; done
  sleep 1; rm -rf "$W"
}
trap stop_slurm EXIT
munged --key-file="$S/munge/munge.key" --socket="$S/munge/munge.socket" --pid-file="$S/munge/munged.pid" \
  --log-file="$S/munge/munged.log" --seed-file="$S/munge/seed" -f 2> "$S/log/munged.err" || { echo "SKIP: munged cannot start"; cat "$S/log/munged.err"; exit 0; }
slurmctld -f "$S/slurm.conf" && slurmd -f "$S/slurm.conf" || { echo "SKIP: slurmctld/slurmd cannot start"; exit 0; }
for i in $(seq 1 60); do sinfo -h -o %t 2>/dev/null | grep -q idle && break; sleep 0.5; done
sinfo -h -o %t | grep -q idle || { echo "SKIP: the one-node Slurm did not come up"; tail -5 "$S/log/"*.log; exit 0; }
echo "MEASURED one-node Slurm $(sinfo -V) up on port $port"

case=taylor_ofhc_baseline
mkdir -p "$W/run"
cp "$ROOT/tests/regression/$case/$case.msh" "$ROOT/tests/regression/$case/$case.nml" "$W/run/"
sed -i 's/^\( *\)t_end = .*/\1t_end = 30.0e-6/' "$W/run/$case.nml"
(cd "$W/run" && timeout 300 "$EXE" $case.nml > straight.log 2>&1) || { cat "$W/run/straight.log"; bad "straight run"; exit 1; }
mv "$W/run/out" "$W/straight"
export UDAR=$EXE MPIRUN=mpirun UDAR_ARGS= UDAR_MAX_JOBS=12
cd "$W"
first=$(sbatch --parsable --ntasks=2 --time=10 "$ROOT/input/batch/udar.slurm" run/$case.nml) || { bad "sbatch"; exit 1; }
# every job of the chain: a real SIGUSR1 to its batch shell, the first at once
declare -A signalled
deadline=$((SECONDS + 240))
done_chain=0
while [ $SECONDS -lt $deadline ]; do
  for j in $(squeue -h -t RUNNING -o %i 2>/dev/null); do
    [ -n "${signalled[$j]:-}" ] && continue
    if [ "$j" = "$first" ]; then
      # as soon as the job's log exists: the script is starting (udar --check)
      [ -e "$W/udar-$j.log" ] || continue
      [ -s "$W/udar-$j.log" ] && echo "note: job $j had printed before its signal"
      scancel --signal=USR1 --batch "$j" && signalled[$j]=early
    elif [ ${#signalled[@]} -lt 2 ] && grep -q '^start:' "$W/udar-$j.log" 2>/dev/null; then
      sleep 0.3; scancel --signal=USR1 --batch "$j" && signalled[$j]=mid    # the second job, mid-run
    fi
  done
  grep -q 'run complete after' "$W"/udar-*.log 2>/dev/null && { done_chain=1; break; }
  grep -q 'not resubmitting\|resubmit by hand' "$W"/udar-*.log 2>/dev/null && break
  sleep 0.01
done
sleep 1
states=$(for j in $(seq "$first" $((first + 20))); do scontrol show job "$j" 2>/dev/null | sed -n 's/^ *JobState=\([A-Z_]*\).*/\1/p'; done | sort | uniq -c | tr '\n' ' ')
njobs=$(ls "$W"/udar-*.log | wc -l)
echo "MEASURED real Slurm chain: $njobs jobs, signals: ${signalled[*]}, job states: $states"
grep -h '^udar job [0-9]*: \(exit code\|time nearly\)' "$W"/udar-*.log
if [ $done_chain = 1 ] && [ "${signalled[$first]:-}" = early ] && \
   grep -q "udar job 1: exit code 0, status 'checkpointed'" "$W/udar-$first.log" && ! grep -qE 'FAILED|CANCELLED|TIMEOUT' <<< "$states"; then
  ok "real_slurm_chain_completes (${njobs} jobs, the first signalled at once)"
else
  bad "real Slurm chain (complete: $done_chain)"; tail -n 12 "$W"/udar-*.log; tail -5 "$S/log/slurmctld.log"
fi
if cmp -s "$W/straight/${case}_history.csv" "$W/run/out/${case}_history.csv" && \
   h5diff --exclude-path /provenance "$W/straight/$case.h5" "$W/run/out/$case.h5" > /dev/null; then ok "real_slurm_chain_bitwise_equals_straight_run"
else bad "real_slurm_chain_bitwise_equals_straight_run"; fi
cd /; [ $fails -eq 0 ]
