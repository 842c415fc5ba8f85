#!/usr/bin/env bash
# The OFHC Taylor bar (Johnson and Cook 1983: 190 m/s, 16.21 mm long,
# footprint 13.56 mm) on the coarse mesh of regression/taylor_ofhc_baseline
# with its strained elements converted (part of make validate; issue 15,
# doc/validation.md 4zb): no conversion; particles that keep their strength
# (eps_convert 2.0, 1.5, 1.0; 1.5 and 1.0 again without the artificial
# stress, artificial_stress = 0, as udar 0.9.4 had them); strengthless particles and free nodes at the
# same strain (eps_f = eps_erode = 1.0). Length and footprint over the
# remaining elements and the particles, the radius holding 95 % of the
# particles' mass, the share of particles paired up (another within half
# their spacing: the tensile instability) and the energy error go to doc/validation/taylor_particles.csv.
#   tests/validate_taylor_particles.sh
source "$(dirname "$0")/validate_common.sh" taylor_particles
case=tests/regression/taylor_ofhc_baseline
mesh_checked "$W/taylor_ofhc_baseline.msh" $case/taylor_ofhc_baseline.geo
meshes_checked
# name | what the material gains after taylor_quinney (empty: the deck as it is)
variants=(
  "none|"
  "convert_2.0|fracture = 'plastic_strain', eps_f = 100.0, eps_erode = 100.0, eroded = 'particles', eps_convert = 2.0"
  "convert_1.5|fracture = 'plastic_strain', eps_f = 100.0, eps_erode = 100.0, eroded = 'particles', eps_convert = 1.5"
  "convert_1.0|fracture = 'plastic_strain', eps_f = 100.0, eps_erode = 100.0, eroded = 'particles', eps_convert = 1.0"
  "convert_1.5_art0|fracture = 'plastic_strain', eps_f = 100.0, eps_erode = 100.0, eroded = 'particles', eps_convert = 1.5, artificial_stress = 0.0"
  "convert_1.0_art0|fracture = 'plastic_strain', eps_f = 100.0, eps_erode = 100.0, eroded = 'particles', eps_convert = 1.0, artificial_stress = 0.0"
  "strengthless_1.0|fracture = 'plastic_strain', eps_f = 1.0, eps_erode = 1.0, eroded = 'particles'"
  "free_nodes_1.0|fracture = 'plastic_strain', eps_f = 1.0, eps_erode = 1.0"
)
runs=()
for v in "${variants[@]}"; do
  name=${v%%|*}; add=${v#*|}
  sed -e "s|file = 'taylor_ofhc_baseline.msh'|file = '$W/taylor_ofhc_baseline.msh'|" \
      -e "s|directory = 'out'|directory = '$W/$name'|" -e "s|dt_field = 40.0e-6|dt_field = 20.0e-6|" \
      $case/taylor_ofhc_baseline.nml > "$W/$name.nml"
  if [ -n "$add" ]; then
    sed -i "s|taylor_quinney = 0.9$|taylor_quinney = 0.9, $add|" "$W/$name.nml"
    grep -qF "$add" "$W/$name.nml" || { echo "deck edit failed: $name"; exit 1; }
  fi
  grep -q "directory = '$W/$name'" "$W/$name.nml" || { echo "deck edit failed: $name output"; exit 1; }
  runs+=("$name")
done
printf '%s\n' "${runs[@]}" | xargs -P "$JOBS" -I{} sh -c "'$W/udar' '$W/{}.nml' > '$W/{}.log' 2>&1 || echo 'FAILED {}'"
csv=doc/validation/taylor_particles.csv
echo "run,tets,cycles,particles,length_mm,footprint_mm,r95_mm,paired,energy_error,experiment_length_mm,experiment_footprint_mm" > $csv
for run in "${runs[@]}"; do
  m=$($PYTHON $case/particles_check.py --measure "$W/$run/$run.h5")
  echo "$run,$(log_value "$W/$run.log" tets),$(log_value "$W/$run.log" cycles),$m,$(log_value "$W/$run.log" energy_error),16.21,13.56" \
    | tee -a $csv
done
echo "results in $csv"
