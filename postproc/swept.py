#!/usr/bin/python3
"""The body of an axisymmetric udar result swept about its axis: a 3-D picture.

A 2D axisymmetric field file (x = r, y along the axis; triangles in z = 0) holds one
meridian section of a body of revolution. This script sweeps that section about the y axis
through ``--angle`` degrees (default 270: a cut-away that shows the inside): the outer
boundary of the mesh becomes the body's surface, and the two end sections are the
triangles themselves, coloured by part or by an element field as in section.py. Drawn with
matplotlib's Poly3DCollection (painter's order, no display needed).

    /usr/bin/python3 postproc/swept.py out/taylor_wg_2d.h5 -o swept.png
    /usr/bin/python3 postproc/swept.py out/taylor_wg_2d.h5 --color plastic_strain --angle 180 -o half.png
    /usr/bin/python3 postproc/swept.py --self-test

Library use: ``boundary_edges(connectivity)``, ``swept_polygons(coords, connectivity,
values, angle_deg, n_segments)``, ``render_swept(path, out, ...)``.
"""

import math
import os
import sys
import tempfile

if __package__:
    from . import udar_results as ur
    from . import section
else:
    import udar_results as ur  # run as a script, it stops with a message if numpy is missing
    import section
import numpy as np


class SweptError(Exception):
    """Bad request (not an axisymmetric file, bad angle, ...); the message says what."""


def boundary_edges(connectivity):
    """The edges used by one triangle only -> (k, 2) node pairs, each in its triangle's
    counter-clockwise order (so the outward normal of edge (a, b) is (dy, -dx))."""
    conn = np.asarray(connectivity)
    edges = np.concatenate([conn[:, [0, 1]], conn[:, [1, 2]], conn[:, [2, 0]]])
    key = np.sort(edges, axis=1)
    _, inverse, counts = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    return edges[counts[inverse.reshape(-1)] == 1]


def swept_polygons(coords, connectivity, values, angle_deg, n_segments):
    """Quadrilaterals of the swept boundary and the two end sections' triangles.

    Returns (polys (k, 4, 3) in m, values (k,), kind (k,): 0 surface, 1 end section). The
    body is swept from the angle 0 (the section in the x-y plane) through ``angle_deg``
    about the y axis; a point (r, y) at angle t is (r cos t, y, -r sin t). Edges on the axis
    (r = 0 at both ends) sweep to nothing and are left out. The surface quads take the value
    of the triangle each boundary edge belongs to."""
    x = np.asarray(coords, dtype=np.float64)
    conn = np.asarray(connectivity)
    r, y = x[:, 0], x[:, 1]
    t = np.radians(np.linspace(0.0, angle_deg, n_segments + 1))
    # the triangle of each boundary edge, for its value
    edges = boundary_edges(conn)
    tri_of = {}
    for e, tri in enumerate(conn):
        for a, b in ((tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0])):
            tri_of[(a, b)] = e
    owner = np.array([tri_of[(a, b)] for a, b in edges], dtype=np.int64)
    keep = (r[edges[:, 0]] > 0.0) | (r[edges[:, 1]] > 0.0)
    edges, owner = edges[keep], owner[keep]
    polys, vals, kind = [], [], []

    def point(n, ang):
        return np.column_stack([r[n] * np.cos(ang), y[n], -r[n] * np.sin(ang)])

    for k in range(n_segments):
        t0, t1 = t[k], t[k + 1]
        quad = np.stack([point(edges[:, 0], t0), point(edges[:, 1], t0),
                         point(edges[:, 1], t1), point(edges[:, 0], t1)], axis=1)
        polys.append(quad)
        vals.append(values[owner])
        kind.append(np.zeros(len(edges), dtype=np.int8))
    if angle_deg < 360.0:
        for ang in (t[0], t[-1]):
            tri = np.stack([point(conn[:, 0], ang), point(conn[:, 1], ang),
                            point(conn[:, 2], ang), point(conn[:, 2], ang)], axis=1)
            polys.append(tri)
            vals.append(values)
            kind.append(np.ones(len(conn), dtype=np.int8))
    return np.concatenate(polys), np.concatenate(vals), np.concatenate(kind)


