#!/usr/bin/env bash
# make bench: ns per element-cycle and peak memory per element on the OFHC
# copper Taylor bar (Johnson-Cook + Mie-Grueneisen, anti-locking on and off)
# at about 20k and 200k tetrahedra. Not a test: the machine is shared and
# noisy, so compare ratios measured in one run. Figures are printed and
# saved in bench/results/.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
mkdir -p bench/results
out=bench/results/bench-$(date +%Y%m%d-%H%M%S).txt
{
  echo "# udar bench $(date -Iseconds) on $(hostname), $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
  echo "# version $(bin/udar --version), commit $(git rev-parse --short HEAD 2>/dev/null || echo unknown)"
  printf '%-10s %-12s %10s %8s %12s %14s %12s\n' case anti_locking tets cycles wall_s ns_per_el_cyc bytes_per_el
} | tee "$out"
for spec in "20k 0.42 300" "200k 0.19 60"; do
  set -- $spec
  name=$1 h=$2 ncyc=$3
  gmsh -3 -v 0 -setnumber h "$h" input/taylor_ofhc/taylor_ofhc.geo -o "$W/bar_$name.msh"
  for al in .true. .false.; do
    deck=$W/bench_${name}_$al.nml
    sed -e "s|file = 'taylor_ofhc.msh'|file = '$W/bar_$name.msh'|" \
        -e "s|directory = 'out'|directory = '$W/out'|" \
        -e "s|cycle_print = 500|cycle_print = 100000, max_cycles = $ncyc|" \
        -e "s|dt_field = 10.0e-6|dt_field = 0.0|" -e "s|dt_history = 0.2e-6|dt_history = 1.0|" \
        input/taylor_ofhc/taylor_ofhc.nml > "$deck"
    printf '&numerics anti_locking = %s /\n' "$al" >> "$deck"
    /usr/bin/time -f '%M' -o "$W/rss" bin/udar "$deck" > "$W/log" 2>&1
    tets=$(grep -o '[0-9]* tetrahedra' "$W/log" | cut -d' ' -f1)
    ns=$(grep -o '[0-9.]* ns per element-cycle' "$W/log" | cut -d' ' -f1)
    wall=$(grep -o '[0-9.]* s wall' "$W/log" | cut -d' ' -f1)
    rss_kb=$(cat "$W/rss")
    printf '%-10s %-12s %10s %8s %12s %14s %12d\n' "ofhc_$name" "${al//./}" "$tets" "$ncyc" "$wall" "$ns" \
      $(( rss_kb * 1024 / tets )) | tee -a "$out"
  done
done
echo "# bytes_per_el is the peak resident memory of the whole process over the tetrahedron count" | tee -a "$out"
echo "saved in $out"
