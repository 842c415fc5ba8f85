#!/usr/bin/env bash
# Collective field output does not depend on the rank count: the test
# program test_field_output_mpi writes the same mesh on 1, 2 and 3 ranks
# (rows scattered over the ranks, one rank without elements on 3 ranks) and
# the files must compare equal with h5diff, /provenance excluded
# (doc/output-format.md); the .xmf indexes must be equal up to the h5 name.
# The comparison itself is checked to be able to fail: h5diff must report
# /provenance when it is not excluded, and a copy with one value changed.
# Usage: field_output_ranks.sh <build/debug/tests/test_field_output_mpi> <work dir>
source "$(dirname "$0")/common.sh" "$1"
OUT=${2:?usage: field_output_ranks.sh <test_field_output_mpi binary> <work dir>}
mkdir -p "$OUT" && OUT=$(realpath "$OUT")
if [ "$(id -u)" = 0 ]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
export OMPI_MCA_rmaps_base_oversubscribe=1
rm -f "$OUT"/np*.h5 "$OUT"/np*.xmf "$OUT"/changed_*.h5

for n in 1 2 3; do
  if timeout 300 mpirun -np $n "$EXE" "$OUT" > "$OUT/np$n.log" 2>&1; then
    ok "write_np$n"
  else
    bad "write_np$n (log: $OUT/np$n.log)"; tail -n 20 "$OUT/np$n.log"
  fi
done
[ -f "$OUT/np1.h5" ] || { echo "FAIL no $OUT/np1.h5"; exit 1; }

for n in 2 3; do
  if h5diff --exclude-path /provenance "$OUT/np1.h5" "$OUT/np$n.h5"; then ok "h5_np1_equals_np$n"
  else bad "h5_np1_differs_from_np$n"; h5diff -r --exclude-path /provenance "$OUT/np1.h5" "$OUT/np$n.h5" | head -20; fi
  if diff <(sed 's/np1\.h5:/NP.h5:/' "$OUT/np1.xmf") <(sed "s/np$n\\.h5:/NP.h5:/" "$OUT/np$n.xmf"); then
    ok "xmf_np1_equals_np$n"
  else bad "xmf_np1_differs_from_np$n"; fi
done

# The comparison can fail.  h5diff: 0 same, 1 differences, 2 error.
h5diff -q "$OUT/np1.h5" "$OUT/np2.h5"; rc=$?
if [ $rc -eq 1 ]; then ok "h5diff_sees_provenance_when_not_excluded"
else bad "h5diff without --exclude-path returned $rc, expected 1 (n_ranks differs)"; fi
cp "$OUT/np1.h5" "$OUT/changed_data.h5"
cp "$OUT/np1.h5" "$OUT/changed_attr.h5"
if $PYTHON - "$OUT/changed_data.h5" "$OUT/changed_attr.h5" <<'PY'
import sys, h5py
with h5py.File(sys.argv[1], 'r+') as f:
    v = f['steps/000001/velocity']
    v[3, 1] = v[3, 1] * (1 + 1e-15)   # one value, last bits only
with h5py.File(sys.argv[2], 'r+') as f:
    f.attrs['title'] = 'another title'
PY
then
  for c in data attr; do
    h5diff -q --exclude-path /provenance "$OUT/np1.h5" "$OUT/changed_$c.h5"; rc=$?
    if [ $rc -eq 1 ]; then ok "h5diff_sees_changed_$c"
    else bad "h5diff on a file with a changed $c returned $rc, expected 1"; fi
  done
else
  bad "could not make the changed copies (h5py)"
fi
[ $fails -eq 0 ]
