#!/usr/bin/env bash
# Failed material kept as ring particles in 2D (issues 14 and 15, part of
# make validate): the seed paper's normal-impact cylinder axisymmetric
# (input/normal_cylinder_2d) at h = 0.8 (the 3D deck's), 0.4 and 0.2 mm,
# its eroded elements becoming particles (eps_erode 3.0, strengthless) and,
# with eps_convert 1.0, its strained elements becoming particles that keep
# their strength (no artificial stress: 2D takes none); the contact both
# ways (symmetric = .true., as 2D eroding contact with particles needs).
# Crater on the axis and deepest at 30 us (postproc/penetration.py) to
# doc/validation/particle_decks_2d.csv, beside the 3D deck's of
# tests/validate_particles.sh (doc/validation.md 4zh).
#   tests/validate_particles_2d.sh
source "$(dirname "$0")/validate_common.sh" particles_2d
for h in 0.8 0.4 0.2; do
  if [ $h = 0.8 ]; then
    mesh_checked "$W/nc_h$h.msh" input/normal_cylinder_2d/normal_cylinder_2d.geo
  else
    mesh_checked "$W/nc_h$h.msh" input/normal_cylinder_2d/normal_cylinder_2d.geo -setnumber h ${h}e-3
  fi
done
meshes_checked
runs=()
for h in 0.8 0.4 0.2; do
  for kind in particles convert1.0; do
    run=${kind}_h$h
    extra=""; [ $kind = convert1.0 ] && extra=", eps_convert = 1.0"
    sed -e "s|file = 'normal_cylinder_2d.msh'|file = '$W/nc_h$h.msh'|" -e "s|directory = 'out'|directory = '$W/$run'|" \
        -e "s|eps_erode = 3.0$|eps_erode = 3.0, eroded = 'particles'$extra|" \
        -e "s|&contact master = 'plate', slave = 'cylinder', friction = 0.18,|\&contact master = 'plate', slave = 'cylinder', friction = 0.18, symmetric = .true.,|" \
        input/normal_cylinder_2d/normal_cylinder_2d.nml > "$W/$run.nml"
    [ "$(grep -c "eroded = 'particles'" "$W/$run.nml")" = 1 ] && grep -q "symmetric = .true." "$W/$run.nml" || \
      { echo "deck edit failed: $run"; exit 1; }
    runs+=("$run")
  done
done
printf '%s\n' "${runs[@]}" | xargs -P "$JOBS" -I{} sh -c "'$W/udar' '$W/{}.nml' > '$W/{}.log' 2>&1 || echo 'FAILED {}'"
csv=doc/validation/particle_decks_2d.csv
echo "run,mesh_mm,triangles,t_us,crater_on_axis_mm,crater_deepest_mm,crater_diameter_mm,projectile_particle_mass_g,target_particle_mass_g,energy_error,cycles,wall_s" > $csv
for run in "${runs[@]}"; do
  line=$($PYTHON postproc/penetration.py "$W/$run/$run.h5" --rod cylinder --target plate --radius 0.5e-3 --axis 0 -1 0 | tail -1)
  tri=$(grep -o '[0-9]* triangles' "$W/$run.log" | head -1 | cut -d' ' -f1)
  echo "$line" | awk -v n=$run -v h=${run##*_h} -v tri=$tri -v e=$(log_value "$W/$run.log" energy_error) \
    -v c=$(log_value "$W/$run.log" cycles) -v w=$(log_value "$W/$run.log" wall_s) \
    '{printf "%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s\n", n, h, tri, $1, $2, $9, $10, $12, $14, e, c, w}' | tee -a $csv
done
$PYTHON postproc/section.py "$W/particles_h0.4/particles_h0.4.h5" --time 30 --color part --mirror --xlim -30 30 --ylim -32 12 \
  --title "normal cylinder, axisymmetric, ring particles (eps_erode 3), h 0.4 mm, 30 us" \
  -o doc/validation/normal_cylinder_2d_particles_30us_parts.png
echo "results in $csv"
