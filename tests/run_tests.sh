#!/usr/bin/env bash
# Runs every test of `make check`; each test is one command whose exit status
# decides it. Output of each test goes to tests/work/<name>.log; the summary
# line (last line) is exactly "N passed, N failed".
set -u
cd "$(dirname "$0")/.."
ROOT=$PWD
export PYTHON=${PYTHON:-/usr/bin/python3}
# mpirun as root (CI machines) and more ranks than cores, also when run
# without make
if [ "$(id -u)" = 0 ]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
export OMPI_MCA_rmaps_base_oversubscribe=1
WORK=$ROOT/tests/work
rm -rf "$WORK"; mkdir -p "$WORK"
passed=0; failed=0
# Tests run in CHECK_JOBS lanes at once (default 2, this machine's cores; 1
# runs them one after another); results print in the order listed, as soon
# as each and those before it are done. Each test has its own folder, so
# lanes never share files; tests that time signals or look for processes
# by name run alone (run_alone). CHECK_ONLY=REGEX runs only the tests
# whose names match (bash regex), e.g. CHECK_ONLY=particles.
JOBS=${CHECK_JOBS:-2}
RESULTS=$WORK/.results; mkdir -p "$RESULTS"
listed=0; printed=0

one_test() {   # index, name, command...
  local idx=$1 name=$2; shift 2
  local log=$WORK/${name//\//_}.log t0=$SECONDS out=$RESULTS/$idx
  if ( "$@" ) > "$log" 2>&1; then
    printf 'PASS %-36s %4ds\n' "$name" $((SECONDS-t0)) > "$out.txt"
  else
    printf 'FAIL %-36s %4ds  (log: %s)\n' "$name" $((SECONDS-t0)) "${log#$ROOT/}" > "$out.txt"
    tail -n 15 "$log" | sed 's/^/    | /' >> "$out.txt"
  fi
  grep -E '^(PASS|FAIL|MEASURED)' "$log" | sed 's/^/    /' >> "$out.txt"
  mv "$out.txt" "$out"   # complete, or not there
}

print_done() {   # results in list order, up to the first still running
  local first
  while [ -f "$RESULTS/$((printed+1))" ]; do
    printed=$((printed+1))
    first=$(head -1 "$RESULTS/$printed")
    case $first in
      PASS*) passed=$((passed+1)) ;;
      *) failed=$((failed+1)) ;;
    esac
    cat "$RESULTS/$printed"
  done
}

run_test() {   # name, command...
  [[ $1 =~ ${CHECK_ONLY:-} ]] || return 0
  while [ "$(jobs -rp | wc -l)" -ge "$JOBS" ]; do wait -n; print_done; done
  listed=$((listed+1))
  one_test $listed "$@" &
}

run_alone() {   # name, command...: nothing else running meanwhile
  [[ $1 =~ ${CHECK_ONLY:-} ]] || return 0
  wait; print_done
  listed=$((listed+1))
  one_test $listed "$@"
  print_done
}

