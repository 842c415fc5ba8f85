"""The OFHC Taylor bar whose strained elements become particles
(taylor_particles.nml: eps_convert = 1.0, strength kept; issue 15).
Checked:
- mass exact: the history's `mass` (mesh and particles) never changes, and
  the particles hold exactly rho0 V0 of the elements that became them;
- energy within 2 % (this mesh without conversion: -1.26 %, the stabilised
  element's; with conversion -1.38 %);
- more than 500 particles made (about 1,096 of the 7,316 tets);
- the converted material stays under the bar, as in the experiment: 95 %
  of the particles' mass lies within 1.25 times the measured footprint
  radius (13.56 / 2 mm, Johnson and Cook 1983) of the axis. Measured 7.16
  mm; strengthless particles (taylor_particles_strengthless.nml, the same
  conversion strain after fracture) run out along the frictionless wall to
  about 14 mm and fail it, which is what this test is for: the particles
  carry the strength;
- the particles do not pair up: fewer than 20 % have another particle
  within half their spacing (m/rho)^(1/3) at the end. SPH's tensile
  instability (particles in tension clump instead of parting) made 55 %
  such pairs here before the artificial stress (&material
  artificial_stress, default 0.3 since 0.9.5); with it 8 %.
  taylor_particles_no_art.nml (artificial_stress = 0) must fail this.
The length and the footprint over the remaining elements and the particles
are printed with the experiment's, not asserted (doc/validation.md 4zb).
taylor_particles_2d.nml is the same bar axisymmetric (ring particles,
masses per revolution; the axis y, the radius x; the spacing of a ring
particle the side of its square, sqrt(m / (rho 2 pi r))), without the
artificial stress, which 2D does not take: the same checks but the
pairing, which is printed (doc/validation.md 4zh).
Usage: called by check.py for a deck whose name starts with taylor_particles."""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..', 'tools'))
sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..', '..', 'postproc'))
sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', 'rod_3kms'))
import checks  # noqa: E402
import udar_results  # noqa: E402
from check_geometry import element_measures  # noqa: E402

RHO0 = 8960.0
FOOTPRINT_M = 13.56e-3       # Johnson and Cook (1983)
LENGTH_M = 16.21e-3


def measure(path):
    """The last step of field file path: particles made (n), their mass and
    the converted elements' (kg), r95 (m: the radius holding 95 % of the
    particles' mass, nan without particles), and over the remaining
    elements' nodes and the particles the length and the footprint (m: the
    farthest point from the axis within 0.5 mm of the lowest)."""
    f = udar_results.FieldFile(path)
    s = f.step(-1)
    p = s.particles
    conn = f.connectivity
    x0 = f.x0
    # (triangles: the axisymmetric bar, masses per revolution, the axis y)
    two_d = conn.shape[1] == 3
    el_mass = RHO0 * element_measures(conn, x0)
    if two_d:
        el_mass *= 2.0 * np.pi * x0[conn, 0].mean(axis=1)
    state = s.fields['fracture_state'] if 'fracture_state' in s.fields.elem_fields else np.zeros(len(conn))
    converted = np.asarray(state) == 2
    n = 0 if p is None else p.count
    xp = np.zeros((0, 3)) if p is None else p.coordinates
    p_mass = np.zeros(0) if p is None else np.asarray(p['mass'])
    r95 = float('nan')
    paired = float('nan')
    if n > 1:
        nearest = np.full(n, np.inf)
        for k in range(0, n, 256):     # (blocks of rows: n^2 distances without n^2 memory)
            dist = np.linalg.norm(xp[k:k + 256, None, :] - xp[None, :, :], axis=2)
            dist[np.arange(dist.shape[0]), np.arange(k, k + dist.shape[0])] = np.inf
            nearest[k:k + 256] = dist.min(axis=1)
        if two_d:
            spacing = np.sqrt(p_mass / (np.asarray(p['density']) * 2.0 * np.pi * np.maximum(xp[:, 0], 1e-12)))
        else:
            spacing = (p_mass / np.asarray(p['density'])) ** (1.0 / 3.0)
        paired = float(np.mean(nearest < 0.5 * spacing))
    if n > 0:
        r = np.abs(xp[:, 0]) if two_d else np.hypot(xp[:, 0], xp[:, 1])
        order = np.argsort(r)
        share = np.cumsum(p_mass[order]) / p_mass.sum()
        r95 = r[order][np.searchsorted(share, 0.95)]
    live = np.unique(conn[~converted].ravel())
    pts = np.vstack([s.coordinates[live], xp])
    z = pts[:, 1] if two_d else pts[:, 2]
    rad = np.abs(pts[:, 0]) if two_d else np.hypot(pts[:, 0], pts[:, 1])
    face = z <= z.min() + 5e-4
    return {'n': n, 'particle_mass': p_mass.sum(), 'converted_mass': el_mass[converted].sum(), 'r95': r95, 'paired': paired,
            'length': np.ptp(z), 'footprint': 2 * rad[face].max()}


def main(run_dir, deck):
    out = os.path.join(run_dir, 'out')
    m = measure(os.path.join(out, deck + '.h5'))
    n, r95, length, footprint = m['n'], m['r95'], m['length'], m['footprint']
    checks.above('particles_made', n, 500)
    checks.compare('particle_mass_is_converted_element_mass', m['particle_mass'], m['converted_mass'], 1e-12, 'kg')
    h = udar_results.read_history(os.path.join(out, deck + '_history.csv'))
    checks.below('mass_change', np.abs(h['mass'] - h['mass'][0]).max(), 0.0, 'kg')
    checks.below('energy_error_max', np.abs(h['energy_error']).max(), 0.02)
    checks.below('particle_mass_radius_95', r95, 1.25 * FOOTPRINT_M / 2, 'm')
    if not deck.endswith('_2d'):
        checks.below('particles_paired', m['paired'], 0.2)
    print(f"MEASURED {n} particles ({m['particle_mass'] * 1e3:.4f} g); 95 % of their mass within {r95 * 1e3:.2f} mm of the "
          f"axis (the experiment's footprint radius {FOOTPRINT_M * 500:.2f} mm); energy error at most "
          f"{np.abs(h['energy_error']).max():.3e}; {100 * m['paired']:.1f} % of them with another within half their spacing")
    print(f"MEASURED length {length * 1e3:.3f} mm ({100 * (length / LENGTH_M - 1):+.1f} % against the experiment), "
          f"footprint over elements and particles {footprint * 1e3:.3f} mm ({100 * (footprint / FOOTPRINT_M - 1):+.1f} %)")
    checks.finish()


if __name__ == '__main__':
    if sys.argv[1] == '--measure':
        # one CSV row fragment per file: particles, length_mm, footprint_mm, r95_mm, paired
        for path in sys.argv[2:]:
            m = measure(path)
            print(f"{m['n']},{m['length'] * 1e3:.3f},{m['footprint'] * 1e3:.3f},{m['r95'] * 1e3:.2f},{m['paired']:.3f}")
    else:
        main(sys.argv[1], sys.argv[2])
