#!/usr/bin/python3
"""Penetration measurements from a udar field file: crater depth, residual rod length and
rod velocity at every output step.

The target's impact face is the plane z = 0 (the rod moves along -z); in a 2D
(axisymmetric) file the line y = 0, the axis being y and the radius x (the rod moves
along -y), and every "z" below is y, every distance from the axis |x|. At each step:

* crater depth P: minus the highest z of the target material still there (elements not
  eroded) near the axis (centroid within --radius of it);
* residual rod length: the axial extent of the rod elements not eroded;
* rod velocity: the mean axial velocity of the nodes of the rod elements not eroded;
* rod tip: the lowest z of those nodes;
* along --axis (the projectile's initial axis, pointing into the target; default 0 0 -1):
  the residual rod length is the extent along it, and the intact length the same for the
  rod elements not fractured;
* deepest crater point anywhere: minus the lowest centroid of the upward-facing boundary
  faces of the target material still there (the crater floor); crater diameter: twice
  the smallest distance from the z axis of those faces within --radius of the impact
  face's level (the hole's rim, for an impact on the axis);
* with particles (&material eroded = 'particles'), at the end of each row: the number and
  mass of the rod's particles and of the target's, the lowest z of the rod's particles,
  and the rod's material on its axis: the extent along --axis of the rod's material within
  --radius of the initial axis line (through --axis-point): the nodes of the rod elements
  not eroded whose centroid lies that close, and the rod's particles within --radius or
  half their spacing (m/rho)^(1/3)/2, whichever is larger (fractured material and
  particles included: what the seed paper's Fig. 3 measures along the cylinder's axis).

    /usr/bin/python3 postproc/penetration.py out/long_rod.h5 --rod rod --target block --radius 1.25e-3
    /usr/bin/python3 postproc/penetration.py out/long_rod_2d.h5 --radius 1.25e-3     (2D: axis y)
    /usr/bin/python3 postproc/penetration.py --self-test

Library use: ``measure(fieldfile, rod, target, radius)`` returns one dict per step.
"""

import argparse
import os
import sys
import tempfile

if __package__:
    from . import udar_results as ur
else:
    import udar_results as ur  # run as a script
import numpy as np


def part_id(ff, name):
    """Part id of the part called name (from the deck stored in the file)."""
    names = ff.part_names
    for pid, pname in names.items():
        if pname.lower() == name.lower():
            return pid
    raise SystemExit("%s: no part '%s' (parts: %s)" % (ff.path, name, ", ".join(names.values()) or "unnamed"))


def upward_boundary(x, conn, elements, up_axis=2):
    """Centroids of the faces of the given elements that are on their boundary
    (not shared by two of them) and face upwards (outward normal along up_axis >
    0.3): tetrahedra's triangles, or 2D triangles' edges (up_axis 1)."""
    el = conn[elements]
    nc = el.shape[1]
    # each face with the corner opposite it
    faces = np.concatenate([np.delete(el, k, axis=1) for k in range(nc)])
    opposite = np.concatenate([el[:, k] for k in range(nc)])
    _, inv, count = np.unique(np.sort(faces, axis=1), axis=0, return_inverse=True, return_counts=True)
    outer = count[inv.ravel()] == 1
    f, o = faces[outer], opposite[outer]
    a, b = x[f[:, 0]], x[f[:, 1]]
    if nc == 4:
        n = np.cross(b - a, x[f[:, 2]] - a)
    else:
        n = np.stack([b[:, 1] - a[:, 1], a[:, 0] - b[:, 0], np.zeros(len(a))], axis=1)
    n *= np.where(np.einsum("ij,ij->i", n, x[o] - a) > 0, -1.0, 1.0)[:, None]
    up = n[:, up_axis] > 0.3 * np.linalg.norm(n, axis=1)
    return x[f].mean(axis=1)[up]


