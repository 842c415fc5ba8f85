#!/usr/bin/env bash
# An element gauge by its mesh tag (&gauge element) on the elastic bar: the
# element holding a point near the bar's middle (its tag found from the mesh
# as udar read it), against a point gauge at that element's centroid (the
# same element values, bitwise, on 2 ranks: the tag's element is owned by
# one of them) and against 1D wave theory (axial stress -rho c v); and a
# node gauge (&gauge node) at a corner of the free end, its tag found the
# same way, against the wave solution (velocity -v, then +v; displacement).
#   gauge_element_tag.sh EXE
source "$(dirname "$0")/common.sh" "$1"
TOOLS="$ROOT/tests/tools"
cp "$ROOT/tests/regression/elastic_bar/elastic_bar.msh" "$W/"
# the mesh as read: a run of one step
sed 's/^\( *\)t_end = .*/\1t_end = 1.0e-9/' "$ROOT/tests/regression/elastic_bar/elastic_bar.nml" > "$W/probe.nml"
(cd "$W" && "$EXE" probe.nml > probe.log 2>&1) || { cat "$W/probe.log"; bad "probe run"; exit 1; }
read -r tag cx cy cz < <($PYTHON "$TOOLS/gauge_tag.py" pick "$W/out/probe.h5" 0.0031 0.0067 0.0503) \
  || { bad "no element holds the point"; exit 1; }
end=$($PYTHON "$TOOLS/gauge_tag.py" node "$W/out/probe.h5" 0.0 0.0 0.1) || { bad "no node at the free end's corner"; exit 1; }
echo "element tag $tag, centroid $cx $cy $cz; free end corner node $end"
cp "$ROOT/tests/regression/elastic_bar/elastic_bar.nml" "$W/"
cat >> "$W/elastic_bar.nml" <<DECK
&gauge name = 'by_tag', element = $tag /
&gauge name = 'at_centroid', point = $cx, $cy, $cz /
&gauge name = 'end_node', node = $end /
DECK
(cd "$W" && timeout 600 mpirun -np 2 "$EXE" elastic_bar.nml > run.log 2>&1) || { cat "$W/run.log"; bad "run"; exit 1; }
$PYTHON "$TOOLS/gauge_tag.py" compare "$W/out/elastic_bar_history.csv" by_tag at_centroid $cx $cy $cz end_node || fails=$((fails+1))
[ $fails -eq 0 ]
