#!/bin/bash
# mk.sh name template form beta vel tend  -> deck name.nml
name=$1; tpl=$2; form=$3; beta=$4; vel=$5; tend=$6
sed -e "s/^ *t_end = .*/  t_end = $tend/" -e "s/velocity = 0.0, 0.0, -[0-9.]*/velocity = 0.0, 0.0, -$vel/" \
    -e "/^&numerics/d" -e "s/^ *cycle_print = .*/  cycle_print = 2000/" -e "s/^ *dt_field = .*/  dt_field = 1.0/" \
    -e "s/directory = 'out'/directory = 'out_$name'/" $tpl > $name.nml
echo "&numerics tet_formulation = '$form', stabilisation = $beta /" >> $name.nml
