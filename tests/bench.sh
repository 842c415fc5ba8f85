#!/usr/bin/env bash
# make bench: ns per element-cycle and peak memory per element on the OFHC
# copper Taylor bar (Johnson-Cook + Mie-Grueneisen; the default element, the
# nodal-averaged one of 0.4 and the plain one) at about 20k and 200k
# tetrahedra; memory per element at 3k, 200k and 1M
# tetrahedra on 1 and 2 ranks; the 2-rank speedup on the 200k bar; a bar
# whose elements become particles. Not a test: the machine is shared and
# noisy, so compare ratios measured in one run. Figures are printed and saved in
# bench/results/.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
PYTHON=${PYTHON:-/usr/bin/python3}
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
mkdir -p bench/results
out=bench/results/bench-$(date +%Y%m%d-%H%M%S).txt
{
  echo "# udar bench $(date -Iseconds) on $(hostname), $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
  echo "# version $(bin/udar --version), commit $(git rev-parse --short HEAD 2>/dev/null || echo unknown)"
  printf '%-10s %-12s %10s %8s %12s %14s %12s %12s\n' case element tets cycles wall_s ns_per_el_cyc bytes_per_el domain_b_el
} | tee "$out"
for spec in "20k 0.42 300" "200k 0.19 60"; do
  set -- $spec
  name=$1 h=$2 ncyc=$3
  gmsh -3 -v 0 -setnumber h "$h" input/taylor_ofhc/taylor_ofhc.geo -o "$W/bar_$name.msh"
  for al in stabilised nodal plain; do
    deck=$W/bench_${name}_$al.nml
    sed -e "s|file = 'taylor_ofhc.msh'|file = '$W/bar_$name.msh'|" \
        -e "s|directory = 'out'|directory = '$W/out'|" \
        -e "s|cycle_print = 500|cycle_print = 100000, max_cycles = $ncyc|" \
        -e "s|dt_field = 10.0e-6|dt_field = 0.0|" -e "s|dt_history = 0.2e-6|dt_history = 1.0|" \
        input/taylor_ofhc/taylor_ofhc_jc.nml > "$deck"
    printf "&numerics tet_formulation = '%s' /\n" "$al" >> "$deck"
    /usr/bin/time -f '%M' -o "$W/rss" bin/udar "$deck" > "$W/log" 2>&1
    tets=$(grep -o '[0-9]* tetrahedra' "$W/log" | cut -d' ' -f1)
    ns=$(grep -o '[0-9.]* ns per element-cycle' "$W/log" | cut -d' ' -f1)
    wall=$(grep -o '[0-9.]* s wall' "$W/log" | cut -d' ' -f1)
    rss_kb=$(cat "$W/rss")
    dom=$(grep -o 'domains [0-9]* bytes per element' "$W/log" | awk '{print $2}')
    printf '%-10s %-12s %10s %8s %12s %14s %12d %12s\n' "ofhc_$name" "$al" "$tets" "$ncyc" "$wall" "$ns" \
      $(( rss_kb * 1024 / tets )) "$dom" | tee -a "$out"
  done
done
echo "# bytes_per_el is the peak resident memory of the whole process over the tetrahedron count;" \
     "domain_b_el the bytes of the domain's own arrays (udar_domain domain_bytes) over it" | tee -a "$out"

# ---- memory: the bar at about 3k (the fixed cost of MPI and HDF5), 200k and
# 1M tets on 1 and 2 ranks, 5 cycles each (udar's 'memory:' log lines, largest
# rank): the start-up peak (reading, partitioning and distributing the mesh),
# the resident memory after the run (the steady footprint) and the process
# peak; the per-element slope between 200k and 1M is the cost of an element
# without the fixed cost
if [ "$(id -u)" = 0 ]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
export OMPI_MCA_rmaps_base_oversubscribe=1
gmsh -3 -v 0 -setnumber h 0.8 input/taylor_ofhc/taylor_ofhc.geo -o "$W/bar_3k.msh"
gmsh -3 -v 0 -setnumber h 0.108 input/taylor_ofhc/taylor_ofhc.geo -o "$W/bar_1m.msh"
echo "# memory: OFHC bar, anti-locking on, 5 cycles; bytes per element = bytes / global tets; largest rank" | tee -a "$out"
printf '%-10s %5s %8s %8s %10s %10s %10s %10s %8s %8s\n' case ranks nodes tets startup_MiB resident_MiB peak_MiB \
  peak_b_el domain global | tee -a "$out"
