#!/usr/bin/python3
"""Taylor anvil test measurements from a udar field file: rod length, gap to the wall,
footprint diameter and maximum (bulge) diameter.

* length = the rod's own extent along the axis (max - min of its nodal coordinates), so a
  rod that has rebounded off the wall is not reported long;
* gap = distance from the wall plane to the rod's lowest point, on the rod's side (the side
  of the mean nodal coordinate); negative = penetration;
* footprint diameter = 2 * max radial distance from the rod axis among the nodes within
  ``--band`` metres of the rod's lowest point (its impact face, wherever the rod is);
* max diameter = 2 * max radial distance from the axis over all nodes.

The radius is measured from the axis line through ``--center``, so full, half and quarter
models give the same numbers; a 2D axisymmetric file (x = r, y along the axis) is measured
about the y axis by default, its radius being x.

    /usr/bin/python3 postproc/taylor.py out/taylor.h5
    /usr/bin/python3 postproc/taylor.py out/taylor.h5 --axis z --wall 0.0 --center 0 0 --band 0.0005
    /usr/bin/python3 postproc/taylor.py out/taylor.h5 --all --json
    /usr/bin/python3 postproc/taylor.py --self-test

Library use: ``measure(coords, axis, wall, center, band)`` -> dict.
"""

import json
import math
import os
import sys
import tempfile

if __package__:
    from . import udar_results as ur
else:
    import udar_results as ur  # run as a script, it stops with a message if numpy is missing
import numpy as np

AXES = "xyz"


class TaylorError(Exception):
    """Bad measurement request; the message says what is wrong."""


def transverse_axes(axis):
    """The two coordinates perpendicular to ``axis`` (0, 1, 2), in increasing order."""
    return [k for k in range(3) if k != axis]


def measure(coords, axis=2, wall=0.0, center=(0.0, 0.0), band=5e-4):
    """Measure a rod standing on the wall plane ``coordinate[axis] = wall``.

    ``center``: the axis line's position in the two transverse coordinates (increasing
    axis order: for axis z it is (x, y), for y it is (x, z), for x it is (y, z)).
    Returns a dict: length_m (extent along the axis), gap_m (lowest point's height above the
    wall; negative = penetration), footprint_diameter_m (nodes within ``band`` of the lowest
    point), max_diameter_m, side (+1 / -1: the rod's side of the wall), n_footprint_nodes.
    """
    x = np.asarray(coords, dtype=np.float64)
    if x.ndim != 2 or x.shape[1] != 3 or x.shape[0] == 0:
        raise TaylorError("coordinates must be a non-empty (n, 3) array, got shape %s" % (x.shape,))
    if not 0 <= axis <= 2:
        raise TaylorError("axis must be 0, 1 or 2")
    if band < 0:
        raise TaylorError("--band must be >= 0")
    h, side = ur.wall_heights(x, axis, wall)       # height above the wall, on the rod's side
    i, j = transverse_axes(axis)
    r = np.hypot(x[:, i] - center[0], x[:, j] - center[1])
    lowest = h.min()
    # the impact face's layer, wherever the rod is: after a rebound no node is at the wall
    face = h <= lowest + band
    return {
        "length_m": float(np.ptp(h)),
        "footprint_diameter_m": float(2.0 * r[face].max()),
        "max_diameter_m": float(2.0 * r.max()),
        "side": int(side),
        "gap_m": float(lowest),
        "n_footprint_nodes": int(face.sum()),
    }


def _fmt(v):
    return "nan" if v is None or (isinstance(v, float) and math.isnan(v)) else "%.9g" % v


def machine_line(m):
    """'length_m=... footprint_diameter_m=... max_diameter_m=... time_s=... gap_m=...'
    (gap_m last: readers of the first four keys keep working)"""
    return "length_m=%s footprint_diameter_m=%s max_diameter_m=%s time_s=%s gap_m=%s" % (
        _fmt(m["length_m"]), _fmt(m["footprint_diameter_m"]), _fmt(m["max_diameter_m"]),
        _fmt(m["time_s"]), _fmt(m["gap_m"]))


