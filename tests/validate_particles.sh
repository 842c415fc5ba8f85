#!/usr/bin/env bash
# Failed material kept as particles (issue 15) on the seed paper's decks and
# the long rod's conversion limit (part of make validate): the yawed W-Ni-Fe
# rod through a plate (Fig. 4) and the compact cylinder's normal impact
# with eroded = 'particles' in both materials, and the long rod at 2 km/s
# with particles and eps_erode (the conversion limit) 2.5 and 3.0 instead
# of the deck's 2.0 (tests/validate_long_rod.sh with ERODED=particles runs
# the deck's). Runs two at a time; doc/validation/particle_decks.csv and
# the Fig. 4 sections at 0, 16 and 44.03 us (doc/validation/).
# EPS_CONVERT=X: Fig. 4 and the normal cylinder only, their strained
# elements that have not fractured becoming particles that keep their
# strength (&material eps_convert = X, every material);
# doc/validation/particle_decks_convertX.csv, pictures *_convertX_*.
#   tests/validate_particles.sh
#   EPS_CONVERT=1.0 tests/validate_particles.sh
tag=${EPS_CONVERT:+_convert$EPS_CONVERT}
source "$(dirname "$0")/validate_common.sh" particles$tag
mesh_checked "$W/yawed_rod.msh" input/yawed_rod/yawed_rod.geo
mesh_checked "$W/normal_cylinder.msh" input/normal_cylinder/normal_cylinder.geo
mesh_checked "$W/long_rod.msh" input/long_rod/long_rod.geo -setnumber h 1.0e-3
meshes_checked
# deck name, input deck, mesh, eps_erode of the deck, eps_erode here
runs=("yawed_rod yawed_rod yawed_rod 2.0 2.0"
      "long_rod_e2.5 long_rod long_rod 2.0 2.5"
      "long_rod_e3.0 long_rod long_rod 2.0 3.0"
      "normal_cylinder normal_cylinder normal_cylinder 3.0 3.0")
[ -n "${EPS_CONVERT:-}" ] && runs=("${runs[0]}" "${runs[3]}")
for r in "${runs[@]}"; do
  set -- $r
  sed -e "s|file = '$3.msh'|file = '$W/$3.msh'|" -e "s|directory = '[^']*'|directory = '$W/$1'|" \
      -e "s|eps_erode = $4$|eps_erode = $5, eroded = 'particles'|" input/$2/$2.nml > "$W/$1.nml"
  [ "$(grep -c "eps_erode = $5, eroded = 'particles'" "$W/$1.nml")" = "$(grep -c "eps_erode = $4$" input/$2/$2.nml)" ] || \
    { echo "deck edit failed: $1"; exit 1; }
  with_eps_convert "$W/$1.nml" "$(grep -c "eps_erode = $4$" input/$2/$2.nml)"
done
printf '%s\n' "${runs[@]}" | cut -d' ' -f1 | xargs -P "$JOBS" -I{} sh -c "'$W/udar' '$W/{}.nml' > '$W/{}.log' 2>&1 || echo 'FAILED {}'"
csv=doc/validation/particle_decks$tag.csv
echo "deck,eps_erode,t_us,crater_on_axis_mm,projectile_left_along_axis_mm,intact_along_axis_mm,crater_deepest_mm,projectile_velocity_along_axis_m_s,projectile_particles,projectile_particle_mass_g,target_particles,target_particle_mass_g,energy_error,cycles,wall_s" > $csv
for r in "${runs[@]}"; do
  set -- $r
  case $2 in
    yawed_rod) args="--rod rod --target plate --radius 0.5e-3 --axis 0.70710678 0 -0.70710678" ;;
    normal_cylinder) args="--rod cylinder --target plate --radius 0.5e-3" ;;
    long_rod) args="--radius 1.25e-3" ;;
  esac
  line=$($PYTHON postproc/penetration.py "$W/$1/$1.h5" $args | tail -1)
  echo "$line" | awk -v n=$1 -v eps=$5 -v e=$(log_value "$W/$1.log" energy_error) -v c=$(log_value "$W/$1.log" cycles) \
    -v w=$(log_value "$W/$1.log" wall_s) \
    '{printf "%s,%s,%s,%s,%s,%s,%s,%s,%s,%.4f,%s,%.4f,%s,%s,%s\n", n, eps, $1, $2, $3, $8, $9, $4, $11, $12, $13, $14, e, c, w}' \
    | tee -a $csv
done
S="$PYTHON postproc/section.py --plane y=0.3mm"
for t in 0 16 44.03; do
  $S "$W/yawed_rod/yawed_rod.h5" --time $t --color part --xlim -30 80 --ylim -70 30 \
     --title "Fig. 4 deck with particles${EPS_CONVERT:+ (eps_convert $EPS_CONVERT)} (W-Ni-Fe rod, 2 km/s, 35 deg, 10 deg yaw), $t us" \
     -o doc/validation/yawed_rod_particles${tag}_${t%%.*}us_parts.png
done
echo "results in $csv"