declare -A peak_mib tets_of
for name in 3k 200k 1m; do
  deck=$W/mem_$name.nml
  sed -e "s|file = 'taylor_ofhc.msh'|file = '$W/bar_$name.msh'|" \
      -e "s|directory = 'out'|directory = '$W/out'|" \
      -e "s|cycle_print = 500|cycle_print = 100000, max_cycles = 5|" \
      -e "s|dt_field = 10.0e-6|dt_field = 0.0|" -e "s|dt_history = 0.2e-6|dt_history = 1.0|" \
      input/taylor_ofhc/taylor_ofhc_jc.nml > "$deck"
  for n in 1 2; do
    mpirun -np $n bin/udar "$deck" > "$W/log" 2>&1
    nodes=$(grep -o '[0-9]* nodes, [0-9]* tetrahedra' "$W/log" | awk '{print $1}')
    tets=$(grep -o '[0-9]* tetrahedra' "$W/log" | head -1 | cut -d' ' -f1)
    su=$(sed -n 's/.*start-up peak \([0-9.]*\) MiB.*/\1/p' "$W/log")
    res=$(sed -n 's/.*resident after the run \([0-9.]*\) MiB.*/\1/p' "$W/log")
    pk=$(sed -n 's/.*process peak \([0-9.]*\) MiB = \([0-9]*\) bytes.*/\1/p' "$W/log")
    pkb=$(sed -n 's/.*process peak \([0-9.]*\) MiB = \([0-9]*\) bytes.*/\2/p' "$W/log")
    dom=$(grep -o 'domains [0-9]* bytes per element' "$W/log" | awk '{print $2}')
    glob=$(grep -o 'global mesh domain [0-9]* bytes per element' "$W/log" | awk '{print $4}')
    printf '%-10s %5d %8s %8s %10s %10s %10s %10s %8s %8s\n' "ofhc_$name" $n "$nodes" "$tets" "$su" "$res" "$pk" \
      "$pkb" "$dom" "$glob" | tee -a "$out"
    peak_mib[$name$n]=$pk; tets_of[$name]=$tets
  done
done
for n in 1 2; do
  echo "${peak_mib[200k$n]} ${peak_mib[1m$n]} ${tets_of[200k]} ${tets_of[1m]} ${peak_mib[3k$n]}" | awk -v n=$n \
    '{printf "memory slope on %d rank(s), 200k -> 1M: %.0f bytes per element (largest rank); fixed cost (3k bar) %.1f MiB\n",
      n, ($2-$1)*1048576/($4-$3), $5}' | tee -a "$out"
done
echo "# startup: peak while reading, partitioning and distributing the mesh; resident: after the run;" \
     "peak: whole process; domain: the local domains of all ranks (ghosts included), global: the mesh domain" \
     "every rank holds at start-up (bytes per element)" | tee -a "$out"

# ---- parallel: the 200k bar (anti-locking on) on 1 and 2 ranks, alternated
# four times; speedup from the cycle-loop time, of the medians and of the
# best runs (single rounds scatter by +-0.3 on a shared host)
deck=$W/bench_200k_stabilised.nml
echo "# parallel: 200k bar, default element, 60 cycles; ns per element-cycle = loop wall time / (global elements x cycles)" | tee -a "$out"
: > "$W/par"
for rep in 1 2 3 4; do
  for n in 1 2; do
    mpirun -np $n bin/udar "$deck" > "$W/log" 2>&1
    ns=$(grep -o '[0-9.]* ns per element-cycle' "$W/log" | cut -d' ' -f1)
    wall=$(grep -o '[0-9.]* s wall' "$W/log" | cut -d' ' -f1)
    printf 'ranks %d  run %d  wall %8s s  %8s ns per element-cycle\n' $n $rep "$wall" "$ns" | tee -a "$out"
    echo "$n $ns" >> "$W/par"
  done
done
awk '{v[$1, ++c[$1]] = $2}
     function med(n,   i, j, t, a) { for (i = 1; i <= c[n]; i++) a[i] = v[n, i]
       for (i = 1; i <= c[n]; i++) for (j = i + 1; j <= c[n]; j++) if (a[j] < a[i]) { t = a[i]; a[i] = a[j]; a[j] = t }
       return (c[n] % 2) ? a[(c[n] + 1) / 2] : (a[c[n] / 2] + a[c[n] / 2 + 1]) / 2 }
     function best(n,   i, b) { b = v[n, 1]; for (i = 2; i <= c[n]; i++) if (v[n, i] < b) b = v[n, i]; return b }
     END { printf "speedup on 2 ranks %.2f of the medians (%.1f / %.1f ns), %.2f of the best runs; parallel efficiency %.0f %% (medians)\n",
             med(1) / med(2), med(1), med(2), best(1) / best(2), 50 * med(1) / med(2) }' "$W/par" | tee -a "$out"

