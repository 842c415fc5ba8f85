#!/usr/bin/env bash
# A damaged checkpoint (bytes changed in the middle: one mantissa or
# exponent byte of a number, an attribute, random bytes) is refused with
# exit 3 and nothing overwritten, never accepted with other results. Random
# bytes may also land where nothing is read (free space): then the restart
# must end bitwise equal to the straight run.
#   damaged_checkpoint.sh EXE
source "$(dirname "$0")/common.sh" "$1"
case=taylor_ofhc_baseline
src=$ROOT/tests/regression/$case
mkdir -p "$W/run"
cp "$src/$case.msh" "$src/$case.nml" "$W/run/"
sed -i 's/^\( *\)t_end = .*/\1t_end = 4.0e-6/; s/^\( *\)dt_field = .*/\1dt_field = 1.0e-6, dt_checkpoint = 2.0e-6/' "$W/run/$case.nml"
(cd "$W/run" && timeout 300 "$EXE" $case.nml > straight.log 2>&1) || { cat "$W/run/straight.log"; bad "straight run"; exit 1; }
cp -r "$W/run/out" "$W/straight"
good=$W/straight/${case}_ckpt1.h5
# the undamaged checkpoint is accepted (the control)
(cd "$W/run" && timeout 300 "$EXE" --restart "$good" $case.nml > control.log 2>&1) && \
  cmp -s "$W/straight/${case}_history.csv" "$W/run/out/${case}_history.csv" && ok "undamaged_checkpoint_accepted_bitwise" \
  || { cat "$W/run/control.log"; bad "undamaged_checkpoint_accepted_bitwise"; }
refused=0; harmless=0; n=0
try() {   # case name for corrupt_checkpoint.py
  local c=$1 rc before after
  n=$((n + 1))
  rm -rf "$W/run/out"; cp -r "$W/straight" "$W/run/out"
  $PYTHON "$ROOT/tests/tools/corrupt_checkpoint.py" "$good" "$W/run/damaged.h5" "$c" > "$W/what.txt" || { bad "$c: corrupting failed"; return; }
  before=$(cd "$W/run/out" && md5sum *)
  (cd "$W/run" && timeout 120 "$EXE" --restart damaged.h5 $case.nml > "$W/run.log" 2>&1); rc=$?
  after=$(cd "$W/run/out" && md5sum *)
  if [ $rc = 3 ] && [ "$before" = "$after" ] && grep -q 'damaged.h5' "$W/run.log"; then
    refused=$((refused + 1)); ok "$c refused (exit 3, nothing overwritten): $(grep -o 'checkpoint damaged.h5.*' "$W/run.log" | cut -c1-110)"
  elif [ $rc = 0 ] && [[ $c == random:* ]] && cmp -s "$W/straight/${case}_history.csv" "$W/run/out/${case}_history.csv" && \
       h5diff --exclude-path /provenance "$W/straight/$case.h5" "$W/run/out/$case.h5" > /dev/null 2>&1; then
    harmless=$((harmless + 1)); ok "$c landed where nothing is read: results bitwise unchanged"
  else
    bad "$c: exit $rc ($(cat "$W/what.txt"))"; tail -3 "$W/run.log"
  fi
}
for c in velocity_mantissa velocity_low_bit position_exponent force_mantissa vref_mantissa stress_exponent \
         stress_mantissa energy_mantissa plastic_strain_exponent volume_mantissa temperature_mantissa state_flag \
         altitude_mantissa wall_work_limb model_hash_byte checksum_byte time_attribute cycle_attribute \
         stable_step_attribute; do
  try $c
done
for seed in 1 2 3 4 5 6 7 8; do try random:$seed; done
echo "MEASURED damaged checkpoints: $n cases, $refused refused with exit 3, $harmless harmless (bytes never read), $fails wrong"
[ $fails -eq 0 ]
