#!/usr/bin/env bash
# The program's own handling of bad input: exit code 1, a message naming the
# file, group and variable, nothing written or destroyed; --check, --help.
source "$(dirname "$0")/common.sh" "$1"
expect() {  # name, expected exit code, pattern in stderr, deck
  local name=$1 code=$2 pat=$3 deck=$4 rc
  (cd "$W" && "$EXE" $deck) > "$W/out.txt" 2> "$W/err.txt"; rc=$?
  if [ $rc -eq "$code" ] && grep -qiE -- "$pat" "$W/err.txt"; then ok "$name (exit $rc)"
  else bad "$name: exit $rc, stderr:"; sed 's/^/      /' "$W/err.txt"; fi
}

cp "$ROOT/tests/regression/elastic_bar/elastic_bar.msh" "$W/bar.msh"
good='&run t_end = 1e-6 /
&mesh file = "bar.msh" /
&material name = "steel", rho0 = 7850, youngs_modulus = 200e9, poisson_ratio = 0.3 /
&part group = "bar", material = "steel" /
&output directory = "out" /'
printf '%s\n' "$good" > "$W/good.nml"
mkdir -p "$W/out"; echo precious > "$W/out/bad_value.h5"

sed 's/rho0 = 7850/rho0 = 78x50/' "$W/good.nml" > "$W/bad_value.nml"
expect bad_value 1 'bad_value.nml.*rho0' bad_value.nml
if [ "$(cat "$W/out/bad_value.h5")" = precious ]; then ok "nothing_destroyed"; else bad "nothing_destroyed"; fi
sed 's/group = "bar"/group = "rod"/' "$W/good.nml" > "$W/bad_group.nml"
expect unknown_part_group 1 "bad_group.nml:4: &part #1 'rod': group = 'rod'.*no physical volume group.*'bar'" bad_group.nml
sed 's/&material name = "steel"/&material name = "steel", yield_stres = 1e8/' "$W/good.nml" > "$W/misspelled.nml"
expect misspelled_variable 1 'yield_stres.*yield_stress' misspelled.nml
printf '%s\n&boundary kind = "symmetry", surface = "nowhere" /\n' "$good" > "$W/bad_surface.nml"
expect unknown_surface 1 "bad_surface.nml:6: &boundary #1 'nowhere': surface = 'nowhere'.*impact_face" bad_surface.nml
expect missing_deck 1 'missing.nml' missing.nml
printf '%s\n&numerics stabilisation = 0.2 /\n' "$good" > "$W/bad_share.nml"
expect share_above_the_large_share 1 "bad_share.nml:6: &numerics.*stabilisation = 0.2 : must be at most stabilisation_large = 0.1" bad_share.nml

# closed voids: only where a part of the contact erodes
printf '%s\n&contact master = "bar", slave = "impact_face", voids = .true. /\n' "$good" > "$W/voids_no_erosion.nml"
expect voids_without_erosion 1 "voids_no_erosion.nml:6: &contact #1.*voids.*neither part of the contact erodes" \
  "--check voids_no_erosion.nml"

# gauges: one of node, element or point, each in the mesh
printf '%s\n&gauge name = "a-b", node = 1, element = 1 /\n' "$good" > "$W/bad_gauge.nml"
expect gauge_name_and_kind 1 "bad_gauge.nml:6: &gauge #1 'a-b': name = .a-b. : letters, digits and _ only" bad_gauge.nml
expect gauge_one_kind 1 "bad_gauge.nml:6: &gauge #1 'a-b': give exactly one of node" bad_gauge.nml
printf '%s\n&gauge name = "far", point = 0.005, 0.005, 0.2 /\n' "$good" > "$W/gauge_outside.nml"
expect gauge_point_outside 1 "gauge_outside.nml:6: &gauge #1 'far': point = 0.005, 0.005, 0.2: the point is in no element of .*bar.msh" \
  gauge_outside.nml
printf '%s\n&gauge name = "n", node = 999999 /\n' "$good" > "$W/gauge_no_node.nml"
expect gauge_node_not_in_mesh 1 "gauge_no_node.nml:6: &gauge #1 'n': node = 999999: no node of that tag" gauge_no_node.nml

# eroded elements become particles only where elements erode
sed 's/&material name = "steel"/\&material name = "steel", eroded = "particles"/' "$W/good.nml" > "$W/particles_no_erosion.nml"
expect particles_without_erosion 1 "particles_no_erosion.nml:3: &material #1 'steel': eroded = .particles. : 'particles' is what eroded elements become.*set eps_erode > 0" \
  particles_no_erosion.nml
