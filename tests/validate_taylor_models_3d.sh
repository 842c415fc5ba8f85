#!/usr/bin/env bash
# The default make run deck's test in 3D with every copper model of the
# material library (issue 16; part of make validate): Johnson and Cook's
# 1983 Taylor test (25.4 by 7.62 mm, 190 m/s, rigid frictionless wall,
# measured 16.21 mm long, footprint 13.56 mm) on input/taylor_ofhc's
# quarter mesh (h = 0.45 mm, the deck's own) with the default element, each
# model's constants from input/materials/ofhc_copper_<model>.nml, 80 us.
# Final length and footprint (postproc/taylor.py) go to
# doc/validation/taylor_models_3d.csv, one row a model.
#   tests/validate_taylor_models_3d.sh
#   MODELS="jc mts" tests/validate_taylor_models_3d.sh
MODELS=${MODELS:-jc za scg mts ptw}
source "$(dirname "$0")/validate_common.sh" taylor_models_3d
mesh=$W/taylor_ofhc_h0.45.msh
mesh_checked "$mesh" input/taylor_ofhc/taylor_ofhc.geo -setnumber h 0.45
meshes_checked
for model in $MODELS; do
  {
    printf "&run title = 'copper Taylor test jc190, 3D, %s', t_end = 80.0e-6, cycle_print = 5000 /\n" "$model"
    printf "&mesh file = '%s', scale = 1.0e-3 /\n" "$mesh"
    cat "input/materials/ofhc_copper_$model.nml"
    printf "&part group = 'rod', material = 'ofhc_copper_%s', velocity = 0.0, 0.0, -190.0 /\n" "$model"
    printf "&boundary kind = 'symmetry', surface = 'sym_x' /\n&boundary kind = 'symmetry', surface = 'sym_y' /\n"
    printf "&boundary kind = 'rigid_wall', point = 0.0, 0.0, 0.0, normal = 0.0, 0.0, 1.0, wall_type = 'frictionless' /\n"
    printf "&output directory = '%s', dt_field = 20.0e-6, dt_history = 1.0e-6 /\n" "$W/$model"
  } > "$W/$model.nml"
done
printf '%s\n' $MODELS | xargs -P "$JOBS" -I{} sh -c "'$W/udar' '$W/{}.nml' > '$W/{}.log' 2>&1 || echo 'FAILED {}'"
csv=doc/validation/taylor_models_3d.csv
[ -f $csv ] || echo "model,tets,final_length_mm,measured_length_mm,length_error,footprint_mm,measured_footprint_mm,footprint_error,cycles,energy_error" > $csv
for model in $MODELS; do
  m=$($PYTHON postproc/taylor.py "$W/$model/$model.h5" --json)
  line=$($PYTHON - "$m" <<'PY'
import json, sys
m = json.loads(sys.argv[1])
L, D = 1e3*m['length_m'], 1e3*m['footprint_diameter_m']
print('%.3f,16.21,%+.4f,%.3f,13.56,%+.4f' % (L, L/16.21 - 1, D, D/13.56 - 1))
PY
)
  sed -i "/^$model,/d" $csv
  echo "$model,$(log_value "$W/$model.log" tets),$line,$(log_value "$W/$model.log" cycles),$(log_value "$W/$model.log" energy_error)" | tee -a $csv
done
echo "results in $csv"
