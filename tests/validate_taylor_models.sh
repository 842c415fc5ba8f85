#!/usr/bin/env bash
# Copper Taylor tests from the experimental record with every strength model
# of the material library (issue 16; part of make validate): axisymmetric
# bars (input/taylor_ofhc_2d/taylor_ofhc_2d.geo at each test's length and
# radius) on a rigid frictionless wall, each model's constants from
# input/materials/ofhc_copper_<model>.nml. Measured final lengths and
# footprints (Banerjee's digitisation of the record, tests/taylor_tests.csv):
# Wilkins and Guinan (1973) at 89-210 m/s, Johnson and Cook (1983) at 190
# m/s, Gust (1982) hot bars at about 720 K. Runs two at a time; the
# final length and footprint (postproc/taylor.py) go to
# doc/validation/taylor_models.csv, one row a run.
#   tests/validate_taylor_models.sh                 (h = 0.2 mm, every test)
#   H=0.1 TESTS="jc190 wg210 gust188" tests/validate_taylor_models.sh   (the mesh check)
#   MODELS="jc za" ...                              (a subset of models)
H=${H:-0.2}
MODELS=${MODELS:-jc za scg mts ptw}
source "$(dirname "$0")/validate_common.sh" taylor_models
tests_csv=tests/taylor_tests.csv
TESTS=${TESTS:-$(tail -n +2 $tests_csv | grep -v '^#' | cut -d, -f1 | tr '\n' ' ')}
runs=()
for t in $TESTS; do
  row=$(grep "^$t," $tests_csv) || { echo "no test $t in $tests_csv"; exit 1; }
  IFS=, read -r name l0 d0 speed temp lf fp t_end source <<< "$row"
  r0=$(awk -v d="$d0" 'BEGIN{printf "%g", d/2}')
  mesh=$W/bar_L${l0}_R${r0}_h$H.msh
  [ -f "$mesh" ] || mesh_checked "$mesh" input/taylor_ofhc_2d/taylor_ofhc_2d.geo \
                      -setnumber h "$H" -setnumber L "$l0" -setnumber R "$r0"
  for model in $MODELS; do
    run=${t}_${model}_h$H
    lib=input/materials/ofhc_copper_$model.nml
    # the deck: the library's material, the test's bar, speed and temperature
    {
      printf "&run title = 'copper Taylor test %s, %s', t_end = %se-6, cycle_print = 5000 /\n" "$t" "$model" "$t_end"
      printf "&mesh file = '%s', scale = 1.0e-3, geometry = 'axisymmetric' /\n" "$mesh"
      cat "$lib"
      printf "&part group = 'rod', material = 'ofhc_copper_%s', velocity = 0.0, -%s, initial_temperature = %s /\n" \
             "$model" "$speed" "$temp"
      printf "&boundary kind = 'rigid_wall', point = 0.0, 0.0, normal = 0.0, 1.0, wall_type = 'frictionless' /\n"
      printf "&output directory = '%s', dt_field = 10.0e-6, dt_history = 1.0e-6 /\n" "$W/$run"
    } > "$W/$run.nml"
    runs+=("$run")
  done
done
meshes_checked
todo=()
for run in "${runs[@]}"; do
  if grep -q '^udar: done: ' "$W/$run.log" 2>/dev/null && [ -f "$W/$run/$run.h5" ]; then
    echo "$run: done before, kept"
  else
    todo+=("$run")
  fi
done
[ ${#todo[@]} = 0 ] || printf '%s\n' "${todo[@]}" | xargs -P "$JOBS" -I{} sh -c "'$W/udar' '$W/{}.nml' > '$W/{}.log' 2>&1 || echo 'FAILED {}'"
csv=doc/validation/taylor_models.csv
[ -f $csv ] || echo "test,model,mesh_mm,triangles,speed_m_s,initial_temperature_K,final_length_mm,measured_length_mm,length_error,footprint_mm,measured_footprint_mm,footprint_error,cycles,energy_error" > $csv
for run in "${runs[@]}"; do
  t=${run%%_*}; rest=${run#*_}; model=${rest%%_*}
  IFS=, read -r name l0 d0 speed temp lf fp t_end source <<< "$(grep "^$t," $tests_csv)"
  m=$($PYTHON postproc/taylor.py "$W/$run/$run.h5" --json)
  line=$($PYTHON - "$m" "$lf" "$fp" <<'EOF'
import json, sys
m = json.loads(sys.argv[1]); lf = float(sys.argv[2]); fp = sys.argv[3]
L, D = 1e3*m['length_m'], 1e3*m['footprint_diameter_m']
fe = '%+.4f' % (D/float(fp) - 1) if fp else ''
print('%.3f,%s,%+.4f,%.3f,%s,%s' % (L, lf, L/lf - 1, D, fp, fe))
EOF
)
  # the row of this test, model and mesh replaces an older one
  sed -i "/^$t,$model,$H,/d" $csv
  echo "$t,$model,$H,$(log_value "$W/$run.log" tets),$speed,$temp,$line,$(log_value "$W/$run.log" cycles),$(log_value "$W/$run.log" energy_error)" | tee -a $csv
done
echo "results in $csv"
