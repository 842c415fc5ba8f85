#!/usr/bin/env bash
# The self-contact check can fail: the self_contact deck without its
# &contact group lets the clamp's arms pass into each other, and the same
# check.py (expect_penetration) must see it.
#   self_contact_off.sh EXE
source "$(dirname "$0")/common.sh" "$1"
mkdir -p "$W/run"
cp "$ROOT/tests/regression/self_contact/self_contact.msh" "$W/run/"
grep -v '^&contact' "$ROOT/tests/regression/self_contact/self_contact.nml" > "$W/run/self_contact.nml"
if grep -q '^&contact' "$W/run/self_contact.nml"; then bad "deck_without_contact"; exit 1; fi
(cd "$W/run" && "$EXE" self_contact.nml > run.log 2>&1) || { cat "$W/run/run.log"; bad "run without self-contact"; exit 1; }
$PYTHON "$ROOT/tests/regression/self_contact/check.py" "$W/run" self_contact expect_penetration || fails=$((fails+1))
[ $fails -eq 0 ]
