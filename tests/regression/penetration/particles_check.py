"""The eroding penetration with eroded elements becoming particles
(penetration_particles.nml, issue 15). Checked against what conversion
must keep and what the contact must hold:
- mass exact: the mesh's and the particles' mass together (the history's
  `mass`) never changes, and the particles hold exactly the mass rho0 V0
  of the elements that became them (from the mesh in the field file);
- momentum conserved to 1e-13 (nothing outside acts), energy within 2 %
  (the balance counts the particles' kinetic and internal energy, and the
  kinetic energy of the corners' relative motion that conversion makes
  heat);
- at every field step no remaining rod node inside a remaining plate
  element (beyond 1e-4 of its size; the same deck without particles holds
  1e-6) and no rod particle deeper inside one than 0.05 of its size (the
  contact takes particles as slave nodes; measured 0.02);
- particles are made (more than 100) and written with each field step.
In plane strain (penetration_plane_strain_particles, triangles) masses are
per metre of depth and momentum is along y; axisymmetric
(penetration_axisymmetric_particles) per revolution (an element's 2 pi
rbar A, rbar its corners' mean radius), momentum along the axis y; where
the deck's contact is symmetric, no plate particle may be deeper inside a
remaining rod element than 0.05 of its size either.
Usage: called by check.py for a deck whose name ends in _particles."""
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..', 'tools'))
sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', 'rod_3kms'))
import checks  # noqa: E402
import udar_results  # noqa: E402
from check_geometry import deepest_inside, element_measures, slave_and_master  # noqa: E402

RHO0 = 7850.0


def main(run_dir, deck):
    out = os.path.join(run_dir, 'out')
    h = udar_results.read_history(os.path.join(out, deck + '_history.csv'))
    with h5py.File(os.path.join(out, deck + '.h5'), 'r') as f:
        # the run's own resolved deck (udar's canonical form) says whether the contact is both ways
        deck_text = f.attrs['deck']
        deck_text = deck_text.decode() if isinstance(deck_text, bytes) else deck_text
        both_ways = 'symmetric = .true.' in deck_text
        conn, x0, rod_nodes, plate, h_plate = slave_and_master(f, 1, 2)
        h_rod = slave_and_master(f, 2, 1)[4]
        # (plane strain: per metre of depth; axisymmetric: per revolution)
        el_mass = RHO0 * element_measures(conn, x0)
        axisymmetric = "geometry = 'axisymmetric'" in deck_text
        if axisymmetric:
            el_mass *= 2.0 * np.pi * x0[conn, 0].mean(axis=1)
        least_radius = 0.0
        axis = 'z' if conn.shape[1] == 4 else 'y'
        nodes_in, particles_in, plate_particles_in, last = 0.0, 0.0, 0.0, None
        for k in sorted(f['steps'].keys()):
            g = f['steps'][k]
            x = g['coordinates'][...]
            state = g['fracture_state'][...]
            plate_alive = plate & (state < 1.5)
            rod_alive = ~plate & (state < 1.5)
            live_rod = np.unique(conn[rod_alive])
            w_nodes = deepest_inside(x[live_rod], x, conn[plate_alive])
            p = g['particles']
            n = int(p.attrs['count'])
            w_part, w_plate_part = 0.0, 0.0
            if n > 0:
                xp = p['coordinates'][...]
                least_radius = min(least_radius, xp[:, 0].min())
                rod_p = xp[p['part_id'][...] == 1]
                if len(rod_p):
                    w_part = deepest_inside(rod_p, x, conn[plate_alive])
                plate_p = xp[p['part_id'][...] == 2]
                if len(plate_p):
                    w_plate_part = deepest_inside(plate_p, x, conn[rod_alive])
            print(f"MEASURED t = {g.attrs['time'] * 1e6:.2f} us: {n} particles, deepest remaining rod node inside "
                  f"the plate {w_nodes / h_plate:.3g} h, deepest rod particle {w_part / h_plate:.3g} h, deepest plate "
                  f"particle inside the rod {w_plate_part / h_rod:.3g} h")
            nodes_in = max(nodes_in, w_nodes)
            particles_in = max(particles_in, w_part)
            plate_particles_in = max(plate_particles_in, w_plate_part)
            last = (state, n, p['mass'][...] if n > 0 else np.zeros(0), p['element'][...] if n > 0 else None)
    state, n, p_mass, p_elem = last
    checks.above('particles_made', n, 100)
    if axisymmetric:
        # (the axis is the images' mirror and a wall to the particles)
        checks.below('particles_beyond_the_axis', -least_radius, 0.0, 'm')
    checks.below('rod_nodes_inside_remaining_plate_over_h', nodes_in / h_plate, 1e-4)
    checks.below('rod_particles_inside_remaining_plate_over_h', particles_in / h_plate, 0.05)
    if both_ways:
        checks.below('plate_particles_inside_remaining_rod_over_h', plate_particles_in / h_rod, 0.05)
    # every eroded element became one particle, of its mass
    eroded = np.nonzero(state > 1.5)[0]
    checks.below('one_particle_per_eroded_element', abs(n - len(eroded)), 0)
    checks.below('particles_are_the_eroded_elements',
                 0 if np.array_equal(np.sort(p_elem.astype(int)), eroded) else 1, 0)
    checks.compare('particle_mass_is_eroded_element_mass', p_mass.sum(), el_mass[eroded].sum(), 1e-12, 'kg')
    checks.below('mass_change', np.abs(h['mass'] - h['mass'][0]).max(), 0.0, 'kg')
    checks.compare('history_particle_mass', h['particle_mass'][-1], el_mass[eroded].sum(), 1e-12, 'kg')
    p0 = h['momentum_' + axis][0]
    checks.below('momentum_conserved_relative', np.abs(h['momentum_' + axis] - p0).max() / abs(p0), 1e-13)
    print(f"MEASURED at the end: {n} particles of {h['particle_mass'][-1] * 1e3:.4f} g, kinetic "
          f"{h['particle_kinetic'][-1]:.4g} J, internal {h['particle_internal'][-1]:.4g} J; conversion made "
          f"{h['conversion_heat'][-1]:.4g} J of kinetic energy heat; energy error {h['energy_error'][-1]:.3e}")
    checks.below('energy_error_max', np.abs(h['energy_error']).max(), 0.02)
