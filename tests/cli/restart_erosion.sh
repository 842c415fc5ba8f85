#!/usr/bin/env bash
# Restart with fracture, erosion and eroding contact: the penetration deck
# run to 2.5 us with a checkpoint at 1.5 us, then restarted from it on 2
# ranks, gives bitwise the history and fields of the straight run.
#   restart_erosion.sh EXE [anti_locking | stabilised | edges | particles | particles_strength |
#                           plane_strain_particles | axisymmetric_particles]
# With anti_locking the deck runs with the nodal-averaged pressure, whose
# reference volumes are rebased at erosion and carried by the checkpoint;
# stabilised: the stabilised nodal element (theory.md 8.1), whose element
# share of the nodal pressure is recomputed every cycle, not checkpointed;
# edges: edge-to-edge contact, whose feature edges erosion changes;
# particles: eroded elements become particles (issue 15), which the
# checkpoint carries, and the nodes' masses without them are recomputed;
# its gauges follow particles made before and after the checkpoint;
# particles_strength: besides, strained elements convert before they
# fracture (eps_convert), so particles carry their stress, hardening and
# damage through the checkpoint, and fracture later;
# plane_strain_particles: the plane-strain deck of penetration_2d whose
# eroded triangles become particles (2D SPH, symmetric contact);
# axisymmetric_particles: its axisymmetric deck, ring particles.
source "$(dirname "$0")/common.sh" "$1"
case=penetration
if [ "${2:-}" = plane_strain_particles ]; then
  # the plane-strain deck whose eroded triangles become particles
  # (tests/regression/penetration_2d), run under the case's name
  cp "$ROOT/tests/regression/penetration_2d/penetration_plane_strain.msh" "$W/"
  cp "$ROOT/tests/regression/penetration_2d/penetration_plane_strain_particles.nml" "$W/$case.nml"
elif [ "${2:-}" = axisymmetric_particles ]; then
  cp "$ROOT/tests/regression/penetration_2d/penetration_2d.msh" "$W/"
  cp "$ROOT/tests/regression/penetration_2d/penetration_axisymmetric_particles.nml" "$W/$case.nml"
else
  cp "$ROOT/tests/regression/$case/$case.msh" "$ROOT/tests/regression/$case/$case.nml" "$W/"
fi
sed -i -e 's/^\( *\)t_end = .*/\1t_end = 2.5e-6/' \
       -e 's|dt_history = 0.0 /|dt_history = 0.0, dt_checkpoint = 1.5e-6 /|' "$W/$case.nml"
grep -q 'dt_checkpoint = 1.5e-6' "$W/$case.nml" || { bad "deck_has_checkpoints"; exit 1; }
if [ "${2:-}" = anti_locking ]; then
  sed -i 's/anti_locking = .false./anti_locking = .true./' "$W/$case.nml"
  grep -q 'anti_locking = .true.' "$W/$case.nml" || { bad "deck_has_anti_locking"; exit 1; }
elif [ "${2:-}" = stabilised ]; then
  sed -i "s/anti_locking = .false./tet_formulation = 'stabilised', stabilisation = 0.1/" "$W/$case.nml"
  grep -q "tet_formulation = 'stabilised'" "$W/$case.nml" || { bad "deck_has_stabilised"; exit 1; }
elif [ "${2:-}" = edges ]; then
  # edge-to-edge contact: the new edges that erosion exposes are the same after a restart
  sed -i "s|&contact master = 'plate', slave = 'rod' /|\&contact master = 'plate', slave = 'rod', edges = .true. /|" "$W/$case.nml"
  grep -q "edges = .true." "$W/$case.nml" || { bad "deck_has_edges"; exit 1; }