# ---- particles: the OFHC bar converting at a total strain of 1.0 (the
# deck of regression/taylor_particles, 7,316 tets, to 80 us): elements and
# particles together per element-cycle, the particles' count at the end
sed -e "s|directory = 'out'|directory = '$W/part'|" \
    tests/regression/taylor_ofhc_baseline/taylor_particles.nml > "$W/particles.nml"
sed -i "s|file = '|file = '$ROOT/tests/regression/taylor_ofhc_baseline/|" "$W/particles.nml"
bin/udar "$W/particles.nml" > "$W/log" 2>&1
printf 'particles: OFHC bar converting at 1.0, %s tets, %s cycles, %s ns per element-cycle, %s elements converted\n' \
  "$(grep -o '[0-9]* tetrahedra' "$W/log" | head -1 | cut -d' ' -f1)" \
  "$(grep -o 'done: [0-9]* cycles' "$W/log" | awk '{print $2}')" \
  "$(grep -o '[0-9.]* ns per element-cycle' "$W/log" | cut -d' ' -f1)" \
  "$(sed -n 's/.*, \([0-9]*\) eroded;.*/\1/p' "$W/log" | tail -1)" | tee -a "$out"

# ---- projected scaling from the partition alone: a 1M-tet bar split into
# 2..64 parts; ghost-element work and halo sizes (udar --check --ranks N)
sed -e "s|file = 'taylor_ofhc.msh'|file = '$W/bar_1m.msh'|" input/taylor_ofhc/taylor_ofhc_jc.nml > "$W/bar_1m.nml"
scaling=doc/scaling.md
{
  echo "# Projected scaling (written by \`make bench\`)"
  echo
  echo "From the partition alone, without running: the OFHC Taylor bar meshed with"
  echo "$(bin/udar --check "$W/bar_1m.nml" 2>&1 | grep -o '[0-9]* tetrahedra') (gmsh h = 0.108 mm), split by METIS as a run on N ranks"
  echo "would split it. Ghost work: elements each rank computes redundantly, over"
  echo "the mesh's elements (all ranks) and over the rank's own (worst rank). Halo:"
  echo "ghost nodes whose values a rank receives each exchange; per cycle a rank"
  echo "receives 8 reals per ghost node with anti-locking (x, v, nodal J and p)."
  echo "Measured $(date -I) on $(hostname) with udar $(bin/udar --version | awk '{print $2}')."
  echo
  echo "| ranks | edge cut (faces) | imbalance | ghost work, all | ghost work, worst rank | ghost nodes, all | ghost nodes, max per rank | received per cycle, max |"
  echo "|---:|---:|---:|---:|---:|---:|---:|---:|"
} > "$scaling.tmp"
echo "# projected scaling, 1M-tet bar (partition only)" | tee -a "$out"
for n in 2 4 8 16 64; do
  bin/udar --check --ranks $n "$W/bar_1m.nml" > "$W/log" 2>&1
  cut=$(grep -o 'edge cut [0-9]*' "$W/log" | awk '{print $3}')
  imb=$(grep -o 'load imbalance *[0-9.]*' "$W/log" | awk '{print $3}')
  line=$(grep 'decomposition cost' "$W/log")
  echo "$line" | tee -a "$out"
  all=$(echo "$line" | sed -n 's/.*work +\( *[0-9.]*\) % in all.*/\1/p' | xargs)
  worst=$(echo "$line" | sed -n 's/.*worst rank +\( *[0-9.]*\) %.*/\1/p' | xargs)
  gall=$(echo "$line" | sed -n 's/.*halo \([0-9]*\) ghost nodes in all.*/\1/p')
  gmax=$(echo "$line" | sed -n 's/.*at most \([0-9]*\) on a rank.*/\1/p')
  kib=$(echo "$line" | sed -n 's/.*(\( *[0-9.]*\) KiB received.*/\1/p' | xargs)
  echo "| $n | $cut | $imb | $all % | $worst % | $gall | $gmax | $kib KiB |" >> "$scaling.tmp"
done
mv "$scaling.tmp" "$scaling"
echo "saved in $out and $scaling"