def human_line(m):
    def mm(v):
        return "n/a" if v is None or math.isnan(v) else "%.4f mm" % (v * 1e3)
    ratio = ""
    if m.get("initial_length_m"):
        ratio = " (L/L0 = %.4f)" % (m["length_m"] / m["initial_length_m"])
    dratio = ""
    if m.get("initial_diameter_m") and not math.isnan(m["footprint_diameter_m"]):
        dratio = " (D/D0 = %.4f)" % (m["footprint_diameter_m"] / m["initial_diameter_m"])
    return ("t = %.4f us (step %d, cycle %d): length %s%s, footprint diameter %s%s, "
            "max diameter %s, gap to the wall %s; initial length %s, initial diameter %s" % (
                m["time_s"] * 1e6, m["step"], m["cycle"], mm(m["length_m"]), ratio,
                mm(m["footprint_diameter_m"]), dratio, mm(m["max_diameter_m"]), mm(m["gap_m"]),
                mm(m.get("initial_length_m", float("nan"))),
                mm(m.get("initial_diameter_m", float("nan")))))


def measure_file(path, steps=(-1,), axis=2, wall=0.0, center=(0.0, 0.0), band=5e-4):
    """Measure the given step indices of a field file -> list of dicts (SI units), each with
    the ``measure`` keys plus step, cycle, time_s, initial_length_m, initial_diameter_m."""
    results = []
    with ur.open_fields(path) as f:
        if f.n_nodes == 0:
            raise TaylorError("%s: the mesh has no nodes" % path)
        i, j = transverse_axes(axis)
        x0 = f.x0
        init = {
            "initial_length_m": float(x0[:, axis].max() - x0[:, axis].min()),
            "initial_diameter_m": float(2.0 * np.hypot(x0[:, i] - center[0], x0[:, j] - center[1]).max()),
        }
        idxs = range(len(f.steps)) if steps == "all" else [f.resolve_index(s) for s in steps]
        for k in idxs:
            st = f.step(k)
            m = measure(st.coordinates, axis, wall, center, band)
            m.update({"step": st.index, "cycle": st.cycle, "time_s": st.time})
            m.update(init)
            results.append(m)
    return results


def parse_machine_line(text):
    """The first 'length_m=...' line of ``text`` as {key: float} (None if there is none)."""
    line = next((ln for ln in text.splitlines() if ln.startswith("length_m=")), None)
    return None if line is None else {k: float(v) for k, v in
                                      (kv.split("=", 1) for kv in line.split())}


# --------------------------------------------------------------------------------------
# self-test
# --------------------------------------------------------------------------------------