# eps_convert (strained elements become particles with strength) needs particles
sed 's/&material name = "steel"/\&material name = "steel", fracture = "plastic_strain", eps_f = 1, eps_erode = 2, eps_convert = 0.8/' \
  "$W/good.nml" > "$W/convert_no_particles.nml"
expect convert_without_particles 1 "convert_no_particles.nml:3: &material #1 'steel': eps_convert = 0.8.*only eroded = 'particles' converts" \
  convert_no_particles.nml
sed 's/&material name = "steel"/\&material name = "steel", eroded = "particles", fracture = "plastic_strain", eps_f = 1, eps_erode = 2, eps_convert = -1/' \
  "$W/good.nml" > "$W/convert_negative.nml"
expect convert_negative 1 "convert_negative.nml:3: &material #1 'steel': eps_convert = -1.*>= 0" convert_negative.nml
# the artificial stress is for particles that keep their strength (and carry tension)
sed 's/&material name = "steel"/\&material name = "steel", eroded = "particles", fracture = "plastic_strain", eps_f = 1, eps_erode = 2, artificial_stress = 0.2/' \
  "$W/good.nml" > "$W/artificial_no_convert.nml"
expect artificial_stress_without_strong_particles 1 \
  "artificial_no_convert.nml:3: &material #1 'steel': artificial_stress = 0.2.*only used with particles that keep their strength" \
  artificial_no_convert.nml
sed 's/&material name = "steel"/\&material name = "steel", eroded = "dust"/' "$W/good.nml" > "$W/eroded_word.nml"
expect eroded_unknown_word 1 "eroded_word.nml:3: &material #1 'steel': eroded = .dust. : unknown choice.*'free_nodes', 'particles'" eroded_word.nml

(cd "$W" && "$EXE" --check good.nml) > "$W/check.txt" 2>&1; rc=$?
if [ $rc -eq 0 ] && grep -q 'rho0' "$W/check.txt" && grep -q 'default' "$W/check.txt" && [ ! -e "$W/out/good.h5" ]
then ok "check_prints_resolved_deck"; else bad "check_prints_resolved_deck (exit $rc)"; cat "$W/check.txt"; fi
(cd "$W" && "$EXE" --check --ranks 3 good.nml) > "$W/ranks.txt" 2>&1; rc=$?
if [ $rc -eq 0 ] && grep -q 'partition over 3 ranks.*edge cut' "$W/ranks.txt" && \
   [ "$(grep -cE '^ +[0-2] +[0-9]+ +[0-9]+ +[0-9]+ +[0-9]+$' "$W/ranks.txt")" -eq 3 ] && grep -q 'decomposition cost over 3 ranks: ghost element work' "$W/ranks.txt"
then ok "check_ranks_partition_report"; else bad "check_ranks_partition_report (exit $rc)"; cat "$W/ranks.txt"; fi
expect ranks_without_check 1 'ranks goes with --check' "--ranks 2 good.nml"
# two separate bodies: warned that there is no contact yet
cat > "$W/two.geo" <<'GEO'
SetFactory("OpenCASCADE");
Box(1) = {0,0,0, 1,1,1};
Box(2) = {0,0,2, 1,1,1};
Physical Volume("a") = {1};
Physical Volume("b") = {2};
Mesh.CharacteristicLengthMax = 0.5;
GEO
gmsh -3 -v 0 "$W/two.geo" -o "$W/two.msh"
printf '%s\n' '&run t_end = 1e-6 /' "&mesh file = 'two.msh' /" \
  "&material name = 'steel', rho0 = 7850, youngs_modulus = 200e9, poisson_ratio = 0.3 /" \
  "&part group = 'a', material = 'steel' /" "&part group = 'b', material = 'steel' /" > "$W/two.nml"
(cd "$W" && "$EXE" --check two.nml) > "$W/two.txt" 2>&1; rc=$?
if [ $rc -eq 0 ] && grep -q 'warning: the mesh holds 2 separate bodies' "$W/two.txt"; then ok "two_bodies_warned"
else bad "two_bodies_warned (exit $rc)"; cat "$W/two.txt"; fi
# Mie-Grueneisen with E and nu: they set only G; the K they imply is shown next
# to rho0*c0**2 and a difference over 1 % is a warning, not an error.
# initial_temperature defaults to the material's t_room.
sed "s/poisson_ratio = 0.3/poisson_ratio = 0.3, eos = 'mie_gruneisen', c0 = 4570, t_room = 300/" "$W/good.nml" > "$W/mg.nml"
(cd "$W" && "$EXE" --check mg.nml) > "$W/mg.txt" 2> "$W/mg_err.txt"; rc=$?
if [ $rc -eq 0 ] && grep -q "bulk_modulus = 1.63946465e11 .*rho0\*c0\*\*2.*imply E/(3(1-2nu)) = 1.667e11" "$W/mg.txt" && \
   grep -q "mg.nml:3: &material #1 'steel': youngs_modulus and poisson_ratio imply a bulk modulus E/(3(1-2nu)) = 1.667e11 Pa, +1.7 % from the rho0\*c0\*\*2" "$W/mg_err.txt"
