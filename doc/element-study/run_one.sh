#!/bin/bash
# run1.sh name form beta vel tend tpl rho0 [maxcyc]
cd /tmp/el
./mk.sh $1 $6 $2 $3 $4 $5
sed -i "s/^ *dt_field = .*/  dt_field = ${DTF:-5.0e-6}/" $1.nml
[ -n "$8" ] && sed -i "s/^\(&run\)$/\1\n  max_cycles = $8/" $1.nml
timeout ${TMO:-400} /work/wt-elem/bin/udar $1.nml > $1.log 2>&1
/usr/bin/python3 an.py $1 $7 >> results.txt 2>&1
tail -2 results.txt