# a regression case: copy the deck and its mesh to tests/work/<case>, run it
# with the given binary (its log also in run.log there), then its check.py
# judges the output
regression() {   # case, binary [deck name, when the case has several]
  local case=$1 exe=$2 deck=${3:-$1} dir=$WORK/${3:-$1}
  mkdir -p "$dir"
  cp tests/regression/$case/*.nml "$dir"/
  # (a case's decks may use a mesh of input/ instead of their own)
  if compgen -G "tests/regression/$case/*.msh" > /dev/null; then cp tests/regression/$case/*.msh "$dir"/; fi
  ( cd "$dir" && set -o pipefail && "$ROOT/$exe" $deck.nml 2>&1 | tee run.log ) && \
    $PYTHON tests/regression/$case/check.py "$dir" $deck
}

# a deck that must fail its case's check at the named assertion (the same
# check without the option under test)
regression_fails() {   # case, binary, deck, assertion
  local case=$1 exe=$2 deck=$3 dir=$WORK/$3
  mkdir -p "$dir"
  cp tests/regression/$case/*.nml tests/regression/$case/*.msh "$dir"/
  ( cd "$dir" && set -o pipefail && "$ROOT/$exe" $deck.nml 2>&1 | tee run.log ) || return 1
  if $PYTHON tests/regression/$case/check.py "$dir" $deck | tee "$dir/check.out" | grep -q "^FAIL $4"; then
    echo "PASS $4 fails without the option, as it must"
  else
    echo "FAIL $4 did not fail without the option"; return 1
  fi
}

# two decks of one case in one folder (the second usually the reference run);
# the case's file 'meshes' names meshes of other cases it uses
regression_pair() {   # case, binary, deck, deck
  local case=$1 exe=$2 dir=$WORK/$1 m
  mkdir -p "$dir"
  cp tests/regression/$case/*.nml "$dir"/
  for m in $(cat tests/regression/$case/meshes); do cp tests/regression/$m "$dir"/; done
  ( cd "$dir" && "$ROOT/$exe" $3.nml && "$ROOT/$exe" $4.nml ) && $PYTHON tests/regression/$case/check.py "$dir"
}

# ---- unit tests (debug build: bounds checks and floating-point traps on)
for t in build/debug/tests/test_*; do
  [ -x "$t" ] || continue
  name=$(basename "$t")
  mkdir -p "$WORK/$name"
  run_test "unit/$name" "$t" "$ROOT/tests/unit" "$WORK/$name"
done
# ---- post-processing scripts on synthetic files with known answers
for s in udar_results plot_history section taylor plot_contact_history penetration shock swept; do
  run_test "postproc/$s" $PYTHON postproc/$s.py --self-test
done
# ---- deck errors through the real program
run_test "cli/deck_errors" tests/cli/deck_errors.sh bin/udar-debug
run_test "cli/input_decks" tests/cli/input_decks.sh bin/udar
run_test "cli/malformed_corpus" tests/cli/malformed_corpus.sh bin/udar
run_test "cli/run_goes_bad" tests/cli/run_goes_bad.sh bin/udar-debug
run_test "cli/repeatable" tests/cli/repeatable.sh bin/udar-debug
# the meshes behind doc/validation.md, against doc/validation/meshes.csv
run_test "cli/validation_meshes" tests/cli/validation_meshes.sh
# ---- parallel: one file from any number of writers; bitwise the same results
# on 1, 2, 3 and 4 ranks; checkpoint/restart on another rank count
run_test "unit/test_distribution_mpi_np3" mpirun -np 3 build/debug/tests/test_distribution_mpi "$ROOT/tests/unit" "$WORK"
run_test "cli/field_output_ranks" tests/cli/field_output_ranks.sh build/debug/tests/test_field_output_mpi "$WORK/field_output_ranks"
run_test "cli/ranks_elastic_bar" tests/cli/rank_invariance.sh bin/udar elastic_bar
run_test "cli/gauge_element_tag" tests/cli/gauge_element_tag.sh bin/udar
run_test "cli/ranks_elastic_bar_2d" tests/cli/rank_invariance.sh bin/udar elastic_bar_2d
run_test "cli/ranks_taylor_wg_2d" tests/cli/rank_invariance.sh bin/udar taylor_wg_2d 10.0e-6
run_test "cli/ranks_taylor_mts_2d" tests/cli/rank_invariance.sh bin/udar taylor_mts_2d 10.0e-6
run_test "cli/ranks_coulomb_wall" tests/cli/rank_invariance.sh bin/udar-debug coulomb_wall
run_test "cli/more_ranks_than_elements" tests/cli/more_ranks_than_elements.sh bin/udar-debug
run_test "cli/ranks_plate_impact" tests/cli/rank_invariance.sh bin/udar plate_impact
run_test "cli/ranks_blocks_head_on" tests/cli/rank_invariance.sh bin/udar blocks_head_on
run_test "cli/ranks_bars_head_on_2d_symmetric" tests/cli/rank_invariance.sh bin/udar bars_head_on_2d - - bars_head_on_2d_symmetric
run_test "cli/ranks_oblique_free" tests/cli/rank_invariance.sh bin/udar oblique_free
run_test "cli/ranks_spall" tests/cli/rank_invariance.sh bin/udar spall
run_test "cli/ranks_penetration" tests/cli/rank_invariance.sh bin/udar penetration 2.5e-6
run_test "cli/ranks_penetration_particles" tests/cli/rank_invariance.sh bin/udar penetration 1.5e-6 - penetration_particles
run_test "cli/ranks_penetration_voids" tests/cli/rank_invariance.sh bin/udar penetration 2.5e-6 - penetration_voids
run_test "cli/ranks_penetration_2d" tests/cli/rank_invariance.sh bin/udar penetration_2d 2.5e-6
run_test "cli/ranks_penetration_plane_strain_particles" tests/cli/rank_invariance.sh bin/udar penetration_2d 1.5e-6 - \
  penetration_plane_strain_particles
run_test "cli/ranks_penetration_axisymmetric_particles" tests/cli/rank_invariance.sh bin/udar penetration_2d 1.5e-6 - \
  penetration_axisymmetric_particles
run_test "cli/ranks_self_contact" tests/cli/rank_invariance.sh bin/udar self_contact
run_test "cli/ranks_self_contact_2d" tests/cli/rank_invariance.sh bin/udar self_contact_2d
run_test "cli/ranks_crossed_edges" tests/cli/rank_invariance.sh bin/udar crossed_edges 8.0e-6
run_test "cli/ranks_crossed_edges_friction" tests/cli/rank_invariance.sh bin/udar crossed_edges 8.0e-6 - crossed_edges_friction
run_test "cli/ranks_rod_valleys" tests/cli/rank_invariance.sh bin/udar rod_3kms - - rod_3kms_fast
run_test "cli/restart_erosion" tests/cli/restart_erosion.sh bin/udar
run_test "cli/restart_erosion_anti_locking" tests/cli/restart_erosion.sh bin/udar anti_locking
run_test "cli/restart_erosion_stabilised" tests/cli/restart_erosion.sh bin/udar stabilised
run_test "cli/restart_erosion_edges" tests/cli/restart_erosion.sh bin/udar edges
run_test "cli/restart_erosion_particles" tests/cli/restart_erosion.sh bin/udar particles
run_test "cli/restart_erosion_particles_strength" tests/cli/restart_erosion.sh bin/udar particles_strength
run_test "cli/restart_erosion_plane_strain_particles" tests/cli/restart_erosion.sh bin/udar plane_strain_particles
run_test "cli/restart_erosion_axisymmetric_particles" tests/cli/restart_erosion.sh bin/udar axisymmetric_particles
run_test "cli/tracking_rod_3kms" tests/cli/tracking.sh bin/udar rod_3kms 0.6e-6
run_test "cli/tracking_oblique_friction" tests/cli/tracking.sh bin/udar oblique_friction
run_test "cli/contact_mirrored" tests/cli/contact_mirrored.sh bin/udar
run_test "cli/ranks_taylor_ofhc" tests/cli/rank_invariance.sh bin/udar taylor_ofhc_baseline 30.0e-6
run_test "cli/ranks_taylor_particles" tests/cli/rank_invariance.sh bin/udar taylor_ofhc_baseline 20.0e-6 - taylor_particles
run_test "cli/ranks_taylor_wg_stabilised" tests/cli/rank_invariance.sh bin/udar taylor_wg 20.0e-6 stabilised
run_test "cli/restart" tests/cli/restart.sh bin/udar
run_test "cli/restart_2d" tests/cli/restart_2d.sh bin/udar
# repartitioning during a run (&run rebalance_imbalance): bitwise the 1-rank run
run_test "cli/rebalance" tests/cli/rebalance.sh bin/udar taylor_ofhc_baseline 20.0e-6 2
run_test "cli/rebalance_erosion" tests/cli/rebalance.sh bin/udar penetration 2.0e-6 1
run_alone "cli/hard_kill" tests/cli/hard_kill.sh bin/udar 8
run_test "cli/damaged_checkpoint" tests/cli/damaged_checkpoint.sh bin/udar
run_test "cli/run_control" tests/cli/run_control.sh bin/udar
run_alone "cli/full_disk" tests/cli/full_disk.sh bin/udar
run_alone "cli/signals_mpirun" tests/cli/signals_mpirun.sh bin/udar
run_test "cli/output_names" tests/cli/output_names.sh bin/udar
run_alone "cli/slurm_chain" tests/cli/slurm_chain.sh bin/udar
run_alone "cli/slurm_real" tests/cli/slurm_real.sh bin/udar
# ---- regressions against analytic and experimental references
run_test "regression/elastic_bar" regression elastic_bar bin/udar-debug
run_test "regression/elastic_bar_2d" regression elastic_bar_2d bin/udar-debug
run_test "regression/plate_impact" regression plate_impact bin/udar-debug
run_test "regression/plate_impact_2d" regression plate_impact_2d bin/udar-debug
run_test "regression/plate_impact_heating_2d" regression plate_impact_heating_2d bin/udar-debug
run_test "regression/coulomb_wall" regression coulomb_wall bin/udar-debug
run_test "regression/blocks_head_on" regression blocks_head_on bin/udar-debug
run_test "regression/blocks_head_on_symmetric" regression blocks_head_on bin/udar-debug blocks_head_on_symmetric
run_test "regression/bars_head_on_2d" regression bars_head_on_2d bin/udar-debug
run_test "regression/bars_head_on_2d_symmetric" regression bars_head_on_2d bin/udar-debug bars_head_on_2d_symmetric
run_test "regression/oblique_free" regression oblique_free bin/udar-debug
run_test "regression/oblique_free_distance_fails" regression_fails oblique_free bin/udar-debug oblique_free_distance angular_momentum_relative
run_test "regression/oblique_friction" regression oblique_friction bin/udar-debug
run_test "regression/oblique_stick" regression oblique_friction bin/udar-debug oblique_stick
run_test "regression/oblique_friction_2d" regression oblique_friction_2d bin/udar-debug
run_test "regression/oblique_stick_2d" regression oblique_friction_2d bin/udar-debug oblique_stick_2d
run_test "regression/rod_3kms" regression rod_3kms bin/udar
run_test "regression/rod_3kms_fast" regression rod_3kms bin/udar rod_3kms_fast
run_test "regression/rod_3kms_fast_seams_off_fails" regression_fails rod_3kms bin/udar rod_3kms_fast_seams_off \
  rod_nodes_inside_plate_over_h
run_test "regression/rod_3kms_fast_valleys_off_fails" regression_fails rod_3kms bin/udar rod_3kms_fast_valleys_off \
  rod_nodes_inside_plate_over_h
run_test "regression/spall" regression spall bin/udar-debug
run_test "regression/spall_averaged" regression spall bin/udar-debug spall_averaged
run_test "regression/penetration" regression penetration bin/udar
run_test "regression/penetration_particles" regression penetration bin/udar penetration_particles
run_test "regression/penetration_voids" regression penetration bin/udar penetration_voids
run_test "regression/penetration_voids_fine" regression penetration bin/udar penetration_voids_fine
run_test "regression/penetration_voids_fine_038" regression penetration bin/udar penetration_voids_fine_038
run_test "regression/penetration_voids_fine_07" regression penetration bin/udar penetration_voids_fine_07
run_test "regression/penetration_voids_off_fails" regression_fails penetration bin/udar penetration_voids_off_fails \
  voids_inside_out_over_reference_volume
run_test "cli/fig4_depth" tests/cli/fig4_depth.sh bin/udar
run_test "cli/fig4_first_20us" tests/cli/fig4_shipped.sh bin/udar 20.0e-6 0.25e-6 81 plate
run_test "cli/fig4_fine_frames" tests/cli/fig4_shipped.sh bin/udar 10.0e-6 0.05e-6 201
run_test "regression/long_rod_particles" regression long_rod_particles bin/udar
run_test "regression/long_rod_energy" regression long_rod_energy bin/udar
run_test "regression/buried_particles" regression buried_particles bin/udar
run_test "regression/buried_particles_half" regression buried_particles bin/udar buried_particles_half
run_test "regression/oblique_particles" regression oblique_particles bin/udar
run_test "regression/taylor_particles" regression taylor_ofhc_baseline bin/udar taylor_particles
run_test "regression/taylor_particles_2d" regression taylor_ofhc_baseline bin/udar taylor_particles_2d
run_test "regression/taylor_particles_strengthless_fails" regression_fails taylor_ofhc_baseline bin/udar \
  taylor_particles_strengthless particle_mass_radius_95
run_test "regression/taylor_particles_no_art_fails" regression_fails taylor_ofhc_baseline bin/udar \
  taylor_particles_no_art particles_paired
run_test "regression/penetration_2d" regression penetration_2d bin/udar
run_test "regression/penetration_plane_strain_particles" regression penetration_2d bin/udar \
  penetration_plane_strain_particles
run_test "regression/penetration_axisymmetric_particles" regression penetration_2d bin/udar \
  penetration_axisymmetric_particles
run_test "regression/deep_node" regression deep_node bin/udar-debug
run_test "regression/crossed_edges" regression crossed_edges bin/udar-debug
run_test "regression/crossed_edges_friction" regression crossed_edges bin/udar-debug crossed_edges_friction
run_test "regression/crossed_edges_off_fails" regression_fails crossed_edges bin/udar crossed_edges_off \
  edges_through_each_other_over_h
run_test "regression/sharp_edge" regression sharp_edge bin/udar-debug
run_test "regression/sharp_edge_off" regression sharp_edge bin/udar-debug sharp_edge_off
run_test "regression/self_contact" regression self_contact bin/udar-debug
run_test "cli/self_contact_off" tests/cli/self_contact_off.sh bin/udar
run_test "regression/self_contact_2d" regression self_contact_2d bin/udar-debug
run_test "cli/self_contact_2d_off" tests/cli/self_contact_off.sh bin/udar self_contact_2d
run_test "cli/step_warning" tests/cli/step_warning.sh bin/udar
run_test "regression/taylor_wg_2d" regression taylor_wg_2d bin/udar
run_test "regression/taylor_wg" regression taylor_wg bin/udar
run_test "regression/taylor_ofhc_baseline" regression taylor_ofhc_baseline bin/udar
run_test "regression/taylor_models_jc" regression taylor_models bin/udar taylor_jc
run_test "regression/taylor_models_za" regression taylor_models bin/udar taylor_za
run_test "regression/taylor_models_scg" regression taylor_models bin/udar taylor_scg
run_test "regression/taylor_models_mts" regression taylor_models bin/udar taylor_mts
run_test "regression/taylor_models_ptw" regression taylor_models bin/udar taylor_ptw
run_test "regression/taylor_half_length" regression_pair taylor_half_length bin/udar taylor_half_length taylor_half_length_plain

wait; print_done
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