def measure(ff, rod, target, radius, axis=(0.0, 0.0, -1.0), axis_point=(0.0, 0.0, 0.0)):
    """Per step: time (s), crater depth (m), residual rod length (m), rod velocity (m/s),
    rod tip z (m), eroded rod and target elements, intact rod length (m), deepest crater
    point anywhere (m), crater diameter (m); when the file has particles also the rod's and
    the target's particles (rod_particles, target_particles), their mass (rod_particle_mass,
    target_particle_mass, kg), the lowest z of the rod's particles (rod_particle_tip, m;
    nan without any) and the extent of the rod's material on its initial axis line
    (rod_on_axis, m: elements and particles, see the module's notes; 0 without any)."""
    conn = ff.connectivity
    planar = conn.shape[1] == 3          # a 2D file: the axis is y, the radius x
    k = 1 if planar else 2               # the coordinate along the axis
    if planar and tuple(axis) == (0.0, 0.0, -1.0):
        axis = (0.0, -1.0, 0.0)
    axis = np.asarray(axis, float) / np.linalg.norm(axis)
    axis_point = np.asarray(axis_point, float)

    def from_line(p):
        d = p - axis_point
        return np.linalg.norm(d - np.outer(d @ axis, axis), axis=1)

    def off_axis(p):
        return np.abs(p[..., 0]) if planar else np.hypot(p[..., 0], p[..., 1])
    rod_pid, tgt_pid = part_id(ff, rod), part_id(ff, target)
    rod_el = ff.part_id == rod_pid
    tgt_el = ff.part_id == tgt_pid
    with_particles = ff.has_particles
    rows = []
    for i in range(ff.n_steps):
        st = ff.step(i)
        x = st.coordinates
        v = np.asarray(st.fields["velocity"])
        state = (np.asarray(st.fields["fracture_state"]) if "fracture_state" in st.fields
                 else np.zeros(ff.n_elems))
        alive = state < 1.5
        centroid = x[conn].mean(axis=1)
        near_axis = off_axis(centroid) < radius
        tgt_axis = tgt_el & alive & near_axis
        depth = -min(x[conn[tgt_axis]][:, :, k].max(), 0.0) if tgt_axis.any() else float("nan")
        rod_alive = rod_el & alive
        if rod_alive.any():
            nodes = np.unique(conn[rod_alive])
            along = x[nodes] @ axis
            length = along.max() - along.min()
            vel = (v[nodes] @ -axis).mean()     # the z velocity for the default axis
            tip = x[nodes, k].min()
        else:
            length, vel, tip = 0.0, float("nan"), float("nan")
        intact = rod_el & (state < 0.5)
        if intact.any():
            along = x[np.unique(conn[intact])] @ axis
            intact_length = along.max() - along.min()
        else:
            intact_length = 0.0
        if (tgt_el & alive).any():
            floor = upward_boundary(x, conn, tgt_el & alive, k)
            deepest = -min(floor[:, k].min(), 0.0)
            rim = floor[np.abs(floor[:, k]) < radius]
            diameter = 2.0 * off_axis(rim).min() if len(rim) else float("nan")
        else:
            deepest, diameter = float("nan"), float("nan")
        rows.append(dict(time=st.time, depth=depth, rod_length=length, rod_velocity=vel, rod_tip=tip,
                         rod_eroded=int(np.count_nonzero(rod_el & ~alive)),
                         target_eroded=int(np.count_nonzero(tgt_el & ~alive)),
                         rod_intact_length=intact_length, crater_deepest=deepest, crater_diameter=diameter))
        if with_particles:
            pt = st.particles
            if pt is not None and pt.count:
                pp, mass, z = np.asarray(pt["part_id"]), np.asarray(pt["mass"]), pt.coordinates[:, k]
                xp, rho = pt.coordinates, np.asarray(pt["density"])
            else:  # a step without any (yet)
                pp, mass, z = np.zeros(0, int), np.zeros(0), np.zeros(0)
                xp, rho = np.zeros((0, 3)), np.zeros(0)
            rod_p, tgt_p = pp == rod_pid, pp == tgt_pid
            # the rod's material on its initial axis line: elements and particles
            on_line = rod_alive & (from_line(centroid) < radius)
            along = [x[np.unique(conn[on_line])] @ axis]
            near = rod_p.copy()
            near[rod_p] = from_line(xp[rod_p]) < np.maximum(radius, 0.5 * np.cbrt(mass[rod_p] / rho[rod_p]))
            along.append(xp[near] @ axis)
            along = np.concatenate(along)
            rows[-1].update(rod_particles=int(np.count_nonzero(rod_p)),
                            rod_particle_mass=float(mass[rod_p].sum()),
                            target_particles=int(np.count_nonzero(tgt_p)),
                            target_particle_mass=float(mass[tgt_p].sum()),
                            rod_particle_tip=float(z[rod_p].min()) if rod_p.any() else float("nan"),
                            rod_on_axis=float(np.ptp(along)) if len(along) else 0.0)
    return rows


