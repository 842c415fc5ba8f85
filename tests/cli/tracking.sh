#!/usr/bin/env bash
# Local tracking of contact candidates gives bitwise the same run as a full
# search every cycle, with fewer full searches.
#   tracking.sh EXE CASE [T_END]
# CASE is a folder of tests/regression with a &contact group.
source "$(dirname "$0")/common.sh" "$1"
case=$2
t_end=${3:-}
for tr in true false; do
  mkdir -p "$W/$tr"
  cp "$ROOT/tests/regression/$case/$case.msh" "$W/$tr/"
  sed "s|^&contact \(.*\) /|\&contact \1, tracking = .$tr. /|" "$ROOT/tests/regression/$case/$case.nml" > "$W/$tr/$case.nml"
  [ -n "$t_end" ] && sed -i "s/^\( *\)t_end = .*/\1t_end = $t_end/" "$W/$tr/$case.nml"
  grep -q "tracking = .$tr." "$W/$tr/$case.nml" || { bad "deck_has_tracking_$tr"; exit 1; }
  if ! (cd "$W/$tr" && timeout 900 "$EXE" $case.nml > run.log 2>&1); then
    cat "$W/$tr/run.log"; bad "run with tracking .$tr."; exit 1
  fi
  grep -E '^contact:|full searches' "$W/$tr/run.log"
done
if cmp -s "$W/true/out/${case}_history.csv" "$W/false/out/${case}_history.csv"; then
  ok "${case}_history_tracking_equals_full_search"
else
  bad "${case}_history_tracking_equals_full_search"
fi
read -r full passes < <(grep -m1 'full searches in' "$W/true/run.log" | sed 's/.*full searches in \([0-9]*\) of \([0-9]*\) passes.*/\1 \2/')
echo "MEASURED $case: full searches in $full of $passes passes with tracking"
if [ "$full" -lt "$passes" ]; then ok "${case}_tracking_skips_searches"; else bad "${case}_tracking_skips_searches"; fi
[ $fails -eq 0 ]
