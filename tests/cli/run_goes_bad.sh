#!/usr/bin/env bash
# A run that goes bad (a time step far above the stable one) must stop with
# exit code 2, name the element, cycle and time, and leave its last state in
# the field file (a committed step at the failing cycle).
source "$(dirname "$0")/common.sh" "$1"
cp "$ROOT/tests/regression/elastic_bar/elastic_bar.msh" "$W/bar.msh"
cat > "$W/bad.nml" <<'DECK'
&run t_end = 1e-4, dt_initial = 2e-6 /
&mesh file = 'bar.msh' /
&material name = 'steel', rho0 = 7850, youngs_modulus = 200e9, poisson_ratio = 0.3 /
&part group = 'bar', material = 'steel', velocity = 0, 0, -100 /
&boundary kind = 'rigid_wall', point = 0, 0, 0, normal = 0, 0, 1 /
&output directory = 'out' /
DECK
(cd "$W" && "$EXE" bad.nml) > "$W/out.txt" 2> "$W/err.txt"; rc=$?
fails=0
if [ $rc -eq 2 ]; then echo "PASS exit_code_2"; else echo "FAIL exit code $rc (expected 2)"; fails=1; fi
if grep -qE 'at cycle 1, time .* element [0-9]+' "$W/err.txt"; then echo "PASS message names cycle, time and element"
else echo "FAIL message:"; cat "$W/err.txt"; fails=1; fi
if $PYTHON - "$W/out/bad.h5" <<'PY'
import sys, h5py
f = h5py.File(sys.argv[1], 'r')
n = int(f['steps'].attrs['count'])
last = f['steps/%06d' % (n - 1)]
sys.exit(0 if n == 2 and int(last.attrs['cycle']) == 1 and 'pressure' in last else 1)
PY
then echo "PASS last state written (step at cycle 1)"; else echo "FAIL no last state in out/bad.h5"; fails=1; fi
# a far larger step inverts elements in the first cycle: named with its part
sed 's/dt_initial = 2e-6/dt_initial = 5e-5/' "$W/bad.nml" > "$W/inv.nml"
(cd "$W" && "$EXE" inv.nml) > "$W/out.txt" 2> "$W/err.txt"; rc=$?
if [ $rc -eq 2 ] && grep -qE "element [0-9]+ \(part 'bar'\) inverted .* at cycle 1, time" "$W/err.txt"
then echo "PASS inverted element named (exit 2)"; else echo "FAIL inverted element: exit $rc"; cat "$W/err.txt"; fails=1; fi
# energy from nothing in a deck at rest (a rod node starts inside the plate;
# putting it out strains the elements): the balance is lost, and the error
# is a readable fraction of the largest energy seen (1: all of it came from
# nothing), not a division by the zero initial energy (0.5.3: 4e+303)
cp "$ROOT/tests/regression/deep_node/deep_node.msh" "$W/"
sed -e 's/velocity = 100.0, 0.0, 0.0/velocity = 0.0, 0.0, 0.0/g' -e "s/directory = 'out'/directory = 'rest'/" \
  "$ROOT/tests/regression/deep_node/deep_node.nml" > "$W/rest.nml"
(cd "$W" && "$EXE" rest.nml) > "$W/out.txt" 2> "$W/err.txt"; rc=$?
if [ $rc -eq 2 ] && grep -qE 'energy balance lost \(error +(1\.000E\+0?00|9\.[0-9]+E-0?01)\)' "$W/err.txt"
then echo "PASS energy from nothing at rest: $(grep -oE 'error +[^)]*' "$W/err.txt")"
else echo "FAIL energy from nothing at rest: exit $rc"; cat "$W/err.txt"; fails=1; fi
[ $fails -eq 0 ]