def render_swept(path, out, step=-1, color="part", angle=270.0, segments=48, cmap=None,
                 vmin=None, vmax=None, elev=20.0, azim=40.0, title=None, size=None, dpi=150,
                 verbose=True):
    """Draw the swept body of axisymmetric field file ``path`` into image ``out``. Returns a
    dict with the step, time, the number of polygons and the swept volume (m³, of the end
    sections' triangles by Pappus: sum of 2 pi rbar A times angle/360)."""
    if not 0.0 < angle <= 360.0:
        raise SweptError("--angle must be in (0, 360] degrees, not %g" % angle)
    if segments < 1:
        raise SweptError("--segments must be at least 1")
    plt = ur.agg_pyplot()
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    import matplotlib.colors as mcolors
    with ur.open_fields(path) as f:
        if f.dim != 2:
            raise SweptError("%s: not a 2D file (its elements have %d nodes): only an "
                             "axisymmetric result can be swept; use section.py for 3D"
                             % (path, f.connectivity.shape[1]))
        idx = f.resolve_index(step)
        st = f.step(idx)
        coords = st.coordinates
        conn = f.connectivity
        if np.any(coords[:, 0] < 0.0):
            raise SweptError("%s: nodes at x < 0: an axisymmetric file has x = r >= 0" % path)
        if color == "part":
            values, label = f.part_id.astype(np.float64), "part"
        else:
            values, label = section.element_values(st, color, conn)
        if "fracture_state" in st.fields:
            gone = np.asarray(st.fields["fracture_state"]) > 1.5
            conn, values = conn[~gone], values[~gone]
        step_time, step_cycle, fname, ftitle = st.time, st.cycle, os.path.basename(path), f.title
    polys, vals, kind = swept_polygons(coords, conn, values, angle, segments)
    a = coords[conn]
    area = 0.5 * ((a[:, 1, 0] - a[:, 0, 0]) * (a[:, 2, 1] - a[:, 0, 1])
                  - (a[:, 2, 0] - a[:, 0, 0]) * (a[:, 1, 1] - a[:, 0, 1]))
    volume = float(np.sum(2.0 * math.pi * a[:, :, 0].mean(axis=1) * area)) * angle / 360.0
    polys_mm = polys * 1e3
    fig = plt.figure(figsize=size or (8.0, 8.0), constrained_layout=True)
    ax = fig.add_subplot(projection="3d")
    if color == "part":
        pids = np.unique(vals)
        palette = plt.get_cmap("tab10").colors
        face = np.array([palette[int(np.searchsorted(pids, v)) % len(palette)] for v in vals])
        face = np.column_stack([face, np.ones(len(face))])
    else:
        unit = ur.field_unit(color)
        lo = np.nanmin(vals) if vmin is None else vmin
        hi = np.nanmax(vals) if vmax is None else vmax
        scale, dunit = section._pretty_unit(unit, np.array([lo, hi], dtype=float))
        norm = mcolors.Normalize(vmin=lo * scale, vmax=hi * scale)
        cm = plt.get_cmap(cmap or "viridis")
        face = cm(norm(vals * scale))
        sm = plt.cm.ScalarMappable(norm=norm, cmap=cm)
        cb = fig.colorbar(sm, ax=ax, shrink=0.6, pad=0.1)
        cb.set_label("%s (%s)" % (label, dunit) if dunit else label)
    # a little shading of the swept surface by its facing, so the shape reads
    normal = np.cross(polys[:, 1] - polys[:, 0], polys[:, 3] - polys[:, 0])
    norm_len = np.linalg.norm(normal, axis=1)
    light = np.array([-0.4, 0.5, 0.75])
    shade = np.where(norm_len > 0, np.abs(normal @ light) / np.maximum(norm_len, 1e-300), 1.0)
    face[:, :3] *= np.where(kind == 0, 0.55 + 0.45 * shade, 1.0)[:, None]
    ax.add_collection3d(Poly3DCollection(polys_mm, facecolors=face, edgecolors="none"))
    lo3, hi3 = polys_mm.reshape(-1, 3).min(axis=0), polys_mm.reshape(-1, 3).max(axis=0)
    ax.set_xlim(lo3[0], hi3[0])
    ax.set_ylim(lo3[2], hi3[2])
    ax.set_zlim(lo3[1], hi3[1])
    # matplotlib's third axis is vertical: the body's axis (y) is drawn upwards
    for p in polys_mm:
        p[:, [1, 2]] = p[:, [2, 1]]
    ax.collections[0].set_verts(polys_mm)
    ax.set_box_aspect((hi3[0] - lo3[0], hi3[2] - lo3[2], hi3[1] - lo3[1]))
    ax.view_init(elev=elev, azim=azim)
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("z (mm)")
    ax.set_zlabel("y, the axis (mm)")
    if title is None:
        title = "%s%s\nswept %g degrees about the axis\nstep %d (cycle %d), t = %.3f µs" % (
            fname, " (%s)" % ftitle if ftitle else "", angle, idx, step_cycle, step_time * 1e6)
    ax.set_title(title, fontsize="medium")
    ur.save_figure(fig, out, dpi, SweptError)
    info = {"step": idx, "time_s": step_time, "polygons": int(len(polys)), "volume_m3": volume}
    if verbose:
        print("%s: step %d (t = %.4f us): %d polygons, swept volume %.6g mm^3, wrote %s"
              % (path, idx, step_time * 1e6, len(polys), volume * 1e9, out))
    return info


