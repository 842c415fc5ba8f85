#!/usr/bin/env bash
# The seed paper's calculations (part of make validate): the compact steel
# cylinder at 30 degrees with f = 0.18 and f = 0 (Fig. 3), its normal impact
# (3D and axisymmetric), and the yawed W-Ni-Fe rod through a plate (Fig. 4),
# run two at a time;
# the numbers of doc/validation.md 4j-4l go to doc/validation/paper_decks.csv
# and the sections at the paper's times to doc/validation/. Then the
# ricochet deck (not the paper's, the same algorithm at a grazing angle) with
# the default and the plain element: doc/validation/ricochet.csv.
source "$(dirname "$0")/validate_common.sh" paper
# deck, folder, name of the projectile part, its initial axis (into the plate)
decks=("oblique_cylinder oblique_cylinder cylinder 0.5 0 -0.8660254"
       "oblique_cylinder_f0 oblique_cylinder cylinder 0.5 0 -0.8660254"
       "normal_cylinder normal_cylinder cylinder 0 0 -1"
       "normal_cylinder_2d normal_cylinder_2d cylinder 0 -1 0"
       "yawed_rod yawed_rod rod 0.70710678 0 -0.70710678")
for d in "${decks[@]}"; do
  set -- $d
  mkdir -p "$W/$1"
  # meshed here from the .geo, not copied: a stale input/*.msh once stood
  # for the wrong mesh (validation.md 4j)
  mesh_checked "$W/$1/$2.msh" "input/$2/$2.geo"
  sed "s|directory = '[^']*'|directory = 'out'|" "input/$2/$1.nml" > "$W/$1/$1.nml"
done
mkdir -p "$W/ricochet"
mesh_checked "$W/ricochet/ricochet.msh" input/ricochet/ricochet.geo
meshes_checked
printf '%s\n' "${decks[@]}" | cut -d' ' -f1 | \
  xargs -P "$JOBS" -I{} sh -c "cd '$W/{}' && '$W/udar' {}.nml > run.log 2>&1 || echo 'FAILED {}'"
csv=doc/validation/paper_decks.csv
echo "deck,t_us,crater_on_axis_mm,projectile_left_along_axis_mm,intact_along_axis_mm,crater_deepest_mm,crater_rim_diameter_mm,projectile_velocity_along_axis_m_s,eroded_projectile,eroded_plate,energy_error,wall_s" > $csv
for d in "${decks[@]}"; do
  set -- $d
  line=$($PYTHON postproc/penetration.py "$W/$1/out/$1.h5" --rod $3 --target plate --radius 0.5e-3 --axis $4 $5 $6 | tail -1)
  err=$(log_value "$W/$1/run.log" energy_error)
  wall=$(log_value "$W/$1/run.log" wall_s)
  echo "$line" | awk -v n=$1 -v e=$err -v w=$wall '{print n","$1","$2","$3","$8","$9","$10","$4","$6","$7","e","w}' | tee -a $csv
done
S="$PYTHON postproc/section.py --plane y=0.3mm"
for f in f18:oblique_cylinder f0:oblique_cylinder_f0; do
  n=${f%%:*}; run=${f#*:}; fr="f = 0.18"; [ $n = f0 ] && fr="f = 0"
  $S "$W/$run/out/$run.h5" --time 12 --color part --xlim -20 40 --ylim -25 20 \
     --title "Fig. 3 deck (30 deg, 3 km/s), $fr, 12 us, section y = 0.3 mm" \
     -o doc/validation/oblique_cylinder_${n}_12us_parts.png
  $S "$W/$run/out/$run.h5" --time 12 --color fracture_state --xlim -20 40 --ylim -25 20 \
     --title "Fig. 3 deck (30 deg, 3 km/s), $fr, 12 us: 0 intact, 1 fractured" \
     -o doc/validation/oblique_cylinder_${n}_12us_fracture.png
done
$S "$W/oblique_cylinder/out/oblique_cylinder.h5" --time 0 --color part --xlim -20 40 --ylim -25 20 \
   --title "Fig. 3 deck (30 deg, 3 km/s), 0 us" -o doc/validation/oblique_cylinder_0us_parts.png
$S "$W/normal_cylinder/out/normal_cylinder.h5" --time 30 --color part --xlim -30 30 --ylim -30 15 \
   --title "normal impact, 3 km/s, f = 0.18, 30 us, section y = 0.3 mm" -o doc/validation/normal_cylinder_30us_parts.png
$S "$W/normal_cylinder/out/normal_cylinder.h5" --time 9 --color fracture_state --xlim -30 30 --ylim -30 15 \
   --title "normal impact, 3 km/s, 9 us: 0 intact, 1 fractured" -o doc/validation/normal_cylinder_9us_fracture.png
for t in 0 16 44.03; do
  $S "$W/yawed_rod/out/yawed_rod.h5" --time $t --color part --xlim -30 80 --ylim -70 30 \
     --title "Fig. 4 deck (W-Ni-Fe rod, 2 km/s, 35 deg obliquity, 10 deg yaw), $t us" \
     -o doc/validation/yawed_rod_${t%%.*}us_parts.png
done
$S "$W/yawed_rod/out/yawed_rod.h5" --time 16 --color plastic_strain --vmax 2 --xlim -30 80 --ylim -70 30 \
   --title "Fig. 4 deck, 16 us: plastic strain" -o doc/validation/yawed_rod_16us_eps.png
echo "results in $csv"

# Ricochet (validation.md 4d): when the rod leaves the plate (last cycle with a
# contact force) and its centre of mass velocity over the last microsecond,
# from the history, with the default element and the plain one
for form in stabilised plain; do
  sed -e "s|directory = '[^']*'|directory = 'out_$form'|" input/ricochet/ricochet.nml > "$W/ricochet/$form.nml"
  printf "&numerics tet_formulation = '%s' /\n" $form >> "$W/ricochet/$form.nml"
done
printf '%s\n' stabilised plain | \
  xargs -P "$JOBS" -I{} sh -c "cd '$W/ricochet' && '$W/udar' {}.nml > {}.log 2>&1 || echo 'FAILED ricochet {}'"
csv=doc/validation/ricochet.csv
echo "tet_formulation,cycles,leaves_plate_us,rod_com_velocity_x_m_s,rod_com_velocity_z_m_s,energy_error,wall_s" > $csv
for form in stabilised plain; do
  log="$W/ricochet/$form.log"
  $PYTHON - "$W/ricochet/out_$form/${form}_history.csv" "$form" \
    "$(log_value "$log" cycles)" "$(log_value "$log" energy_error)" "$(log_value "$log" wall_s)" <<'PY' | tee -a $csv
import sys, numpy as np
sys.path.insert(0, 'postproc')
import udar_results
path, form, cycles, err, wall = sys.argv[1:]
h = udar_results.read_history(path)
t = h['time']
touching = np.nonzero(h['contact_normal_rod_on_plate'] > 0)[0]
late = t >= t[-1] - 1e-6
vx = np.polyfit(t[late], h['com_x_rod'][late], 1)[0]
vz = np.polyfit(t[late], h['com_z_rod'][late], 1)[0]
print("%s,%s,%.1f,%.1f,%.1f,%s,%s" % (form, cycles, 1e6 * t[touching[-1]], vx, vz, err, wall))
PY
done
for t in 0 10 30; do
  $PYTHON postproc/section.py "$W/ricochet/out_stabilised/stabilised.h5" --plane y=0 --time $t --color plastic_strain \
     --title "ricochet, 800 m/s at 15 deg, $t us: plastic strain" -o doc/validation/ricochet_${t}us.png
done
echo "results in $csv"
