#!/usr/bin/env bash
# A run tells when its time step collapses, and can end when the event is
# over:
#  - a Taylor bar driven at 400 m/s ('nodal' element): a warning when the stable step falls
#    below dt_warn_ratio of the first one, then one per further factor of 10,
#    naming the element, its part and volume ratios; none with dt_warn_ratio = 0;
#  - the 190 m/s bar with end_kinetic_fraction = 0.05: the run ends at the first
#    balance cycle whose kinetic energy is below 5 % of its peak, with status
#    complete, a last field step and history row there; a restart from a
#    checkpoint before it ends at the same cycle, bitwise.
#   run_control.sh EXE
source "$(dirname "$0")/common.sh" "$1"
case=taylor_ofhc_baseline
src=$ROOT/tests/regression/$case
cp "$src/$case.msh" "$W/"
sed 's/velocity = 0.0, 0.0, -190.0/velocity = 0.0, 0.0, -400.0/; s/^\( *\)t_end = .*/\1t_end = 15.0e-6/; s/^&run/\&run dt_warn_ratio = 0.9,/' \
  "$src/$case.nml" > "$W/fast.nml"
# the nodal-averaged element of 0.4, whose spurious mode crushes single elements
echo "&numerics tet_formulation = 'nodal' /" >> "$W/fast.nml"
grep -q -- '-400.0' "$W/fast.nml" && grep -q 'dt_warn_ratio = 0.9' "$W/fast.nml" || { bad "deck edit"; exit 1; }
(cd "$W" && "$EXE" fast.nml > fast.log 2>&1) || { cat "$W/fast.log"; bad "fast run"; }
grep 'time-step collapse' "$W/fast.log" | head -3
n=$(grep -c 'warning: time-step collapse' "$W/fast.log")
if [ "$n" = 2 ] && grep -q "8.99E-01 of the first.*set by element [0-9]* (part 'rod') at volume ratio 0\.[0-9]*, its nodes' averaged volume ratios" "$W/fast.log" \
   && grep -q 'next warning at 9.0E-03 of the first step' "$W/fast.log" && grep -q 'When the time step collapses' "$W/fast.log"; then
  ok "step_collapse_warned_twice (0.9 and 0.09 of the first step)"
else bad "step_collapse_warned ($n warnings)"; fi
sed -i 's/dt_warn_ratio = 0.9/dt_warn_ratio = 0.0/' "$W/fast.nml"
(cd "$W" && "$EXE" fast.nml > quiet.log 2>&1)
grep -q 'time-step collapse' "$W/quiet.log" && bad "dt_warn_ratio = 0 still warns" || ok "no_warning_with_ratio_0"
grep -q 'When the time step collapses' "$ROOT/doc/user-guide.md" && ok "user_guide_section" || bad "user guide has no section 'When the time step collapses'"

# end of the event
sed 's/^\( *\)t_end = .*/\1t_end = 150.0e-6/; s/^&run/\&run end_kinetic_fraction = 0.05,/; s/^\( *\)dt_field = .*/\1dt_field = 20.0e-6, dt_checkpoint = 20.0e-6/' \
  "$src/$case.nml" > "$W/ke.nml"
(cd "$W" && "$EXE" ke.nml > ke.log 2>&1) || { cat "$W/ke.log"; bad "end-criterion run"; }
grep 'event is over' "$W/ke.log"
$PYTHON - "$W/out" <<'PY' && ok "ended_when_kinetic_energy_below_5_percent_of_peak" || bad "end criterion"
import sys, csv, h5py
out = sys.argv[1]
# the header's names less their units ('kinetic [J]'), after the comment line
rows = [{k.split(' [')[0]: v for k, v in r.items()}
        for r in csv.DictReader(l for l in open(f'{out}/ke_history.csv') if not l.startswith('#'))]
ke = [float(r['kinetic']) for r in rows]
cyc = [int(r['cycle']) for r in rows]
t = float(rows[-1]['time'])
status = open(f'{out}/ke.status').read()
steps = h5py.File(f'{out}/ke.h5')['steps']
last = steps[sorted(steps)[-1]].attrs
print(f'MEASURED ended at cycle {cyc[-1]}, t = {t:.4e} s, kinetic {ke[-1]:.4g} J of peak {max(ke):.4g} J '
      f'({100*ke[-1]/max(ke):.2f} %); last field step at cycle {last["cycle"]}')
assert 'status = complete' in status and 'end_kinetic_fraction' in status, status
assert t < 150e-6 and cyc[-1] % 10 == 0
assert ke[-1] < 0.05*max(ke)
# no earlier history row was below the threshold at a balance cycle (rows every dt_history)
assert all(k >= 0.05*max(ke) for k, c in zip(ke[:-1], cyc[:-1]) if c % 10 == 0), 'should have ended earlier'
assert last['cycle'] == cyc[-1] and abs(last['time'] - t) == 0.0
PY
mv "$W/out" "$W/ke_straight"
# restart from the checkpoint before the end (the end wrote the other slot)
c1=$(h5dump -a /cycle "$W/ke_straight/ke_ckpt1.h5" | sed -n 's/.*(0): \([0-9]*\).*/\1/p')
c2=$(h5dump -a /cycle "$W/ke_straight/ke_ckpt2.h5" | sed -n 's/.*(0): \([0-9]*\).*/\1/p')
if [ "$c1" -lt "$c2" ]; then early=ke_ckpt1.h5; last=ke_ckpt2.h5; first=$c1; else early=ke_ckpt2.h5; last=ke_ckpt1.h5; first=$c2; fi
cp -r "$W/ke_straight" "$W/out"
(cd "$W" && "$EXE" --restart out/$early ke.nml > restart.log 2>&1) || { cat "$W/restart.log"; bad "restart"; }
if cmp -s "$W/ke_straight/ke_history.csv" "$W/out/ke_history.csv" && \
   h5diff --exclude-path /provenance "$W/ke_straight/ke.h5" "$W/out/ke.h5" > /dev/null; then
  ok "restart_from_cycle_${first}_ends_at_the_same_cycle_bitwise"
else bad "restart with the end criterion differs"; tail -3 "$W/restart.log"; fi
before=$(md5sum "$W/out/ke.h5" "$W/out/ke_history.csv")
(cd "$W" && "$EXE" --restart out/$last ke.nml > again.log 2>&1); rc=$?
if [ $rc = 0 ] && grep -q 'end of the event.*nothing to do' "$W/again.log" && [ "$before" = "$(md5sum "$W/out/ke.h5" "$W/out/ke_history.csv")" ]; then
  ok "restart_from_the_end_does_nothing"
else bad "restart from the end checkpoint (exit $rc)"; tail -3 "$W/again.log"; fi
[ $fails -eq 0 ]