def _self_test(verbose=True):
    """Synthetic deformed cylinders (full/half/quarter, each axis, both wall sides)."""
    test = ur.SelfTest("taylor", verbose)
    check = test.check

    def close(a, b, tol=1e-12):
        return abs(a - b) <= tol * max(1.0, abs(b))

    R, L = 3.8e-3, 25.4e-3
    n_len = 20
    cases = [  # sector, axis, wall, side, center
        ("full", 2, 0.0, +1, (0.0, 0.0)),
        ("half", 0, 0.1, -1, (0.01, -0.02)),
        ("quarter", 1, -0.05, +1, (0.0, 0.0)),
        ("quarter", 2, 0.3, -1, (-0.004, 0.002)),
    ]
    with tempfile.TemporaryDirectory(prefix="udar_taylor_test_") as tmp:
        for sector, axis, wall, side, center in cases:
            nodes, conn = ur.cylinder_tets(R, L, 4, n_len, sector, axis=axis)
            t = nodes[:, axis] / L                            # 0 at the impact end .. 1
            # deformed shape: shortened to 0.7 L, mushroom at the wall and a bulge at 40 %
            def g(tt):
                return 1.0 + 0.45 * np.exp(-tt / 0.05) + 0.9 * np.exp(-((tt - 0.4) / 0.02) ** 2)
            layers = np.linspace(0.0, 1.0, n_len + 1)
            exp_len = 0.7 * L
            exp_foot = 2.0 * R * g(0.0)
            exp_max = 2.0 * R * g(layers).max()
            x = nodes.copy()
            i, j = transverse_axes(axis)
            x[:, i] = center[0] + nodes[:, i] * g(t)
            x[:, j] = center[1] + nodes[:, j] * g(t)
            x[:, axis] = wall + side * 0.7 * nodes[:, axis]
            x0 = x.copy()
            x0[:, i] = center[0] + nodes[:, i]
            x0[:, j] = center[1] + nodes[:, j]
            x0[:, axis] = wall + side * (nodes[:, axis] + 1e-3)   # 1 mm gap before impact
            what = "%s model, axis %s, wall %g m, rod on the %s side" % (
                sector, AXES[axis], wall, "positive" if side > 0 else "negative")
            m = measure(x, axis, wall, center, band=5e-4)
            check(close(m["length_m"], exp_len) and close(m["footprint_diameter_m"], exp_foot)
                  and close(m["max_diameter_m"], exp_max) and m["side"] == side,
                  "%s: L %.6f mm, foot %.6f mm, max %.6f mm" % (
                      what, m["length_m"] * 1e3, m["footprint_diameter_m"] * 1e3,
                      m["max_diameter_m"] * 1e3))
            # end-to-end through a file and the CLI
            h5 = os.path.join(tmp, "rod_%s_%d.h5" % (sector, axis))
            ur.write_fields(h5, x0, conn, [
                {"time": 0.0, "cycle": 0, "coordinates": x0},
                {"time": 6e-5, "cycle": 1234, "coordinates": x}])
            argv = [h5, "--axis", AXES[axis], "--wall", repr(wall), "--center",
                    repr(center[0]), repr(center[1]), "--band", "0.0005"]
            rc, out, _ = test.run_main(main, argv)
            vals = parse_machine_line(out)
            ok = (rc == 0 and vals is not None and close(vals["length_m"], exp_len, 1e-8)
                  and close(vals["footprint_diameter_m"], exp_foot, 1e-8)
                  and close(vals["max_diameter_m"], exp_max, 1e-8) and vals["time_s"] == 6e-5
                  and abs(vals["gap_m"]) < 1e-12)
            check(ok, "%s: CLI machine-readable line" % what)
            if axis == 2 and sector == "full":
                rc, out, err = test.run_main(main, argv + ["--json", "--all"])
                try:
                    js = json.loads(out)
                    # step 0: the undeformed rod 1 mm before the wall
                    ok = (rc == 0 and len(js) == 2 and close(js[0]["gap_m"], 1e-3)
                          and close(js[0]["footprint_diameter_m"], 2.0 * R)
                          and close(js[0]["length_m"], L) and close(js[1]["length_m"], exp_len)
                          and close(js[0]["initial_length_m"], L) and err == "")
                except ValueError:
                    ok = False
                check(ok, "--json --all (step 0: rod 1 mm off the wall, its own length and diameter)")
        # A rebounded bar: its lowest point is 0.9 mm off the wall (more than --band), as
        # steel and aluminium bars are at 80 us. Length is its own extent, not the top's height.
        nodes, conn = ur.cylinder_tets(R, L, 4, n_len, "quarter", axis=2)
        t = nodes[:, 2] / L
        g = 1.0 + 0.3 * np.exp(-t / 0.05)             # mushroom, widest at the impact face
        gap = 0.9e-3
        x = np.column_stack([nodes[:, 0] * g, nodes[:, 1] * g, gap + 0.8 * nodes[:, 2]])
        exp = {"length_m": 0.8 * L, "gap_m": gap, "footprint_diameter_m": 2.6 * R,
               "max_diameter_m": 2.6 * R}
        m = measure(x, 2, 0.0, (0.0, 0.0), band=5e-4)
        check(all(close(m[k], v) for k, v in exp.items()) and m["n_footprint_nodes"] > 0,
              "rebounded bar (gap 0.9 mm): L %.6f mm (expected %.6f), gap %.6f mm, foot %.6f mm "
              "(expected %.6f)" % (m["length_m"] * 1e3, exp["length_m"] * 1e3, m["gap_m"] * 1e3,
                                   m["footprint_diameter_m"] * 1e3, exp["footprint_diameter_m"] * 1e3))
        h5 = os.path.join(tmp, "rebounded.h5")
        ur.write_fields(h5, nodes, conn, [{"time": 8e-5, "cycle": 9, "coordinates": x}])
        rc, out, err = test.run_main(main, [h5, "--axis", "z", "--wall", "0",
                                            "--reference-length", repr(0.8 * L)])
        vals = parse_machine_line(out)
        check(rc == 0 and err == "" and vals is not None
              and all(close(vals[k], v, 1e-8) for k, v in exp.items())
              and "gap to the wall 0.9000 mm" in out and "difference +0.000 mm" in out,
              "rebounded bar through the CLI: length, gap and footprint on the machine line")
        png = os.path.join(tmp, "rebounded_section.png")
        rc, out, err = test.run_main(main, [h5, "--axis", "z", "--wall", "0", "--reference-length",
                                            repr(0.8 * L), "--section", png])
        check(rc == 0 and os.path.exists(png) and os.path.getsize(png) > 5000,
              "--section: the quarter bar's section drawn with its length and footprint")
        # a 2D axisymmetric bar (x = r, y along the axis): measured about y by default
        nodes, conn = ur.rectangle_tris(4, n_len, (0.0, 0.0), (R, L))
        t = nodes[:, 1] / L
        g = 1.0 + 0.3 * np.exp(-t / 0.05)
        x = np.column_stack([nodes[:, 0] * g, 0.8 * nodes[:, 1], np.zeros(len(nodes))])
        h5 = os.path.join(tmp, "axisymmetric.h5")
        ur.write_fields(h5, nodes, conn, [{"time": 8e-5, "cycle": 9, "coordinates": x}])
        rc, out, err = test.run_main(main, [h5])
        vals = parse_machine_line(out)
        check(rc == 0 and err == "" and vals is not None and close(vals["length_m"], 0.8 * L, 1e-8)
              and close(vals["footprint_diameter_m"], 2.6 * R, 1e-8),
              "2D axisymmetric file: the y axis by default, footprint diameter 2 x the largest r")
        rc, _, err = test.run_main(main, [os.path.join(tmp, "missing.h5")])
        check(rc == 1 and "missing.h5: no such file" in err,
              "missing file: exit code 1 and a message naming the file")
    return test.finish()


