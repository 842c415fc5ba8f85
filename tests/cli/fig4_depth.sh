#!/usr/bin/env bash
# The seed paper's Fig. 4 deck (input/yawed_rod, eroding to free nodes) for
# its first 10 us at dt_safety 0.33, 0.35 (the deck's) and 0.37, a field
# step every 0.25 us: in how many field steps, over the three runs, a node
# of a remaining rod element lies inside a remaining plate element by more
# than 1e-4 of the plate's median edge (tests/cli/fig4_depth.py; a node on
# a face in the symmetry plane counts as inside the mirrored plate since
# 0.9.4), and how deep the rod nodes on the plane go. One run's count
# scatters with the step (0.9.4: 12 / 11 / 21 frames; 0.9.3, whose master
# surface held the plate's faces in the plane: 17 / 20 / 25, its plane
# nodes 0.10 h deep by 2 us). Since 0.9.8 the deck keeps its eroded
# elements' holes closed (&contact voids), and the rod nodes on the plane
# are checked over the whole 10 us too (without voids 0.086 h at 0.33:
# the plate folded into itself through them; validation.md 4zi). Issue 13
# asks for none beyond 1e-6 h: this guards what was reached. Since 0.9.13
# the deck is symmetric, and the plate's nodes inside the rod are checked too.
#   fig4_depth.sh EXE
source "$(dirname "$0")/common.sh" "$1"
mesh=$ROOT/input/yawed_rod/yawed_rod.msh
[ -f "$mesh" ] || { bad "mesh $mesh missing (make meshes)"; exit 1; }
files=()
for dts in 0.33 0.35 0.37; do
  mkdir -p "$W/$dts"
  cp "$mesh" "$W/$dts/"
  sed -e "s/^\( *\)t_end = .*/\1t_end = 10.0e-6/" -e "s/dt_field = [0-9.e-]*/dt_field = 0.25e-6/" \
      -e "s/^\( *\)dt_safety = [0-9.]*/\1dt_safety = $dts/" "$ROOT/input/yawed_rod/yawed_rod.nml" > "$W/$dts/yawed_rod.nml"
  grep -q "t_end = 10.0e-6" "$W/$dts/yawed_rod.nml" && grep -q "dt_safety = $dts" "$W/$dts/yawed_rod.nml" \
    || { bad "deck edit ($dts)"; exit 1; }
  (cd "$W/$dts" && timeout 900 "$EXE" yawed_rod.nml > run.log 2>&1) || { tail "$W/$dts/run.log"; bad "run at $dts"; exit 1; }
  files+=("$W/$dts/out/yawed_rod.h5")
done
$PYTHON "$ROOT/tests/cli/fig4_depth.py" "${files[@]}" || fails=$((fails+1))
# the velocity matching ends converged: with friction, the symmetric deck's
# joint passes ended unconverged at iterations = 50 in 0.9.13 (148 at 0.35,
# 524 over the three runs); since 0.9.14 a pass the alternation
# does not settle is solved together, normals and friction (0.9.14: 0)
unconv=0
for dts in 0.33 0.35 0.37; do
  n=$(grep -o '[0-9]* passes ended at iterations = [0-9]* unconverged' "$W/$dts/run.log" | awk '{print $1}' | sort -n | tail -1)
  unconv=$((unconv + ${n:-0}))
done
if [ "$unconv" -le 10 ]; then ok "fig4_matching_converges ($unconv unconverged passes over the three runs, limit 10)"
else bad "fig4_matching_converges ($unconv unconverged passes over the three runs, limit 10)"; fi
exit $((fails > 0))