elif [ "${2:-}" = particles ]; then
  sed -i "s/eps_erode = 1.5$/eps_erode = 1.5, eroded = 'particles'/" "$W/$case.nml"
  grep -q "eroded = 'particles'" "$W/$case.nml" || { bad "deck_has_particles"; exit 1; }
  # gauges whose elements become particles before the checkpoint (nose_side,
  # 1.30 us) and after it (the others, 1.59-1.98 us): followed alike after a restart
  cat >> "$W/$case.nml" <<'DECK'
&gauge name = 'nose', point = 0.3e-3, 0.2e-3, 0.3e-3 /
&gauge name = 'nose_side', point = 1.5e-3, 0.5e-3, 0.5e-3 /
&gauge name = 'behind_nose', point = 0.2e-3, 0.3e-3, 1.2e-3 /
&gauge name = 'plate_below', point = 0.4e-3, -0.3e-3, -0.5e-3 /
DECK
elif [ "${2:-}" = particles_strength ]; then
  sed -i "s/eps_erode = 1.5$/eps_erode = 1.5, eroded = 'particles', eps_convert = 0.8/" "$W/$case.nml"
  grep -q "eps_convert = 0.8" "$W/$case.nml" || { bad "deck_has_particles_with_strength"; exit 1; }
fi
straight_run $case
eroded=$(grep -o '[0-9]* eroded;' "$W/straight.log" | cut -d' ' -f1)
echo "MEASURED $eroded elements eroded in the straight run"
[ "${eroded:-0}" -gt 0 ] && ok "elements_eroded_before_the_end" || bad "elements_eroded_before_the_end"
if [ "${2:-}" = particles ] || [ "${2:-}" = particles_strength ] || [ "${2:-}" = plane_strain_particles ] || \
   [ "${2:-}" = axisymmetric_particles ]; then
  n=$($PYTHON -c "import sys; sys.path.insert(0, sys.argv[1]); import udar_results as u; print(int(u.read_history(sys.argv[2])['particles'][-1]))" \
      "$ROOT/postproc" "$W/straight/${case}_history.csv")
  echo "MEASURED particles at the end of the straight run: $n"
  [ "${n:-0}" -gt 0 ] && ok "particles_made" || bad "particles_made"
fi
if [ "${2:-}" = particles ]; then
  # when each gauge's element became a particle (state 3), against the checkpoint's 1.5 us
  times=$($PYTHON -c "
import sys; sys.path.insert(0, sys.argv[1]); import udar_results as u
h = u.read_history(sys.argv[2])
print(' '.join('%.3f' % (h['time'][list(h['gauge_%s_state' % g]).index(3.0)] * 1e6) if 3.0 in h['gauge_%s_state' % g] else 'never'
               for g in ('nose_side', 'nose', 'behind_nose', 'plate_below')))" "$ROOT/postproc" "$W/straight/${case}_history.csv")
  echo "MEASURED gauges nose_side, nose, behind_nose, plate_below on a particle from (us): $times"
  read -r t_side t_nose _ <<< "$times"
  [ "$t_side" != never ] && awk "BEGIN{exit !($t_side < 1.5)}" && ok "gauge_on_a_particle_before_the_checkpoint" \
    || bad "gauge_on_a_particle_before_the_checkpoint"
  [ "$t_nose" != never ] && awk "BEGIN{exit !($t_nose > 1.5)}" && ok "gauge_on_a_particle_after_the_checkpoint" \
    || bad "gauge_on_a_particle_after_the_checkpoint"
fi
if [ "${2:-}" = particles_strength ]; then
  # the checkpoint the restart starts from holds particles that keep their strength
  strong=$($PYTHON -c "import h5py, sys; a = h5py.File(sys.argv[1], 'r')['particles'][1:]; print(int((a[:, 26] > 0).sum()))" \
           "$W/out/${case}_ckpt1.h5")
  echo "MEASURED particles keeping their strength in the checkpoint: $strong"
  [ "${strong:-0}" -gt 0 ] && ok "checkpoint_has_particles_with_strength" || bad "checkpoint_has_particles_with_strength"
fi
restart_matches_straight $case 2
[ $fails -eq 0 ]
