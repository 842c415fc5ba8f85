#!/usr/bin/env bash
# A long run is never lost: a run killed hard (kill -9: what a node failure,
# the out-of-memory killer or a batch system's last word look like) at
# random moments and resumed each time with --restart auto ends with a
# history and fields bitwise equal to the straight run.
#   hard_kill.sh EXE [TRIALS]
source "$(dirname "$0")/common.sh" "$1"
trials=${2:-8}
case=taylor_ofhc_baseline
src=$ROOT/tests/regression/$case
mkdir -p "$W/run"
cp "$src/$case.msh" "$src/$case.nml" "$W/run/"
# 10 us, a history row every 0.1 us, fields every 1 us, a checkpoint every 0.5 us
sed -i 's/^\( *\)t_end = .*/\1t_end = 10.0e-6/; s/^\( *\)dt_field = .*/\1dt_field = 1.0e-6, dt_checkpoint = 0.5e-6/; s/^\( *\)dt_history = .*/\1dt_history = 0.1e-6/' \
  "$W/run/$case.nml"
grep -q 'dt_checkpoint = 0.5e-6' "$W/run/$case.nml" && grep -q 'dt_history = 0.1e-6' "$W/run/$case.nml" \
  || { bad "deck edit"; exit 1; }
t0=$(date +%s.%N)
(cd "$W/run" && timeout 300 "$EXE" $case.nml > straight.log 2>&1) || { cat "$W/run/straight.log"; bad "straight run"; exit 1; }
t1=$(date +%s.%N)
mv "$W/run/out" "$W/straight"
span=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%d", (b - a)*1000 }')   # ms the straight run took
echo "MEASURED straight run: $span ms, $(($(wc -l < "$W/straight/${case}_history.csv") - 1)) history rows"
equal=0
for k in $(seq 1 "$trials"); do
  rm -rf "$W/run/out"
  kills=0
  # kill the run (and each resumed run) at a random moment until one completes
  for attempt in 1 2 3 4 5 6 7 8; do
    (cd "$W/run" && exec "$EXE" --restart auto $case.nml >> trial.log 2>&1) &
    pid=$!
    if [ $attempt -le 3 ]; then
      ms=$(( (RANDOM % (span > 50 ? span : 50)) + 20 ))
      sleep "$(awk -v m="$ms" 'BEGIN { printf "%.3f", m/1000 }')"
      kill -9 $pid 2>/dev/null && kills=$((kills + 1))
    fi
    wait $pid 2>/dev/null
    [ "$(sed -n 's/^status = //p' "$W/run/out/$case.status" 2>/dev/null)" = complete ] && break
  done
  if cmp -s "$W/straight/${case}_history.csv" "$W/run/out/${case}_history.csv" && \
     h5diff --exclude-path /provenance "$W/straight/$case.h5" "$W/run/out/$case.h5" > "$W/diff.txt" 2>&1; then
    equal=$((equal + 1)); ok "trial_${k}_bitwise_after_${kills}_kills"
  else
    bad "trial_${k} after ${kills} kills: outputs differ from the straight run"
    diff <(cut -d, -f1-2 "$W/straight/${case}_history.csv") <(cut -d, -f1-2 "$W/run/out/${case}_history.csv") | head -5
    head -5 "$W/diff.txt"; tail -5 "$W/run/trial.log"
  fi
done
echo "MEASURED hard kills: $equal of $trials trials bitwise equal to the straight run"
# a history that lost rows before the checkpoint (cut by hand here: what an
# older udar left after a hard kill) is continued, and the restart says so
rm -rf "$W/run/out"; cp -r "$W/straight" "$W/run/out"
ck=$(for f in "$W/run/out/${case}"_ckpt*.h5; do echo "$(h5dump -a /cycle "$f" | sed -n 's/.*(0): \([0-9]*\).*/\1/p') $f"; done | sort -n | head -1 | cut -d' ' -f2)
# 19 data rows kept, after the header and the comment line before it (the
# quarter model's symmetry planes)
notes=$(grep -c '^#' "$W/straight/${case}_history.csv" || true)
head -n $((20 + notes)) "$W/straight/${case}_history.csv" > "$W/run/out/${case}_history.csv"
(cd "$W/run" && "$EXE" --restart "$ck" $case.nml > cut.log 2>&1); rc=$?
if [ $rc = 0 ] && grep -q "warning: restart: the history .* holds 19 rows up to the checkpoint, which was written after row [0-9]*: [0-9]* rows were lost" "$W/run/cut.log"; then
  ok "missing_history_rows_reported"
else bad "missing history rows not reported (exit $rc)"; grep -i 'history\|restart' "$W/run/cut.log"; fi
[ $fails -eq 0 ]