def _stack_file(path, particles=None):
    """The 3D self-test file: a stack of single tets along z, target in [-4, 0] (part 2
    'block'), rod in [0, 4] (part 1 'rod'); at the second step the top two target tets and
    the rod's two lowest are eroded. ``particles``: the two steps' particles groups."""
    xs, conn = [], []
    for k in range(8):
        z0 = -4.0 + k
        base = len(xs)
        # base on top (an upward-facing face at z0 + 1), apex below
        xs += [[0, 0, z0 + 1], [0.1, 0, z0 + 1], [0, 0.1, z0 + 1], [0, 0, z0]]
        conn.append([base, base + 1, base + 2, base + 3])
    x0 = np.array(xs, float)
    part = np.array([2] * 4 + [1] * 4, dtype=np.int32)
    deck = "&part group = 'rod', material = 'w' /\n&part group = 'block', material = 's' /\n"
    v = np.tile([0.0, 0.0, -5.0], (len(x0), 1))
    state2 = np.array([0, 0, 2, 2, 2, 2, 0, 0], float)
    steps = [dict(time=0.0, cycle=0, coordinates=x0, fields=dict(velocity=0 * v, fracture_state=np.zeros(8))),
             dict(time=1.0, cycle=9, coordinates=x0, fields=dict(velocity=v, fracture_state=state2))]
    if particles is not None:
        for st, pts in zip(steps, particles):
            st["particles"] = pts
    ur.write_fields(path, x0, conn, steps, part_id=part, deck=deck)


def self_test():
    """A synthetic two-part file: a rod column above a target column, some target
    elements eroded at the second step."""
    ok = True
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "t.h5")
        _stack_file(path)
        ff = ur.open_fields(path)
        rows = measure(ff, "rod", "block", 0.5)
        ff.close()
    # (depth, rod length, eroded rod, eroded target, intact length, deepest, crater diameter):
    # the target tets' top faces (upward, on the boundary: the tets touch only at corners)
    # are at z = -3 .. 0; the rim is the one at z = 0, centroid (0.1/3, 0.1/3)
    rim = 2.0 * np.hypot(0.1 / 3, 0.1 / 3)
    want = [(0.0, 4.0, 0, 0, 4.0, 3.0, rim), (2.0, 2.0, 2, 2, 2.0, 3.0, float("nan"))]
    for r, (depth, length, re, te, intact, deepest, diam) in zip(rows, want):
        good = abs(r["depth"] - depth) < 1e-12 and abs(r["rod_length"] - length) < 1e-12 \
            and r["rod_eroded"] == re and r["target_eroded"] == te \
            and abs(r["rod_intact_length"] - intact) < 1e-12 and abs(r["crater_deepest"] - deepest) < 1e-12 \
            and (abs(r["crater_diameter"] - diam) < 1e-12 or (np.isnan(diam) and np.isnan(r["crater_diameter"])))
        print("  %s  t = %g: depth %g (%g), rod length %g (%g), eroded %d/%d (%d/%d), intact %g (%g), "
              "deepest %g (%g), diameter %g (%g)"
              % ("ok  " if good else "FAIL", r["time"], r["depth"], depth, r["rod_length"], length,
                 r["rod_eroded"], r["target_eroded"], re, te, r["rod_intact_length"], intact,
                 r["crater_deepest"], deepest, r["crater_diameter"], diam))
        ok &= good
    ok &= self_test_2d()
    ok &= self_test_particles(rows)
    print("penetration self-test: %s" % ("PASS" if ok else "FAIL"))
    return ok


