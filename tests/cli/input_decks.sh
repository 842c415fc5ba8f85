#!/usr/bin/env bash
# Every deck shipped in input/ reads: `udar --check` accepts it with its
# mesh (exit 0), so a deck an analyst copies is a valid starting point; and
# every material of the library (input/materials) reads, included in a deck.
#   input_decks.sh EXE
source "$(dirname "$0")/common.sh" "$1"
n=0
for deck in "$ROOT"/input/*/*.nml; do
  case $deck in "$ROOT"/input/materials/*) continue ;; esac
  n=$((n+1))
  name=${deck#$ROOT/}
  if (cd "$(dirname "$deck")" && "$EXE" --check "$(basename "$deck")" > "$W/check.log" 2>&1); then
    ok "$name"
  else
    tail -5 "$W/check.log"; bad "$name"
  fi
done
m=0
for lib in "$ROOT"/input/materials/*.nml; do
  m=$((m+1))
  name=$(sed -n "s/^ *name = '\([^']*\)'.*/\1/p" "$lib")
  printf "&run t_end = 1e-6 /\n&mesh file = '%s', scale = 0.001, geometry = 'axisymmetric' /\ninclude '%s'\n" \
         "$ROOT/input/taylor_ofhc_2d/taylor_ofhc_2d.msh" "$lib" > "$W/library.nml"
  printf "&part group = 'rod', material = '%s' /\n" "$name" >> "$W/library.nml"
  if [ -n "$name" ] && "$EXE" --check "$W/library.nml" > "$W/check.log" 2>&1; then
    ok "${lib#$ROOT/} ($name)"
  else
    tail -5 "$W/check.log"; bad "${lib#$ROOT/}"
  fi
done
echo "MEASURED $n decks and $m library materials checked"
[ $fails -eq 0 ]
