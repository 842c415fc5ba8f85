"""Two identical elastic bodies (nu = 0) head-on, frictionless contact (the
seed paper's algorithm), against 1D elastic wave theory: the contact lasts
2 L / c and the bodies exchange velocities (striker at rest, target at the
impact speed); momentum is conserved exactly and little energy is lost;
the contact pressure output adds up over each contact face to the contact
force of its cycle and its mean is near rho c v / 2. One check for the 3D
blocks (tests/regression/blocks_head_on) and the axisymmetric bars
(tests/regression/bars_head_on_2d): axis 'z' or 'y'; the faces of a
tetrahedron or the edges of a 2D triangle (ring areas per revolution)."""
import math
import os

import numpy as np

import checks
import udar_results

E, RHO, V, L = 200e9, 7850.0, 100.0, 0.02


def check(run_dir, deck, axis, area, symmetric):
    """axis: the impact direction ('z' 3D, 'y' axisymmetric); area: the
    cross-section (m2); symmetric: the deck's contact is symmetric."""
    c = math.sqrt(E / RHO)
    k = 'xyz'.index(axis)
    path = os.path.join(run_dir, 'out', deck + '_history.csv')
    h = udar_results.read_history(path)
    if axis == 'y':
        # axisymmetric: the history says its columns are the full revolution's
        note = udar_results.history_note(path)
        print(f"MEASURED history note: {note}")
        checks.above('history_note_says_full_revolution', float('full revolution' in note), 1)
    # the contact force: both directions' of a symmetric contact
    t, f = h['time'], sum(h[n] for n in h if n.startswith('contact_normal_'))
    touching = np.nonzero(f > 0.0)[0]
    duration = t[touching[-1]] - t[touching[0]]
    checks.compare('contact_duration_2L_over_c', duration, 2 * L / c, 0.03, 's')
    # centre-of-mass velocities after separation (fit over the last 6 us)
    after = t > t[touching[-1]] + 3e-6
    v = {p: np.polyfit(t[after], h[f'com_{axis}_' + p][after], 1)[0] for p in ('striker', 'target')}
    checks.compare('target_velocity_after', v['target'], V, 0.03, 'm/s')
    checks.below('striker_velocity_after_over_v', v['striker'] / V, 0.03)
    lost = 1.0 - h['total'][-1] / h['total'][0]
    print(f"MEASURED energy lost {100 * lost:.3f} %, contact force plateau "
          f"{np.median(f[touching]):.4g} N vs rho c v/2 A = {RHO * c * V / 2 * area:.4g} N")
    checks.below('energy_lost', lost, 0.02)
    p0 = h[f'momentum_{axis}'][0]
    checks.below('momentum_conserved_relative', np.abs(h[f'momentum_{axis}'] - p0).max() / abs(p0), 1e-13)
    for name in ['striker_on_target'] + (['target_on_striker'] if symmetric else []):
        checks.below(f'passes_unconverged_{name}', checks.unconverged_passes(run_dir, name), 0)

    # contact pressure (node field) at 5 us, halfway through the contact:
    # over each contact face it adds up to the contact force of that cycle
    # (the history), and its mean is near the wave theory's rho c v/2 (one
    # cycle's value on non-conforming faces: within 5 %; the force's median
    # above is the time-averaged comparison)
    fld = udar_results.open_fields(os.path.join(run_dir, 'out', deck + '.h5'))
    conn, part = fld.connectivity, fld.part_id
    step = fld.step(fld.nearest_step(5e-6))
    x, pc = step.coordinates, np.asarray(step.fields['contact_pressure'])
    x0 = fld.step(0).coordinates     # the contact faces by where they started (they deform unevenly)
    if fld.dim == 3:
        faces = np.sort(conn[:, [[1, 2, 3], [0, 2, 3], [0, 1, 3], [0, 1, 2]]].reshape(-1, 3), axis=1)
    else:
        faces = np.sort(conn[:, [[1, 2], [2, 0], [0, 1]]].reshape(-1, 2), axis=1)
    nv = faces.shape[1]
    face_part = np.repeat(part, conn.shape[1])
    for name, pid, pick in (('striker', part.min(), np.max), ('target', part.max(), np.min)):
        fp = faces[face_part == pid]
        key, count = np.unique(fp, axis=0, return_counts=True)
        outer = key[count == 1]
        a_face = pick(x0[np.unique(conn[part == pid]), k])
        on = outer[np.all(np.abs(x0[outer, k] - a_face) < 5e-5, axis=1)]
        if nv == 3:
            face_area = 0.5 * np.linalg.norm(np.cross(x[on[:, 1]] - x[on[:, 0]], x[on[:, 2]] - x[on[:, 0]]), axis=1)
        else:
            # the ring a segment sweeps in a revolution
            face_area = math.pi * (x[on[:, 0], 0] + x[on[:, 1], 0]) * np.linalg.norm(x[on[:, 1]] - x[on[:, 0]], axis=1)
        node_area = np.zeros(len(x))
        np.add.at(node_area, on.ravel(), np.repeat(face_area / nv, nv))
        force = (pc * node_area).sum()
        row = np.argmin(np.abs(t - step.time))
        checks.compare(f'contact_pressure_times_area_{name}_face', force, f[row], 0.01, 'N')
        checks.compare(f'contact_pressure_mean_{name}_face', force / node_area.sum(), RHO * c * V / 2, 0.05, 'Pa')
    checks.finish()
