#!/usr/bin/env bash
# Taylor bars (part of make validate, tests/validate.sh): (Wilkins-Guinan; OFHC copper, Johnson and Cook 1983) at several
# mesh sizes, with the default element ('stabilised') and the plain
# tetrahedron, run two at a time; the measured final
# length, footprint and gap to the wall (postproc/taylor.py) go to doc/validation/taylor.csv and the pictures to
# doc/validation/. Every mesh is first compared with doc/validation/meshes.csv.
#   validate_taylor.sh [3d | 2d]   (default 3d; 2d: the axisymmetric bars,
#   doc/validation/taylor_2d.csv, down to 0.1 mm)
study=${1:-3d}
source "$(dirname "$0")/validate_common.sh" taylor_$study
# case  geo  deck  mesh sizes (mm)
if [ "$study" = 2d ]; then
cases="wg2d tests/regression/taylor_wg_2d/taylor_wg_2d.geo tests/regression/taylor_wg_2d/taylor_wg_2d.nml 0.6,0.4,0.3,0.2,0.1
ofhc2d input/taylor_ofhc_2d/taylor_ofhc_2d.geo input/taylor_ofhc_2d/taylor_ofhc_2d.nml 0.6,0.45,0.3,0.2,0.1"
else
cases="wg tests/regression/taylor_wg/taylor_wg.geo tests/regression/taylor_wg/taylor_wg.nml 0.6,0.4,0.3
ofhc input/taylor_ofhc/taylor_ofhc.geo input/taylor_ofhc/taylor_ofhc_jc.nml 0.6,0.45,0.3"
fi
jobs=()
while read -r name geo deck sizes; do
  for h in ${sizes//,/ }; do
    mesh_checked "$W/${name}_h$h.msh" "$geo" -setnumber h "$h"
    for form in stabilised plain; do
      run=${name}_h${h}_$form
      sed -e "s|file = '[^']*'|file = '$W/${name}_h$h.msh'|" -e "s|directory = 'out'|directory = '$W/$run'|" \
          -e "/^&numerics/d" "$deck" > "$W/$run.nml"
      printf "&numerics tet_formulation = '%s' /\n" "$form" >> "$W/$run.nml"
      jobs+=("$run")
    done
  done
done <<< "$cases"
meshes_checked
printf '%s\n' "${jobs[@]}" | xargs -P "$JOBS" -I{} sh -c "'$W/udar' '$W/{}.nml' > '$W/{}.log' 2>&1 || echo 'FAILED {}'"
csv=doc/validation/taylor.csv
[ "$study" = 2d ] && csv=doc/validation/taylor_2d.csv
echo "case,mesh_mm,tet_formulation,$([ "$study" = 2d ] && echo triangles || echo tets),cycles,wall_s,final_length_mm,footprint_diameter_mm,energy_error,gap_mm" > $csv
for run in "${jobs[@]}"; do
  name=${run%%_h*}; rest=${run#*_h}; h=${rest%%_*}; form=${run##*_}
  m=$($PYTHON postproc/taylor.py "$W/$run/$run.h5" --json)
  L=$($PYTHON -c "import json,sys; m=json.loads(sys.argv[1]); print('%.3f' % (1e3*m['length_m']))" "$m")
  D=$($PYTHON -c "import json,sys; m=json.loads(sys.argv[1]); print('%.3f' % (1e3*m['footprint_diameter_m']))" "$m")
  G=$($PYTHON -c "import json,sys; m=json.loads(sys.argv[1]); print('%.3f' % (1e3*m['gap_m']))" "$m")
  tets=$(log_value "$W/$run.log" tets)
  cyc=$(log_value "$W/$run.log" cycles)
  wall=$(log_value "$W/$run.log" wall_s)
  err=$(log_value "$W/$run.log" energy_error)
  echo "$name,$h,$form,$tets,$cyc,$wall,$L,$D,$err,$G" | tee -a $csv
done
# pictures of the finest runs with the default element
for name in $(cut -d' ' -f1 <<< "$cases"); do
  run=$(printf '%s\n' "${jobs[@]}" | grep "^${name}_" | grep "_stabilised" | tail -1)
  $PYTHON postproc/section.py "$W/$run/$run.h5" --plane y=0 --color plastic_strain --mirror -o doc/validation/${name}_section.png
  $PYTHON postproc/plot_history.py "$W/$run/${run}_history.csv" -o doc/validation/${name}_history.png
done
echo "results in $csv and doc/validation/*.png"
