#!/usr/bin/env bash
# Long-rod penetration against the Lanz-Odermatt fit (part of make
# validate): the tungsten-alloy rod of input/long_rod (L/D = 10, D = 5 mm)
# into the thick steel block at 1.5, 2.0 and 2.5 km/s, run two at a time;
# the crater depth at the end over the rod length (postproc/penetration.py)
# goes to doc/validation/long_rod.csv (h = 1 mm, the deck's mesh) or
# long_rod_hH.csv (H in mm, a refinement) next to the reference values.
#   [VELOCITIES='2000'] tests/validate_long_rod.sh [2d] [mesh size in m, default 1.0e-3 (2d: 0.5e-3)]
# make validate runs the 1 mm mesh and the 2D deck's 0.5 mm; the
# refinements of doc/validation.md 4i and 4v:
#   tests/validate_long_rod.sh 0.7e-3; VELOCITIES=2000 tests/validate_long_rod.sh 0.5e-3
#   VELOCITIES=2000 tests/validate_long_rod.sh 2d 0.25e-3
# 2d: the axisymmetric deck input/long_rod_2d (csv long_rod_2d_hH.csv).
# ERODED=particles: eroded elements become particles (issue 15; csv
# long_rod_particles[_hH].csv, 2D: long_rod_2d_particles_hH.csv, whose
# contact is then both ways, symmetric = .true., as 2D eroding contact
# with particles needs: user-guide), e.g.
#   VELOCITIES=2000 ERODED=particles tests/validate_long_rod.sh
# with EPS_CONVERT=X besides, strained elements become particles that keep
# their strength (&material eps_convert = X, both materials), and with
# EPS_F=Y the fracture strain of both is Y (eps_erode too); csv
# long_rod_particles_convertX[_fY][_hH].csv; with ARTIFICIAL_STRESS=Z
# besides, those particles have Monaghan's artificial stress (&material
# artificial_stress = Z, both materials; csv ..._convertX_artZ...); with
# SPH_SWITCH=1 the particles' viscosity has Balsara's switch (&numerics
# sph_viscosity_switch; csv ..._switch...).
dim=3d
if [ "${1:-}" = 2d ]; then dim=2d; shift; fi
source "$(dirname "$0")/validate_common.sh" long_rod_$dim
if [ $dim = 2d ]; then
  H=${1:-0.5e-3}; name=long_rod_2d; vel3='0.0, '
else
  H=${1:-1.0e-3}; name=long_rod; vel3='0.0, 0.0, '
fi
# h of the .geo is in metres, like H
mesh_checked "$W/${name}_h$H.msh" input/$name/$name.geo -setnumber h "$H"
meshes_checked
# Lanz-Odermatt P/L for tungsten alloy into RHA, L/D = 10 (Anderson, Walker
# and Hohler 1999, as tabulated in doc/validation.md)
declare -A ref=([1500]=0.90 [2000]=1.24 [2500]=1.44)
runs=()
for v in ${VELOCITIES:-1500 2000 2500}; do
  run=v${v}_h$H
  sed -e "s|file = '$name.msh'|file = '$W/${name}_h$H.msh'|" -e "s|directory = 'out'|directory = '$W/$run'|" \
      -e "s|velocity = ${vel3}-2000.0|velocity = ${vel3}-$v.0|" -e "s|2.0 km/s|$v m/s|" \
      input/$name/$name.nml > "$W/$run.nml"
  if [ "${ERODED:-}" = particles ]; then
    sed -i "s|eps_erode = 2.0$|eps_erode = 2.0, eroded = 'particles'|" "$W/$run.nml"
    [ "$(grep -c "eroded = 'particles'" "$W/$run.nml")" = 2 ] || { echo "deck edit failed: eroded"; exit 1; }
    with_eps_convert "$W/$run.nml" 2
    if [ $dim = 2d ]; then
      sed -i "s|^&contact master = 'block', slave = 'rod' /|\&contact master = 'block', slave = 'rod', symmetric = .true. /|" "$W/$run.nml"
      grep -q "symmetric = .true." "$W/$run.nml" || { echo "deck edit failed: symmetric"; exit 1; }
    fi
    if [ -n "${ARTIFICIAL_STRESS:-}" ]; then
      sed -i "s|eps_convert = ${EPS_CONVERT:-}\$|eps_convert = ${EPS_CONVERT:-}, artificial_stress = $ARTIFICIAL_STRESS|" "$W/$run.nml"
      [ "$(grep -c "artificial_stress = $ARTIFICIAL_STRESS" "$W/$run.nml")" = 2 ] || { echo "deck edit failed: artificial_stress"; exit 1; }
    fi
    if [ -n "${EPS_F:-}" ]; then
      sed -i "s|eps_f = 1.5, eps_erode = 2.0|eps_f = $EPS_F, eps_erode = $EPS_F|" "$W/$run.nml"
      [ "$(grep -c "eps_f = $EPS_F, eps_erode = $EPS_F" "$W/$run.nml")" = 2 ] || { echo "deck edit failed: eps_f"; exit 1; }
    fi
  fi
  if [ "${SPH_SWITCH:-0}" = 1 ]; then
    sed -i "s|^&numerics |\&numerics sph_viscosity_switch = .true., |" "$W/$run.nml"
    grep -q "sph_viscosity_switch = .true." "$W/$run.nml" || { echo "deck edit failed: sph_viscosity_switch"; exit 1; }
  fi
  grep -q "velocity = ${vel3}-$v.0" "$W/$run.nml" || { echo "deck edit failed for $v m/s"; exit 1; }
  runs+=("$run")
