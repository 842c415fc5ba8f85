#!/usr/bin/env bash
# Every deck shipped in input/ reads: `udar --check` accepts it with its
# mesh (exit 0), so a deck an analyst copies is a valid starting point.
#   input_decks.sh EXE
source "$(dirname "$0")/common.sh" "$1"
n=0
for deck in "$ROOT"/input/*/*.nml; do
  n=$((n+1))
  name=${deck#$ROOT/}
  if (cd "$(dirname "$deck")" && "$EXE" --check "$(basename "$deck")" > "$W/check.log" 2>&1); then
    ok "$name"
  else
    tail -5 "$W/check.log"; bad "$name"
  fi
done
echo "MEASURED $n decks checked"
[ $fails -eq 0 ]
