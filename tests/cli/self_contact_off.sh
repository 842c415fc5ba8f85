#!/usr/bin/env bash
# The self-contact check can fail: the self_contact deck (or CASE's, e.g.
# self_contact_2d, the plane-strain clamp) without its &contact group lets
# the clamp's arms pass into each other, and the same check.py
# (expect_penetration) must see it.
#   self_contact_off.sh EXE [CASE]
source "$(dirname "$0")/common.sh" "$1"
case=${2:-self_contact}
mkdir -p "$W/run"
cp "$ROOT/tests/regression/$case/$case.msh" "$W/run/"
grep -v '^&contact' "$ROOT/tests/regression/$case/$case.nml" > "$W/run/$case.nml"
if grep -q '^&contact' "$W/run/$case.nml"; then bad "deck_without_contact"; exit 1; fi
(cd "$W/run" && "$EXE" $case.nml > run.log 2>&1) || { cat "$W/run/run.log"; bad "run without self-contact"; exit 1; }
$PYTHON "$ROOT/tests/regression/$case/check.py" "$W/run" $case expect_penetration || fails=$((fails+1))
[ $fails -eq 0 ]