then ok "mie_gruneisen_implied_bulk_modulus"; else bad "mie_gruneisen_implied_bulk_modulus (exit $rc)"; cat "$W/mg.txt" "$W/mg_err.txt"; fi
if grep -qE "^  initial_temperature = 300.0 +! K \(derived: t_room\)" "$W/mg.txt"; then ok "initial_temperature_is_t_room"
else bad "initial_temperature_is_t_room"; grep -E "t_room|initial_temperature" "$W/mg.txt"; fi
"$EXE" --help > "$W/help.txt" 2>&1 && grep -q usage "$W/help.txt" && ok help || bad help
"$EXE" --version 2>&1 | grep -qE '^udar [0-9]' && ok version || bad version
# udar --check deck > resolved.nml gives a valid deck (log lines go to stderr),
# and checking that one prints the same deck again (but for its file name)
(cd "$W" && "$EXE" --check good.nml > resolved.nml 2> check_err.txt && "$EXE" --check resolved.nml > resolved2.nml 2>> check_err.txt); rc=$?
if [ $rc = 0 ] && [ "$(head -c1 "$W/resolved.nml")" = '!' ] && grep -q '^&run' "$W/resolved.nml" && \
   diff <(grep -v '^! from:' "$W/resolved.nml" | sed 's/ *!.*//') <(grep -v '^! from:' "$W/resolved2.nml" | sed 's/ *!.*//') > /dev/null && \
   grep -q 'is valid' "$W/check_err.txt" && ! grep -q 'is valid\|^mesh ' "$W/resolved.nml"; then
  ok "check_output_is_a_valid_deck"
else bad "check_output_is_a_valid_deck (exit $rc)"; head -3 "$W/resolved.nml"; cat "$W/check_err.txt"; fi
# the output folder is checked by --check too, at its deck line
sed 's#directory = "out"#directory = "good.nml/out"#' "$W/good.nml" > "$W/bad_dir.nml"
grep -q 'good.nml/out' "$W/bad_dir.nml" || bad "deck edit"
expect output_folder_under_a_file 1 "bad_dir.nml:5: &output: directory = 'good.nml/out': cannot be created: 'good.nml' is a file" "--check bad_dir.nml"
# 2D decks (&mesh geometry): the mesh and the deck's vectors must be 2D
cp "$ROOT/tests/regression/elastic_bar_2d/elastic_bar_2d.msh" "$W/bar2d.msh"
good2d='&run t_end = 1e-6 /
&mesh file = "bar2d.msh", geometry = "axisymmetric" /
&material name = "steel", rho0 = 7850, youngs_modulus = 200e9, poisson_ratio = 0.3 /
&part group = "bar", material = "steel", velocity = 0.0, -10.0 /
&output directory = "out" /'
printf '%s\n' "$good2d" > "$W/good2d.nml"
expect axisymmetric_deck_checks 0 '' "--check good2d.nml"
sed 's/&material name = "steel"/\&material name = "steel", fracture = "plastic_strain", eps_f = 1, eps_erode = 2, eroded = "particles"/' \
  "$W/good2d.nml" > "$W/particles2d.nml"
# axisymmetric and plane strain take them (the 2D kernel; ring particles axisymmetric)
expect particles_axisymmetric_deck_checks 0 '' "--check particles2d.nml"
# particles that keep their strength: no artificial stress in 2D (it gained energy there)
sed 's/eroded = "particles"/eroded = "particles", eps_convert = 1.0, artificial_stress = 0.3/' "$W/particles2d.nml" > "$W/art2d.nml"
expect artificial_stress_in_2d 1 "art2d.nml:3: &material #1 'steel': artificial_stress = 0.3 : is 3D only: in 2D \(geometry = 'axisymmetric'\)" \
  "--check art2d.nml"
