#!/usr/bin/env bash
# Rank-count independence: a regression deck run on 1, 2, 3 and 4 MPI ranks
# gives bitwise identical history files (cmp) and field files (h5diff,
# /provenance excluded, which holds the rank count).
#   rank_invariance.sh EXE CASE [T_END] [TET_FORMULATION] [DECK]
# CASE is a folder of tests/regression; T_END, if given (and not '-'), shortens
# the run; TET_FORMULATION, if given (and not '-'), replaces the deck's
# &numerics with tet_formulation = TET_FORMULATION; DECK names one of the
# case's decks (default: CASE.nml).
source "$(dirname "$0")/common.sh" "$1"
case=$2
t_end=${3:-}
[ "$t_end" = - ] && t_end=
tet=${4:-}
[ "$tet" = - ] && tet=
deck=${5:-$case}
# the same deck in the same folder (the resolved deck, stored in the field
# file, names the mesh by its absolute path); each run's output moved aside
mkdir -p "$W/run"
cp "$ROOT/tests/regression/$case/"*.msh "$W/run/"     # (a deck of the case may take another of its meshes)
cp "$ROOT/tests/regression/$case/$deck.nml" "$W/run/$case.nml"
[ -n "$t_end" ] && sed -i "s/^\( *\)t_end = .*/\1t_end = $t_end/" "$W/run/$case.nml"
if [ -n "$tet" ]; then
  sed -i '/^&numerics/d' "$W/run/$case.nml"
  echo "&numerics tet_formulation = '$tet' /" >> "$W/run/$case.nml"
fi
for n in 1 2 3 4; do
  if ! (cd "$W/run" && timeout 900 mpirun -np $n "$EXE" $case.nml > run.log 2>&1); then
    cat "$W/run/run.log"; bad "run on $n ranks"; exit 1
  fi
  grep -E 'partition over|^ +[0-9]+ +[0-9]+ +[0-9]+ +[0-9]+ +[0-9]+$' "$W/run/run.log"
  mkdir -p "$W/np$n" && mv "$W/run/out" "$W/np$n/out"
done
rows=$(wc -l < "$W/np1/out/${case}_history.csv")
steps=$(h5dump -a /steps/count "$W/np1/out/$case.h5" | sed -n 's/.*(0): \([0-9]*\).*/\1/p')
echo "MEASURED $case: $rows history lines, $steps field steps per run"
for n in 2 3 4; do
  if cmp -s "$W/np1/out/${case}_history.csv" "$W/np$n/out/${case}_history.csv"; then
    ok "${case}_history_1_vs_${n}_ranks_bitwise"
  else
    bad "${case}_history_1_vs_${n}_ranks_bitwise"; diff "$W/np1/out/${case}_history.csv" "$W/np$n/out/${case}_history.csv" | head -6
  fi
  if h5diff --exclude-path /provenance "$W/np1/out/$case.h5" "$W/np$n/out/$case.h5" > "$W/h5diff$n.txt" 2>&1; then
    ok "${case}_fields_1_vs_${n}_ranks_bitwise"
  else
    bad "${case}_fields_1_vs_${n}_ranks_bitwise"; head -20 "$W/h5diff$n.txt"
  fi
done
# the comparison can fail: the rank count itself differs in /provenance
if h5diff "$W/np1/out/$case.h5" "$W/np2/out/$case.h5" > /dev/null 2>&1; then bad "h5diff_sees_provenance"
else ok "h5diff_sees_provenance"; fi
[ $fails -eq 0 ]
