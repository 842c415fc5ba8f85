#!/usr/bin/env bash
# A corpus of malformed decks and meshes (tests/tools/malformed_corpus.py):
# every case must end with exit 1 (input) or 3 (I/O) and a message that names
# the file and, for a deck mistake, the deck line; no crash (exit >= 128,
# a backtrace), no hang (each case under `timeout 20`), nothing written
# anywhere (the scratch tree is compared before and after each case), none
# slow (over 5 s; the 1 MB string over 2 s).
# Usage: malformed_corpus.sh <udar binary>
source "$(dirname "$0")/common.sh" "$1"
R=$W/a/run                     # cases run here; '../../x' from its out/ lands in $W/a; all of $W is watched
mkdir -p "$R"
"$PYTHON" "$ROOT/tests/tools/malformed_corpus.py" "$R" || { echo "FAIL generator"; exit 1; }
mkdir -p "$W/log"               # the test's own files: not in the snapshot
snapshot() { (cd "$W" && find . -path ./log -prune -o -printf '%p %y %s %T@\n' | sort); }

# the base deck and meshes are valid: the corpus tests what it means to
(cd "$R" && "$EXE" --check ok.nml > /dev/null 2>&1) && ok "base deck valid" || bad "base deck is not valid"
sed "s/ok22.msh/ok41.msh/" "$R/ok.nml" > "$R/ok41.nml"
(cd "$R" && "$EXE" --check ok41.nml > /dev/null 2>&1) && ok "base mesh 4.1 valid" || bad "base mesh 4.1 is not valid"
rm -f "$R/ok41.nml"

n_deck=0; n_mesh=0; n_bad=0
while IFS=$'\t' read -r kind arg pat; do
  name=${arg##*/}
  before=$(snapshot)
  t0=$(date +%s%N)
  (cd "$R" && timeout 20 "$EXE" "$arg") > "$W/log/out.txt" 2> "$W/log/err.txt"; rc=$?
  ms=$(( ($(date +%s%N) - t0) / 1000000 ))
  after=$(snapshot)
  why=''
  if [ $rc -eq 124 ]; then why="hangs (killed after 20 s)"
  elif [ $rc -ge 128 ]; then why="crashes (exit $rc)"
  elif [ $rc -ne 1 ] && [ $rc -ne 3 ]; then why="exit $rc, not 1 or 3"
  elif grep -qE 'Backtrace|Segmentation|Error termination|At line [0-9]+ of file' "$W/log/err.txt"; then why="crash text in the output"
  elif ! grep -qE -- "$pat" "$W/log/err.txt"; then why="no message matching: $pat"
  elif [ "$before" != "$after" ]; then why="wrote files: $(diff <(echo "$before") <(echo "$after") | grep '^>' | head -3 | tr '\n' ' ')"
  elif [ "$name" = d_long_string.nml ] && [ $ms -gt 2000 ]; then why="1 MB string took $ms ms"
  elif [ $ms -gt 5000 ]; then why="took $ms ms (a clear error comes at once)"
  fi
  if [ "$kind" = deck ]; then n_deck=$((n_deck+1)); else n_mesh=$((n_mesh+1)); fi
  if [ -z "$why" ]; then ok "$kind $name (exit $rc, $ms ms)"
  else
    bad "$kind $name: $why"; n_bad=$((n_bad+1))
    cut -c1-300 "$W/log/err.txt" | head -5 | sed 's/^/      /'
  fi
done < "$R/cases.tsv"
if [ $n_bad -eq 0 ]; then
  echo "MEASURED corpus: $n_deck decks, $n_mesh meshes, all clear errors"
else
  echo "MEASURED corpus: $n_deck decks, $n_mesh meshes, $n_bad without a clear error"
fi
[ $fails -eq 0 ]