def _self_test(verbose=True):
    test = ur.SelfTest("swept", verbose)
    check = test.check
    # a 1 x 2 rectangle of 2 x 4 cells: its boundary is 2 (2 + 4) = 12 edges, ccw
    nodes, conn = ur.rectangle_tris(2, 4, (0.0, 0.0), (1.0, 2.0))
    edges = boundary_edges(conn)
    d = nodes[edges[:, 1]] - nodes[edges[:, 0]]
    mid = 0.5 * (nodes[edges[:, 0]] + nodes[edges[:, 1]])
    outward = np.column_stack([d[:, 1], -d[:, 0]])
    centre = np.array([0.5, 1.0])
    check(len(edges) == 12 and np.all(np.einsum("ij,ij->i", outward, mid[:, :2] - centre) > 0),
          "boundary of a structured rectangle: 12 edges, each with its outward normal")
    # the swept cylinder: the surface quads' area is that of the cylinder's side and ends
    R, H = 1.0, 2.0
    polys, vals, kind = swept_polygons(nodes, conn, np.zeros(len(conn)), 360.0, 720)
    quad_area = 0.5 * np.linalg.norm(np.cross(polys[:, 2] - polys[:, 0], polys[:, 3] - polys[:, 1]), axis=1)
    exact = 2 * math.pi * R * H + 2 * math.pi * R ** 2
    check(np.all(kind == 0) and abs(quad_area.sum() / exact - 1) < 1e-4,
          "full sweep of a rectangle: a closed cylinder's area %.6f (exact %.6f), no end sections"
          % (quad_area.sum(), exact))
    polys, vals, kind = swept_polygons(nodes, conn, np.arange(len(conn), dtype=float), 90.0, 8)
    check(np.sum(kind == 1) == 2 * len(conn) and np.all(vals[kind == 1][:len(conn)] == np.arange(len(conn))),
          "a quarter sweep: two end sections of every triangle, with their values")
    with tempfile.TemporaryDirectory(prefix="udar_swept_test_") as tmp:
        h5 = os.path.join(tmp, "cyl.h5")
        x = nodes * [1.0, 1.0, 0.0]
        ur.write_fields(h5, nodes, conn, [{"time": 1e-5, "cycle": 7, "coordinates": x,
                                           "fields": {"pressure": np.linspace(0.0, 1e9, len(conn))}}])
        out = os.path.join(tmp, "s.png")
        info = render_swept(h5, out, color="pressure", verbose=False)
        check(os.path.getsize(out) > 1000 and abs(info["volume_m3"] / (0.75 * math.pi * R ** 2 * H) - 1) < 1e-12,
              "render by pressure: the swept volume of 270 degrees, 3/4 pi R^2 H (Pappus), %.9f"
              % info["volume_m3"])
        rc, outp, _ = test.run_main(main, [h5, "--angle", "180", "-o", out])
        check(rc == 0 and "polygons" in outp, "CLI: by part, 180 degrees")
        nodes3, conn3 = ur.box_tets(1, 1, 1)
        h3 = os.path.join(tmp, "box.h5")
        ur.write_fields(h3, nodes3, conn3, [{"time": 0.0, "cycle": 0, "coordinates": nodes3}])
        test.raises(SweptError, "a 3D file is refused", render_swept, h3, out, verbose=False,
                    contains="not a 2D file")
        test.raises(SweptError, "an angle of 400 degrees is refused", render_swept, h5, out, angle=400.0,
                    verbose=False, contains="--angle")
    return test.finish()