def self_test_particles(rows_without):
    """The 3D stack with a particles group: none at the first step; at the second the four
    eroded tets' particles (rod: 2 and 3 g at z = -0.5 and -2.5; target: 1 and 0.5 g at
    z = -3.2 and -1; one of a third part, not counted). ``rows_without``: the rows of the
    same file without particles, whose columns must not change."""
    test = ur.SelfTest("penetration")
    pts = {"coordinates": [[0, 0, -0.5], [0, 0, -2.5], [0, 0, -3.2], [0, 0, -1.0], [0, 0, -9.0]],
           "velocity": np.zeros((5, 3)), "mass": [3e-3, 2e-3, 1e-3, 0.5e-3, 7e-3],
           "density": np.full(5, 7800.0), "part_id": [1, 1, 2, 2, 3], "element": [5, 4, 3, 2, 0]}
    with tempfile.TemporaryDirectory() as d:
        path, plain = os.path.join(d, "p.h5"), os.path.join(d, "plain.h5")
        _stack_file(path, [{}, pts])
        _stack_file(plain)
        with ur.open_fields(path) as ff:
            rows = measure(ff, "rod", "block", 0.5)
        new = ("rod_particles", "rod_particle_mass", "target_particles", "target_particle_mass",
               "rod_particle_tip", "rod_on_axis")
        same = all(set(r) - set(new) == set(r0) and all(
            r[key] == r0[key] or (np.isnan(r[key]) and np.isnan(r0[key])) for key in r0)
            for r, r0 in zip(rows, rows_without))
        test.check(same and all(key not in r0 for r0 in rows_without for key in new),
                   "particles: the other columns as without them; no particle keys without them")
        r0, r1 = rows
        test.check((r0["rod_particles"], r0["target_particles"], r0["rod_particle_mass"],
                    r0["target_particle_mass"]) == (0, 0, 0.0, 0.0) and np.isnan(r0["rod_particle_tip"]),
                   "t = 0: particles group with count 0: 0, 0 kg, tip nan")
        test.check(r1["rod_particles"] == 2 and r1["target_particles"] == 2
                   and abs(r1["rod_particle_mass"] - 5e-3) < 1e-15
                   and abs(r1["target_particle_mass"] - 1.5e-3) < 1e-15 and r1["rod_particle_tip"] == -2.5,
                   "t = 1: rod 2 particles %g kg (5e-3), target 2 %g kg (1.5e-3), rod particle tip %g (-2.5)"
                   % (r1["rod_particle_mass"], r1["target_particle_mass"], r1["rod_particle_tip"]))
        # on the axis: at t = 0 the rod's four tets (z 0..4); at t = 1 its two left
        # (z 2..4) and its particles at z = -0.5 and -2.5: 4 + 2.5 (the third part's
        # particle at -9 does not count); with the line moved 1 m off, nothing is near it
        test.check(abs(r0["rod_on_axis"] - 4.0) < 1e-12 and abs(r1["rod_on_axis"] - 6.5) < 1e-12,
                   "rod on its axis: %g (4), %g (6.5)" % (r0["rod_on_axis"], r1["rod_on_axis"]))
        with ur.open_fields(path) as ff:
            off = measure(ff, "rod", "block", 0.5, axis_point=(1.0, 0.0, 0.0))
        test.check(off[1]["rod_on_axis"] == 0.0, "nothing within 0.5 of a line 1 off: %g" % off[1]["rod_on_axis"])
        rc, out, _ = test.run_main(main, [path, "--radius", "0.5", "--length", "4"])
        lines = out.splitlines()
        head, last = lines[0].split(), lines[-1].split()
        test.check(rc == 0 and head[10:] == ["P/L", "rod_ptcl", "rod_ptcl_g", "tgt_ptcl", "tgt_ptcl_g",
                                             "ptcl_tip_mm", "on_axis_mm"]
                   and last[1] == "2000.000" and last[10] == "0.500"
                   and last[11:] == ["2", "5.00000", "2", "1.50000", "-2500.000", "6500.000"]
                   and lines[1].split()[11:] == ["0", "0.00000", "0", "0.00000", "nan", "4000.000"],
                   "CLI: particle columns after P/L, column 2 still the crater: %s" % " ".join(last))
        rc, out, _ = test.run_main(main, [plain, "--radius", "0.5"])
        test.check(rc == 0 and len(out.splitlines()[0].split()) == 10 and len(out.splitlines()[-1].split()) == 10
                   and out.splitlines()[-1].split()[1] == "2000.000",
                   "CLI without particles: the 10 columns only")
    return not test.failures