# --------------------------------------------------------------------------------------
# CLI
# --------------------------------------------------------------------------------------

def build_parser():
    p = ur.cli_parser(
        "taylor.py",
        "Measure a Taylor anvil rod in a udar field file (<case>.h5): its length "
        "(its own extent along the axis), footprint diameter (of its lowest layer), "
        "maximum diameter and gap to the wall. Prints a machine-readable line "
        "'length_m=... footprint_diameter_m=... max_diameter_m=... time_s=... gap_m=...' "
        "and a human-readable line in mm.",
        """examples:
  /usr/bin/python3 postproc/taylor.py out/taylor.h5
  /usr/bin/python3 postproc/taylor.py out/taylor.h5 --step -1 --axis z --wall 0.0 --center 0 0 --band 0.0005
  /usr/bin/python3 postproc/taylor.py out/taylor.h5 --all            # one line per output step
  /usr/bin/python3 postproc/taylor.py out/taylor.h5 --json
  /usr/bin/python3 postproc/taylor.py --self-test

All lengths in metres. --center gives the rod axis in the two transverse coordinates in
increasing axis order: (x, y) for --axis z, (x, z) for --axis y, (y, z) for --axis x.
The rod's side of the wall is the side of the mean nodal coordinate; full, half and quarter
models give the same result when the axis lies in the symmetry planes.""")
    g = ur.add_fields_argument(p)
    g.add_argument("--all", action="store_true", help="measure every output step")
    p.add_argument("--axis", default=None, choices=("x", "y", "z"),
                   help="rod axis (default z; y for a 2D axisymmetric file, whose axis is y)")
    p.add_argument("--wall", type=float, default=0.0, metavar="POS",
                   help="wall plane position along the axis, m (default 0.0)")
    p.add_argument("--center", type=float, nargs=2, default=(0.0, 0.0), metavar=("C1", "C2"),
                   help="rod axis position in the two transverse coordinates, m (default 0 0)")
    p.add_argument("--band", type=float, default=5e-4, metavar="DIST",
                   help="nodes within DIST m of the rod's lowest point form the footprint "
                        "(default 0.0005)")
    p.add_argument("--json", action="store_true",
                   help="print JSON instead (an object; a list with --all); nan -> null")
    p.add_argument("--reference-length", type=float, metavar="L", default=None,
                   help="measured final length, m: also print the difference from it")
    p.add_argument("--reference-diameter", type=float, metavar="D", default=None,
                   help="measured footprint diameter, m: also print the difference from it")
    p.add_argument("--section", metavar="OUT.png", default=None,
                   help="also draw the section through the axis (plastic strain; a quarter or half "
                        "model mirrored) with the computed length and footprint, solid, and the "
                        "measured ones (--reference-*), dashed")
    return ur.add_self_test(p, "run the built-in checks on synthetic cylinders, print PASS/FAIL")


def materials_line(path):
    """'material: NAME (strength = 'MODEL'), ...' from the deck the field file keeps, so the
    result says which model made it; '' when the file keeps no deck."""
    with ur.open_fields(path) as f:
        text = f.deck
    mats = [ur.deck_values(body) for group, body in ur.deck_groups(text) if group == "material"]
    return ("material: " + ", ".join("%s (strength = '%s')" % (m.get("name", "?"), m.get("strength", "elastic"))
                                     for m in mats)) if mats else ""