def build_parser():
    p = ur.cli_parser(
        "swept.py",
        "Draw the body of a 2D axisymmetric udar result swept about its axis (3-D picture, "
        "coloured by part or by an element field; the end sections show the inside).",
        """examples:
  /usr/bin/python3 postproc/swept.py out/taylor_wg_2d.h5 -o swept.png
  /usr/bin/python3 postproc/swept.py out/taylor_wg_2d.h5 --color plastic_strain --angle 180 -o half.png
  /usr/bin/python3 postproc/swept.py --self-test""")
    ur.add_fields_argument(p)
    p.add_argument("-o", "--output", metavar="OUT.png", help="image file (default <case>_swept.png)")
    p.add_argument("--color", "--colour", default="part", metavar="part|FIELD",
                   help="colour by part (default) or by an element field (pressure, von_mises, ...)")
    p.add_argument("--angle", type=float, default=270.0, help="sweep, degrees (default 270: a cut-away)")
    p.add_argument("--segments", type=int, default=48, help="facets around the sweep (default 48)")
    p.add_argument("--cmap", help="matplotlib colormap for fields (default viridis)")
    p.add_argument("--vmin", type=float, help="colour range minimum, SI units of the field")
    p.add_argument("--vmax", type=float, help="colour range maximum, SI units of the field")
    p.add_argument("--elev", type=float, default=20.0, help="view elevation, degrees (default 20)")
    p.add_argument("--azim", type=float, default=40.0, help="view azimuth, degrees (default 40: into the cut-away)")
    p.add_argument("--title", help="figure title (default: file, sweep, step and time)")
    ur.add_figure_arguments(p, "figure size in inches (default 8 8)")
    return ur.add_self_test(p, "run the built-in checks, print PASS/FAIL")


def main(argv=None):
    return ur.cli_main(build_parser(), argv, _self_test, _run, errors=(SweptError, section.SectionError,
                                                                      IndexError),
                       require=ur.FIELDS_REQUIRED)


def _run(args, p):
    out = args.output or os.path.splitext(os.path.basename(args.fields))[0] + "_swept.png"
    render_swept(args.fields, out, step=args.step, color=args.color, angle=args.angle,
                 segments=args.segments, cmap=args.cmap, vmin=args.vmin, vmax=args.vmax,
                 elev=args.elev, azim=args.azim, title=args.title, size=args.size, dpi=args.dpi)
    return 0


if __name__ == "__main__":
    sys.exit(main())