done
printf '%s\n' "${runs[@]}" | xargs -P "$JOBS" -I{} sh -c "'$W/udar' '$W/{}.nml' > '$W/{}.log' 2>&1 || echo 'FAILED {}'"
mm=$(awk -v h=$H 'BEGIN{print h*1000}')
tags=""
[ "${ERODED:-}" = particles ] && tags+=_particles
[ -n "${EPS_CONVERT:-}" ] && tags+=_convert$EPS_CONVERT
[ -n "${ARTIFICIAL_STRESS:-}" ] && tags+=_art$ARTIFICIAL_STRESS
[ "${SPH_SWITCH:-0}" = 1 ] && tags+=_switch
[ -n "${EPS_F:-}" ] && tags+=_f$EPS_F
if [ $dim = 2d ]; then
  csv=doc/validation/long_rod_2d${tags}_h$mm.csv
else
  csv=doc/validation/long_rod${tags}$([ "$mm" = 1 ] || echo _h$mm).csv
fi
echo "velocity_m_s,mesh_mm,tet_formulation,$([ $dim = 2d ] && echo triangles || echo tets),cycles,wall_s,crater_depth_mm,P_over_L,lanz_odermatt,difference_percent,energy_error" > $csv
form=$(grep -o "tet_formulation = '[a-z_]*'" input/$name/$name.nml | cut -d"'" -f2)
for run in "${runs[@]}"; do
  v=${run#v}; v=${v%%_h*}
  depth=$($PYTHON postproc/penetration.py "$W/$run/$run.h5" --radius 1.25e-3 | tail -1 | awk '{print $2}')
  tets=$(log_value "$W/$run.log" tets)
  cyc=$(log_value "$W/$run.log" cycles)
  wall=$(log_value "$W/$run.log" wall_s)
  err=$(log_value "$W/$run.log" energy_error)
  pl=$(awk -v d="$depth" 'BEGIN{printf "%.3f", d/50.0}')
  diff=$(awk -v p="$pl" -v r="${ref[$v]}" 'BEGIN{printf "%+.1f", 100*(p/r - 1)}')
  echo "$v,$mm,${form:-stabilised},$tets,$cyc,$wall,$depth,$pl,${ref[$v]},$diff,$err" | tee -a $csv
done
# section of the 2 km/s run on the deck's mesh at 30 us, by part and by plastic strain
if [ $dim = 3d ] && [ "$mm" = 1 ] && [ -z "${ERODED:-}" ] && last=$(printf '%s\n' "${runs[@]}" | grep '^v2000'); then
  $PYTHON postproc/section.py "$W/$last/$last.h5" --plane y=0 --color part --time 30 -o doc/validation/long_rod_2000_30us_parts.png
  $PYTHON postproc/section.py "$W/$last/$last.h5" --plane y=0 --color plastic_strain --time 30 -o doc/validation/long_rod_2000_30us_eps.png
fi
echo "results in $csv"