# ---- contact: the 3 km/s rod onto a plate (tests/regression/rod_3kms) at three
# mesh sizes (about 4x the surface nodes each): time per slave node-cycle and
# the contact's share of the cycle; linear search cost = constant ns per node
echo "# contact: steel rod onto a plate at 3 km/s, 1 us; contact time per slave node-cycle" | tee -a "$out"
for h in 1.2e-3 0.6e-3 0.3e-3; do
  gmsh -3 -v 0 -setnumber h $h tests/regression/rod_3kms/rod_3kms.geo -o "$W/rod.msh"
  sed -e "s|file = 'rod_3kms.msh'|file = '$W/rod.msh'|" -e "s|directory = 'out'|directory = '$W/out'|" \
      -e "s|dt_field = 0.25e-6|dt_field = 0.0|" tests/regression/rod_3kms/rod_3kms.nml > "$W/rod.nml"
  bin/udar "$W/rod.nml" > "$W/log" 2>&1
  tets=$(grep -o '[0-9]* tetrahedra' "$W/log" | head -1 | cut -d' ' -f1)
  printf 'h %-7s %8s tets  %s  %s\n' "$h" "$tets" "$(grep '^contact:' "$W/log")" \
    "$(grep -o 'full searches in [0-9]* of [0-9]*' "$W/log")" | tee -a "$out"
  if [ $h = 0.6e-3 ]; then
    # the same run with a full search every cycle: what local tracking saves
    sed -i "s|^&contact \(.*\) /|\&contact \1, tracking = .false. /|" "$W/rod.nml"
    bin/udar "$W/rod.nml" > "$W/log" 2>&1
    printf 'h %-7s %8s tets  %s  (tracking off)\n' "$h" "$tets" "$(grep '^contact:' "$W/log")" | tee -a "$out"
  fi
done

# ---- the contact on 1, 2 and 4 ranks, and its projection to 64 (doc/scaling.md)
tests/bench_contact.sh "$out"

# ---- side by side with OpenRadioss (issue 12): the full OFHC cylinder
# (bench/taylor_full.geo) at h 0.62 and 0.31 mm, 190 m/s to 80 us: cycles
# and final length / footprint diameter. OpenRadioss's figures are from the
# project's measurement (OpenRadioss built from source at commit
# bd4557ba7503, gfortran 12.2, default element time step, scale 0.9, on this
# kind of machine, 2026-11-24; doc/performance.md).
echo "# side by side with OpenRadioss: full OFHC cylinder, 190 m/s, 80 us" | tee -a "$out"
printf '%-7s %-22s %9s %9s %8s %16s %16s %10s\n' mesh element tets cycles ns "udar Lf/Dm mm" "OpenRadioss" "OR cycles" | tee -a "$out"
declare -A or_ref=([coarse_plain]="17.23/12.81 3324" [coarse_stabilised]="17.32/14.48 5998" \
                   [fine_plain]="17.38/13.57 9865" [fine_stabilised]="17.35/14.68 12995")
for spec in "coarse 0.62" "fine 0.31"; do
  set -- $spec
  # gmsh 4.8.4's 3D mesh of this .geo changes with its working folder's
  # path, the size of its environment and its threads (measured: the
  # memory layout steers it), so it is made in one fixed folder with an
  # empty environment and one thread, the same files from any caller
  mesh_dir=/tmp/udar-bench-mesh
  rm -rf "$mesh_dir"; mkdir -p "$mesh_dir"
  cp bench/taylor_full.geo "$mesh_dir/"
  (cd "$mesh_dir" && env -i PATH=/usr/bin:/bin gmsh -3 -v 0 -nt 1 -setnumber h $2 -format msh22 taylor_full.geo \
     -o full_$1.msh)
  mv "$mesh_dir/full_$1.msh" "$W/"; rm -rf "$mesh_dir"
  for form in stabilised plain; do
    sed -e "s|file = 'taylor_ofhc.msh'|file = '$W/full_$1.msh'|" -e "/surface = 'sym_/d" \
        -e "s|directory = 'out'|directory = '$W/peer', case_name = '$1_$form'|" \
        -e "s|cycle_print = 500|cycle_print = 1000000|" -e "s|dt_field = 10.0e-6|dt_field = 80.0e-6|" \
        input/taylor_ofhc/taylor_ofhc_jc.nml > "$W/peer.nml"
    printf "&numerics tet_formulation = '%s' /\n" "$form" >> "$W/peer.nml"
    bin/udar "$W/peer.nml" > "$W/log" 2>&1
    tets=$(grep -o '[0-9]* tetrahedra' "$W/log" | head -1 | cut -d' ' -f1)
    cyc=$(grep -o 'done: [0-9]* cycles' "$W/log" | awk '{print $2}')
    ns=$(grep -o '[0-9.]* ns per element-cycle' "$W/log" | cut -d' ' -f1)
    m=$($PYTHON postproc/taylor.py "$W/peer/$1_$form.h5" | grep -o 'length_m=[0-9.e-]* footprint_diameter_m=[0-9.e-]*' | \
        awk -F'[= ]' '{printf "%.2f/%.2f", 1000*$2, 1000*$4}')
    set -- $1 $2 ${or_ref[$1_$form]}
    printf '%-7s %-22s %9s %9s %8s %16s %16s %10s\n' $1 "$form" "$tets" "$cyc" "$ns" "$m" "$3" "$4" | tee -a "$out"
    set -- $1 $2
  done