def self_test_2d():
    """The same in an axisymmetric file: a column of unit squares (two
    triangles each) along y, x in [0, 1]: target in [-4, 0], rod in [0, 4]."""
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "t2.h5")
        xs, conn = [], []
        for k in range(8):
            y0 = -4.0 + k
            base = len(xs)
            xs += [[0, y0, 0], [1, y0, 0], [1, y0 + 1, 0], [0, y0 + 1, 0]]
            conn += [[base, base + 1, base + 2], [base, base + 2, base + 3]]
        x0 = np.array(xs, float)
        part = np.array([2] * 8 + [1] * 8, dtype=np.int32)
        deck = "&part group = 'rod', material = 'w' /\n&part group = 'block', material = 's' /\n"
        v = np.tile([0.0, -5.0, 0.0], (len(x0), 1))
        # second step: the target's top square and the rod's lowest eroded
        state2 = np.array([0] * 6 + [2] * 4 + [0] * 6, float)
        ur.write_fields(path, x0, conn, [
            dict(time=0.0, cycle=0, coordinates=x0, fields=dict(velocity=0 * v, fracture_state=np.zeros(16))),
            dict(time=1.0, cycle=9, coordinates=x0, fields=dict(velocity=v, fracture_state=state2))],
            part_id=part, deck=deck)
        ff = ur.open_fields(path)
        rows = measure(ff, "rod", "block", 2.0)
        ff.close()
    # (depth, rod length, rod velocity (the y velocity, as the 3D one is z's), rod tip,
    # deepest, crater diameter): the squares touch only at corners, so each target
    # square's top edge (y = -3 .. 0, centre x = 0.5) faces up: deepest 3, diameter 1
    want = [(0.0, 4.0, 0.0, 0.0, 3.0, 1.0), (1.0, 3.0, -5.0, 1.0, 3.0, 1.0)]
    ok = True
    for r, (depth, length, vel, tip, deepest, diam) in zip(rows, want):
        good = abs(r["depth"] - depth) < 1e-12 and abs(r["rod_length"] - length) < 1e-12 \
            and abs(r["rod_velocity"] - vel) < 1e-12 and abs(r["rod_tip"] - tip) < 1e-12 \
            and abs(r["crater_deepest"] - deepest) < 1e-12 and abs(r["crater_diameter"] - diam) < 1e-12
        print("  %s  2D t = %g: depth %g (%g), rod length %g (%g), velocity %g (%g), tip %g (%g), "
              "deepest %g (%g), diameter %g (%g)"
              % ("ok  " if good else "FAIL", r["time"], r["depth"], depth, r["rod_length"], length,
                 r["rod_velocity"], vel, r["rod_tip"], tip, r["crater_deepest"], deepest,
                 r["crater_diameter"], diam))
        ok &= good
    return ok


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("h5", nargs="?", help="udar field file (.h5)")
    ap.add_argument("--rod", default="rod", help="name of the rod's part (default rod)")
    ap.add_argument("--target", default="block", help="name of the target's part (default block)")
    ap.add_argument("--radius", type=float, default=1.0e-3,
                    help="m, target elements with a centroid this close to the axis measure the crater")
    ap.add_argument("--length", type=float, default=0.0, help="m, initial rod length: also print P/L")
    ap.add_argument("--axis", type=float, nargs=3, default=(0.0, 0.0, -1.0), metavar=("AX", "AY", "AZ"),
                    help="the projectile's initial axis, into the target (default 0 0 -1)")
    ap.add_argument("--axis-point", type=float, nargs=3, default=(0.0, 0.0, 0.0), metavar=("PX", "PY", "PZ"),
                    help="m, a point of the projectile's initial axis (default 0 0 0): the line along "
                         "which the rod's material on its axis is measured (files with particles)")
    ap.add_argument("--self-test", action="store_true", help="run the built-in checks")
    a = ap.parse_args(argv)
    if a.self_test:
        return 0 if self_test() else 1
    if not a.h5:
        ap.error("give a field file or --self-test")
    ff = ur.open_fields(a.h5)
    rows = measure(ff, a.rod, a.target, a.radius, a.axis, a.axis_point)
    ff.close()
    # the particle columns come last (after P/L): the others keep their positions
    particles = bool(rows) and "rod_particles" in rows[0]
    print("%10s %12s %14s %14s %12s %10s %10s %10s %12s %12s%s%s"
          % ("t_us", "crater_mm", "rod_length_mm", "rod_vz_m_s", "rod_tip_mm", "rod_ero", "tgt_ero",
             "intact_mm", "deepest_mm", "crater_d_mm", "  P/L" if a.length else "",
             " %9s %11s %9s %11s %12s %12s" % ("rod_ptcl", "rod_ptcl_g", "tgt_ptcl", "tgt_ptcl_g",
                                               "ptcl_tip_mm", "on_axis_mm") if particles else ""))
    for r in rows:
        print("%10.3f %12.3f %14.3f %14.1f %12.3f %10d %10d %10.3f %12.3f %12.3f%s%s"
              % (r["time"] * 1e6, r["depth"] * 1e3, r["rod_length"] * 1e3, r["rod_velocity"], r["rod_tip"] * 1e3,
                 r["rod_eroded"], r["target_eroded"], r["rod_intact_length"] * 1e3, r["crater_deepest"] * 1e3,
                 r["crater_diameter"] * 1e3, "  %.3f" % (r["depth"] / a.length) if a.length else "",
                 " %9d %11.5f %9d %11.5f %12.3f %12.3f" % (
                     r["rod_particles"], r["rod_particle_mass"] * 1e3, r["target_particles"],
                     r["target_particle_mass"] * 1e3, r["rod_particle_tip"] * 1e3,
                     r["rod_on_axis"] * 1e3) if particles else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