def draw_section(path, out, m, axis, wall, center, ref_length=None, ref_diameter=None, step=-1):
    """The section through the rod's axis (section.py: plastic strain, mirrored about the axis)
    with the measured rod drawn on it: its length (a line across the top) and footprint (a bar
    on the wall), and the experiment's where given (dashed)."""
    if __package__:
        from . import section as sec
    else:
        import section as sec
    with ur.open_fields(path) as f:
        planar = f.dim == 2
    if planar and axis != 1:
        raise TaylorError("--section: a 2D file's rod axis is y")
    if not planar and axis != 2:
        raise TaylorError("--section draws a 3D rod along z only (its section y = %g)" % center[1])
    plane = None if planar else sec.plane_from_spec("y=%r" % center[1])
    side = m["side"]
    bottom = wall + side * m["gap_m"]
    top = bottom + side * m["length_m"]
    x0 = center[0]

    def decorate(ax):
        half = 0.5 * m["max_diameter_m"]
        ax.plot([(x0 - half) * 1e3, (x0 + half) * 1e3], [top * 1e3] * 2, color="k", lw=1.6,
                label="computed: length %.3f mm, footprint %.3f mm"
                % (m["length_m"] * 1e3, m["footprint_diameter_m"] * 1e3))
        r = 0.5 * m["footprint_diameter_m"]
        ax.plot([(x0 - r) * 1e3, (x0 + r) * 1e3], [bottom * 1e3] * 2, color="k", lw=3.0)
        if ref_length or ref_diameter:
            parts = []
            if ref_length:
                ax.plot([(x0 - half) * 1e3, (x0 + half) * 1e3], [(bottom + side * ref_length) * 1e3] * 2,
                        color="C3", lw=1.6, ls="--")
                parts.append("length %.3f mm" % (ref_length * 1e3))
            if ref_diameter:
                ax.plot([(x0 - 0.5 * ref_diameter) * 1e3, (x0 + 0.5 * ref_diameter) * 1e3],
                        [bottom * 1e3] * 2, color="C3", lw=1.6, ls="--")
                parts.append("footprint %.3f mm" % (ref_diameter * 1e3))
            ax.plot([], [], color="C3", ls="--", label="measured: " + ", ".join(parts))
        lo, hi = ax.get_ylim()
        ax.set_ylim(min(lo, top * 1e3 - 0.5), max(hi, top * 1e3 + 0.5))
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.07), fontsize="small", frameon=False)

    # a model on one side of the axis (a quarter, a half, an axisymmetric meridian) is drawn
    # with its mirror image
    with ur.open_fields(path) as f:
        one_side = f.x0[:, 0].min() >= x0 - 1e-9 * max(np.ptp(f.x0[:, 0]), 1e-300)
        colour = "plastic_strain" if "plastic_strain" in f.step(step).fields else "part"
    sec.render_section(path, out, step=step, plane=plane, color=colour,
                       mirror="h" if one_side else None, decorate=decorate, verbose=False)
    print("wrote %s" % out)


def main(argv=None):
    return ur.cli_main(build_parser(), argv, _self_test, _run, errors=(TaylorError, IndexError),
                       require=ur.FIELDS_REQUIRED)


def _run(args, p):
    if args.band < 0:
        p.error("--band must be >= 0")
    if not all(math.isfinite(v) for v in (args.wall, args.band, *args.center)):
        p.error("--wall, --band and --center must be finite numbers")
    axis = args.axis
    if axis is None:
        with ur.open_fields(args.fields) as f:
            axis = "y" if f.dim == 2 else "z"
    res = measure_file(args.fields, "all" if args.all else [args.step], AXES.index(axis),
                       args.wall, tuple(args.center), args.band)
    if args.json:
        def clean(m):
            return {k: (None if isinstance(v, float) and math.isnan(v) else v) for k, v in m.items()}
        payload = [clean(m) for m in res] if args.all else clean(res[0])
        print(json.dumps(payload, indent=2))
        return 0
    if args.section:
        draw_section(args.fields, args.section, res[-1], AXES.index(axis), args.wall, tuple(args.center),
                     args.reference_length, args.reference_diameter, args.step if not args.all else -1)
    materials = materials_line(args.fields)
    for m in res:
        print(machine_line(m))
        print(human_line(m))
        if materials:
            print(materials)
        for key, ref, what in (("length_m", args.reference_length, "final length"),
                               ("footprint_diameter_m", args.reference_diameter, "footprint diameter")):
            if ref:
                print("%s: computed %.3f mm, experiment %.3f mm, difference %+.3f mm (%+.1f%%)"
                      % (what, m[key] * 1e3, ref * 1e3, (m[key] - ref) * 1e3, 100 * (m[key] / ref - 1)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