done
echo "# OpenRadioss: 'plain' rows against its default tetrahedron, 'stabilised' against Itetra4=3 (nodal pressure)" | tee -a "$out"

# ---- 2D (issue 14) against 3D at the same mesh size, default element: a
# deck run to its end on a mesh of size H, with one field step at T_END;
# sets els, cyc, ns, wall (cost per element-cycle, cycles, time to solution)
#   full_run H MODEL DECK_PATH_WITHOUT_EXTENSION CASE_NAME T_END
full_run() {
  gmsh -3 -v 0 -setnumber h "$1" "${3%_jc}.geo" -o "$W/$4.msh"   # (a _jc deck shares its mesh)
  sed -e "s|file = '[^']*.msh'|file = '$W/$4.msh'|" \
      -e "s|directory = 'out'|directory = '$W/twod', case_name = '$4'|" \
      -e "s|cycle_print = 500|cycle_print = 1000000|" -e "s|dt_field = 10.0e-6|dt_field = $5|" \
      "$3.nml" > "$W/twod.nml"
  bin/udar "$W/twod.nml" > "$W/log" 2>&1
  els=$(grep -o 'start: [0-9]* elements' "$W/log" | awk '{print $2}')
  cyc=$(grep -o 'done: [0-9]* cycles' "$W/log" | awk '{print $2}')
  ns=$(grep -o '[0-9.]* ns per element-cycle' "$W/log" | cut -d' ' -f1)
  wall=$(grep -o '[0-9.]* s wall' "$W/log" | cut -d' ' -f1)
}
# the OFHC bar, Johnson-Cook in both (input/taylor_ofhc/taylor_ofhc_jc quarter model, input/taylor_ofhc_2d
# axisymmetric), 80 us: final length and footprint
echo "# 2D against 3D: OFHC bar, 190 m/s, 80 us, default element; time to solution = wall" | tee -a "$out"
printf '%-5s %-14s %9s %9s %8s %9s %16s\n' h model elements cycles ns wall_s "Lf/Dm mm" | tee -a "$out"
for spec in "0.45 3d input/taylor_ofhc/taylor_ofhc_jc" "0.45 2d input/taylor_ofhc_2d/taylor_ofhc_2d" \
            "0.2 2d input/taylor_ofhc_2d/taylor_ofhc_2d"; do
  set -- $spec
  case_name=ofhc_$2_h$1
  full_run "$1" "$2" "$3" "$case_name" 80.0e-6
  m=$($PYTHON postproc/taylor.py "$W/twod/$case_name.h5" | grep -o 'length_m=[0-9.e-]* footprint_diameter_m=[0-9.e-]*' | \
      awk -F'[= ]' '{printf "%.2f/%.2f", 1000*$2, 1000*$4}')
  printf '%-5s %-14s %9s %9s %8s %9s %16s\n' "$1" "$2" "$els" "$cyc" "$ns" "$wall" "$m" | tee -a "$out"
done
# the long rod (input/long_rod quarter model, input/long_rod_2d axisymmetric)
# at 2 km/s to 90 us at the same mesh size, 1 mm (2.5 elements across the
# rod's radius), and the 2D deck's 0.5 mm: P/L
echo "# 2D against 3D: long rod, W alloy into steel, 2 km/s, 90 us, default element; time to solution = wall" | tee -a "$out"
printf '%-5s %-14s %9s %9s %8s %9s %8s\n' h model elements cycles ns wall_s "P/L" | tee -a "$out"
for spec in "1.0e-3 3d input/long_rod/long_rod" "1.0e-3 2d input/long_rod_2d/long_rod_2d" \
            "0.5e-3 2d input/long_rod_2d/long_rod_2d"; do
  set -- $spec
  case_name=long_rod_$2_h$1
  full_run "$1" "$2" "$3" "$case_name" 90.0e-6
  pl=$($PYTHON postproc/penetration.py "$W/twod/$case_name.h5" --radius 1.25e-3 --length 0.05 | tail -1 | awk '{print $NF}')
  printf '%-5s %-14s %9s %9s %8s %9s %8s\n' "$1" "$2" "$els" "$cyc" "$ns" "$wall" "$pl" | tee -a "$out"
done
echo "saved in $out"
