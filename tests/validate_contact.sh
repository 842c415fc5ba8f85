#!/usr/bin/env bash
# Contact depth sweeps (part of make validate; doc/validation.md 4r, 4s): the
# 3 km/s rod deck (tests/regression/rod_3kms, rod_3kms_fast.nml) and the
# eroding penetration deck (tests/regression/penetration) on their
# committed meshes, at several dt_safety, with &contact valleys off and on
# (and, for the penetration deck, sharp_edges on), fields every 0.05 us; the
# block sliding towards a wedge's sharp edge (tests/regression/sharp_edge)
# with sharp_edges on and off; the seed paper's Fig. 4 deck's first 20 us:
# over every frame, how often and how deep a slave
# node is inside a remaining master element (tests/tools/contact_depth.py).
# The make check decks look at a few frames of one dt_safety, where a
# node's stay inside for a few cycles can fall between frames; this is the
# measure of a contact change. Results: doc/validation/contact_depth.csv.
source "$(dirname "$0")/validate_common.sh" contact
meshes_checked
runs=()
for dts in 0.7 0.75 0.8 0.85 0.9 0.95 1.0; do
  for v in off on; do runs+=("rod_3kms rod_3kms_fast $dts $v"); done
done
for dts in 0.33 0.35 0.37 0.4 0.5 0.7 0.9; do
  for v in off on sharp; do runs+=("penetration penetration $dts $v"); done
done
for r in "${runs[@]}"; do
  set -- $r
  d=$W/$2_$3_$4
  mkdir -p "$d"
  cp tests/regression/$1/$1.msh "$d/"
  # the deck's own contact line with valleys set, its step and field interval changed
  # off: neither valleys nor sharp_edges (0.5.6's defaults); on: valleys;
  # sharp: sharp_edges (0.5.7's defaults)
  extra=", valleys = .$([ $4 = on ] && echo true || echo false)., sharp_edges = .$([ $4 = sharp ] && echo true || echo false)."
  sed -e "s/^\( *\)dt_safety = [0-9.]*/\1dt_safety = $3/" -e "s/dt_field = [0-9.e-]*/dt_field = 0.05e-6/" \
      -e "s/, valleys = \.[a-z]*\.//" -e "s/, sharp_edges = \.[a-z]*\.//" -e "/^&contact/s| /\$|$extra /|" \
      tests/regression/$1/$2.nml > "$d/$2.nml"
  grep -q "valleys = .$([ $4 = on ] && echo true || echo false)." "$d/$2.nml" || { echo "stopped: valleys not set in $d/$2.nml"; exit 1; }
done
# the wedge, as its make check decks are (sharp_edges on / off)
for deck in sharp_edge sharp_edge_off; do
  runs+=("sharp_edge $deck - -")
  d=$W/${deck}_-_-
  mkdir -p "$d"
  cp tests/regression/sharp_edge/sharp_edge.msh tests/regression/sharp_edge/$deck.nml "$d/"
done
# the seed paper's Fig. 4 deck (input/yawed_rod, eroding) at its own step,
# its first 20 us with fields every 0.25 us (validation.md 4t), eroding to
# free nodes (the deck) and to particles
runs+=("yawed_rod yawed_rod 0.35 deck")
d=$W/yawed_rod_0.35_deck
mkdir -p "$d"
cp input/yawed_rod/yawed_rod.msh "$d/"
sed -e "s/t_end = [0-9.e-]*/t_end = 20.0e-6/" -e "s/dt_field = [0-9.e-]*/dt_field = 0.25e-6/" \
    input/yawed_rod/yawed_rod.nml > "$d/yawed_rod.nml"
grep -q "t_end = 20.0e-6" "$d/yawed_rod.nml" || { echo "stopped: t_end not set in $d/yawed_rod.nml"; exit 1; }
# the same with failed material kept as particles (issue 15): the slave
# points are then the remaining rod elements' nodes and the rod's particles
runs+=("yawed_rod yawed_rod 0.35 particles")
d=$W/yawed_rod_0.35_particles
mkdir -p "$d"
cp input/yawed_rod/yawed_rod.msh "$d/"
sed -e "s/eps_erode = 2.0$/eps_erode = 2.0, eroded = 'particles'/" "$W/yawed_rod_0.35_deck/yawed_rod.nml" > "$d/yawed_rod.nml"
[ "$(grep -c "eroded = 'particles'" "$d/yawed_rod.nml")" = 2 ] || { echo "stopped: particles not set in $d/yawed_rod.nml"; exit 1; }
export W
printf '%s\n' "${runs[@]}" | awk '{print $2"_"$3"_"$4" "$2}' | \
  xargs -P "$JOBS" -L1 sh -c 'cd "$W/$0" && "$W/udar" "$1.nml" > run.log 2>&1 || echo "FAILED $0"'
csv=doc/validation/contact_depth.csv
echo "deck,dt_safety,variant,frames,frames_with_a_node_inside,deepest_over_h,at_us,cycles,energy_error" > $csv
for r in "${runs[@]}"; do
  set -- $r
  d=$W/$2_$3_$4
  depth=$($PYTHON tests/tools/contact_depth.py "$d/out/$2.h5" 1 2)
  cyc=$(log_value "$d/run.log" cycles)
  err=$(log_value "$d/run.log" energy_error)
  echo "$2,$3,$4,$depth,$cyc,$err" | tee -a $csv
done
echo "results in $csv"