sed 's/eroded = "particles"/eroded = "particles", eps_convert = 1.0/' "$W/particles2d.nml" > "$W/conv2d.nml"
expect converting_2d_deck_checks 0 '' "--check conv2d.nml"
sed 's/geometry = "axisymmetric"/geometry = "plane_strain"/' "$W/particles2d.nml" > "$W/particles_plane.nml"
expect particles_plane_strain_deck_checks 0 '' "--check particles_plane.nml"
sed 's/bar2d.msh/bar.msh/' "$W/good2d.nml" > "$W/mesh3d.nml"
expect 3d_mesh_with_a_2d_deck 1 "mesh3d.nml:2: &mesh: file = .*the mesh is 3D but a 2D calculation was asked for" "--check mesh3d.nml"
sed 's/velocity = 0.0, -10.0/velocity = 0.0, 0.0, -10.0/' "$W/good2d.nml" > "$W/vel3.nml"
expect third_velocity_component_in_2d 1 "vel3.nml:4: &part #1 'bar': velocity = .*third component must be 0 in a 2D \(axisymmetric\)" "--check vel3.nml"
printf '%s\n&boundary kind = "rigid_wall", point = 0, 0, 0, normal = 0, 0, 1 /\n' "$good2d" > "$W/wall3.nml"
expect 3d_wall_in_2d 1 "wall3.nml:6: &boundary #1.*normal = .*a rigid wall is a line in the mesh plane" "--check wall3.nml"
printf '%s\n&boundary kind = "symmetry", surface = "bar_side" /\n' "$good2d" > "$W/curve2d.nml"
expect unknown_curve_in_2d 1 "curve2d.nml:6: &boundary #1 'bar_side': surface = 'bar_side': no physical curve group of that name .*'impact_face', 'axis'" "--check curve2d.nml"
printf '%s\n&contact master = "bar", slave = "impact_face", edges = .true. /\n' "$good2d" > "$W/edges2d.nml"
expect edges_in_2d 1 "edges2d.nml:6: &contact #1.*edges.*edge-to-edge contact has no 2D meaning" "--check edges2d.nml"
printf '%s\n&contact master = "bar", slave = "impact_face", voids = .true. /\n' "$good2d" > "$W/voids2d.nml"
expect voids_in_2d 1 "voids2d.nml:6: &contact #1.*voids.*closed voids are for 3D meshes only" "--check voids2d.nml"
printf '%s\n&contact master = "bar_side", slave = "bar" /\n' "$good2d" > "$W/contact2d.nml"
expect unknown_contact_curve_in_2d 1 "contact2d.nml:6: &contact #1.*'bar_side' is neither a part nor a physical curve group .*curve groups: 'impact_face', 'axis'" "--check contact2d.nml"
printf '%s\n&contact master = "axis", slave = "bar" /\n' "$good2d" > "$W/axis2d.nml"
expect contact_on_the_axis 1 "axis2d.nml:6: &contact #1.*curve group 'axis' has no segment on the boundary of the mesh \\(off the axis" "--check axis2d.nml"
# 3D: a contact surface that lies in a symmetry plane bounds no material either
cp "$ROOT/tests/regression/plate_impact/plate_impact.msh" "$W/column.msh"
printf '%s\n' '&run t_end = 1e-6 /' '&mesh file = "column.msh" /' \
  '&material name = "copper", rho0 = 8930, youngs_modulus = 120e9, poisson_ratio = 0.3 /' \
  '&part group = "column", material = "copper" /' '&boundary kind = "symmetry", surface = "side_x0" /' \
  '&contact master = "column", slave = "side_x0" /' '&output directory = "out" /' > "$W/plane3d.nml"
expect contact_on_a_symmetry_plane 1 "plane3d.nml:6: &contact #1.*surface group 'side_x0' has no triangle on the boundary of the mesh \\(off the symmetry planes\\)" "--check plane3d.nml"
sed 's/geometry = "axisymmetric"/geometry = "axisymetric"/' "$W/good2d.nml" > "$W/geom.nml"
expect misspelled_geometry 1 "geom.nml:2: &mesh: geometry = .*axisymetric.*axisymmetric" "--check geom.nml"
# an axisymmetric mesh with a node at r < 0
sed 's/^Point(1) = {0, 0, 0}; Point(2) = {R, 0, 0}; Point(3) = {R, L, 0}; Point(4) = {0, L, 0};/Point(1) = {-R, 0, 0}; Point(2) = {R, 0, 0}; Point(3) = {R, L, 0}; Point(4) = {-R, L, 0};/' \
  "$ROOT/tests/regression/elastic_bar_2d/elastic_bar_2d.geo" > "$W/neg.geo"
gmsh -2 -v 0 "$W/neg.geo" -o "$W/neg.msh"
sed 's/bar2d.msh/neg.msh/' "$W/good2d.nml" > "$W/neg.nml"
expect node_at_negative_radius 1 "neg.nml:2: &mesh: file = .*node [0-9]+ is at x = -.*x = r >= 0" "--check neg.nml"
[ $fails -eq 0 ]
