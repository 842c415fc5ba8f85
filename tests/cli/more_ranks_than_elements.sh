#!/usr/bin/env bash
# More ranks than elements: ranks with nothing to own still take part in the
# collective steps; the run ends normally and matches the one-rank run.
#   more_ranks_than_elements.sh EXE
source "$(dirname "$0")/common.sh" "$1"
cp "$ROOT/tests/unit/meshes/two_tets_v41.msh" "$W/"
cat > "$W/two.nml" <<'NML'
! two aluminium tetrahedra, the second one moving: a stress wave between them
&run t_end = 2.0e-3, dt_safety = 0.4 /   ! a lone tetrahedron needs less than 0.5 (doc/theory.md)
&mesh file = 'two_tets_v41.msh' /
&material name = 'al', rho0 = 2700, eos = 'linear', bulk_modulus = 70e9, strength = 'elastic', shear_modulus = 26e9 /
&part group = 'block', material = 'al', velocity = 0.1, 0.0, -0.2 /
&boundary kind = 'fixed', surface = 'bottom' /
&output directory = 'out', dt_field = 1.0e-3 /
NML
for n in 1 5; do
  (cd "$W" && timeout 900 mpirun -np $n "$EXE" two.nml > np$n.log 2>&1) || { cat "$W/np$n.log"; bad "run_on_${n}_ranks"; exit 1; }
  mv "$W/out" "$W/np$n"
done
grep -q 'some ranks own no element' "$W/np5.log" && ok "empty_ranks_reported" || bad "empty_ranks_reported"
cmp -s "$W/np1/two_history.csv" "$W/np5/two_history.csv" && ok "history_1_vs_5_ranks_bitwise" || bad "history_1_vs_5_ranks_bitwise"
h5diff --exclude-path /provenance "$W/np1/two.h5" "$W/np5/two.h5" && ok "fields_1_vs_5_ranks_bitwise" || bad "fields_1_vs_5_ranks_bitwise"
[ $fails -eq 0 ]
