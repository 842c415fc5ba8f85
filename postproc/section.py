#!/usr/bin/python3
"""Plane section of a udar tetrahedral mesh, coloured by part or by an element field.

Every tetrahedron of the chosen step's deformed mesh is intersected with the plane
(vectorised numpy); each cut is a triangle or a quadrilateral, drawn in the plane's 2-D
coordinates (mm) with a matplotlib PolyCollection. A 2D file (axisymmetric or plane strain:
triangles in z = 0) is its own section: its triangles are drawn as they are (the plane
options do not apply), and ``--mirror`` reflects them about the axis x = 0 to show the
whole diameter of an axisymmetric body. When the step has particles (``&material eroded =
'particles'``), those within a slab about the plane are drawn over the section as small
markers, coloured as the elements (``--particle-slab``, ``--no-particles``).

    /usr/bin/python3 postproc/section.py out/taylor.h5 --plane y=0 --color von_mises -o vm.png
    /usr/bin/python3 postproc/section.py out/taylor.h5 --step 0 --color part --mirror -o parts.png
    /usr/bin/python3 postproc/section.py out/taylor.h5 --normal 1 -1 0 --point 0 0 0 -o oblique.png
    /usr/bin/python3 postproc/section.py --self-test

Library use: ``plane_from_spec``, ``plane_from_normal``, ``cut_tets``, ``polygon_areas``,
``particles_in_slab``, ``render_section``.
"""

import os
import re
import sys
import tempfile
import time as _time

if __package__:
    from . import udar_results as ur
else:
    import udar_results as ur  # run as a script, it stops with a message if numpy is missing
import numpy as np

AXES = "xyz"
# in-plane (horizontal, vertical) global axes for the axis-aligned planes
_AXIS_PLANE_UV = {0: (1, 2), 1: (0, 2), 2: (0, 1)}


class SectionError(Exception):
    """Bad section request (plane, field, ...); the message says what is wrong."""


# --------------------------------------------------------------------------------------
# plane
# --------------------------------------------------------------------------------------

class Plane:
    """A cutting plane with an orthonormal in-plane basis.

    ``point`` (m) and unit ``normal``; ``u`` (horizontal) and ``v`` (vertical) in-plane unit
    vectors; 2-D coordinates of a point X are ((X - point).u, (X - point).v) except for
    axis-aligned planes, whose 2-D coordinates are the two global coordinates themselves.
    """

    def __init__(self, point, normal, u, v, u_label, v_label, description):
        self.point = np.asarray(point, dtype=np.float64)
        self.normal = np.asarray(normal, dtype=np.float64)
        self.u = np.asarray(u, dtype=np.float64)
        self.v = np.asarray(v, dtype=np.float64)
        self.u_label, self.v_label, self.description = u_label, v_label, description

    def signed_distance(self, xyz):
        return (np.asarray(xyz) - self.point) @ self.normal

    def to2d(self, xyz):
        d = np.asarray(xyz) - self.point
        return np.stack([d @ self.u, d @ self.v], axis=-1)

    def __repr__(self):
        return "Plane(%s)" % self.description


def _axis_plane(axis, value):
    point = np.zeros(3)
    point[axis] = value
    normal = np.zeros(3)
    normal[axis] = 1.0
    iu, iv = _AXIS_PLANE_UV[axis]
    u, v = np.zeros(3), np.zeros(3)
    u[iu], v[iv] = 1.0, 1.0
    return Plane(point, normal, u, v, AXES[iu], AXES[iv], "%s = %g mm" % (AXES[axis], value * 1e3))


_LENGTH = re.compile(r"^\s*([xyzXYZ])\s*=\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(mm|m)?\s*$")


def plane_from_spec(spec):
    """'y=0', 'z=0.012', 'x=-2.5mm' (value in metres unless suffixed 'mm') -> Plane."""
    m = _LENGTH.match(spec)
    if not m:
        raise SectionError("cannot parse --plane %r: expected AXIS=VALUE such as y=0, z=0.012 or "
                           "x=-2.5mm (value in metres unless suffixed with mm)" % spec)
    axis = AXES.index(m.group(1).lower())
    value = float(m.group(2)) * (1e-3 if m.group(3) == "mm" else 1.0)
    return _axis_plane(axis, value)


def plane_from_normal(normal, point=(0.0, 0.0, 0.0)):
    """Plane through ``point`` (m) with normal ``normal`` (any length)."""
    n = np.asarray(normal, dtype=np.float64)
    p = np.asarray(point, dtype=np.float64)
    if n.shape != (3,) or p.shape != (3,) or not np.all(np.isfinite(n)) or not np.all(np.isfinite(p)):
        raise SectionError("--normal and --point need 3 finite numbers each")
    norm = np.linalg.norm(n)
    if norm == 0.0:
        raise SectionError("--normal 0 0 0 is not a direction")
    n = n / norm
    nz = np.nonzero(np.abs(n) > 1e-14)[0]
    if len(nz) == 1:  # axis-aligned: keep the global axes and labels
        axis = int(nz[0])
        pl = _axis_plane(axis, float(p[axis]))
        if n[axis] < 0:
            pl.description += " (normal -%s)" % AXES[axis]
        return pl
    up = np.array([0.0, 0.0, 1.0]) if abs(n[2]) < 0.9 else np.array([0.0, 1.0, 0.0])
    v = up - (up @ n) * n
    v /= np.linalg.norm(v)
    u = np.cross(n, v)
    if u[np.argmax(np.abs(u))] < 0:  # horizontal axis: largest component positive
        u = -u
    fmt = lambda a: "(%s)" % ", ".join("%.3g" % (c + 0.0) for c in np.round(a, 12))
    return Plane(p, n, u, v, "u = %s" % fmt(u), "v = %s" % fmt(v),
                 "normal %s through %s mm" % (fmt(n), fmt(p * 1e3)))


# --------------------------------------------------------------------------------------
# tetrahedron / plane intersection
# --------------------------------------------------------------------------------------

def _build_edge_table():
    """For each of the 16 above/below patterns of the 4 vertices, the 4 cut edges (i, j),
    ordered around the polygon (triangles repeat their last vertex)."""
    table = np.zeros((16, 4, 2), dtype=np.int64)
    nverts = np.zeros(16, dtype=np.int64)
    for mask in range(16):
        pos = [k for k in range(4) if mask >> k & 1]
        neg = [k for k in range(4) if not mask >> k & 1]
        if len(pos) in (1, 3):
            lone, others = (pos[0], neg) if len(pos) == 1 else (neg[0], pos)
            edges = [(lone, o) for o in others]
            edges.append(edges[-1])
            nverts[mask] = 3
        elif len(pos) == 2:
            (a, b), (c, e) = pos, neg
            # a-c, a-e share a; a-e, b-e share e; b-e, b-c share b; b-c, a-c share c: a cycle
            edges = [(a, c), (a, e), (b, e), (b, c)]
            nverts[mask] = 4
        else:
            continue
        table[mask] = edges
    return table, nverts


_EDGE_TABLE, _EDGE_NVERTS = _build_edge_table()


def cut_tets(coords, connectivity, point, normal):
    """Intersect tetrahedra with the plane through ``point`` with unit ``normal``.

    A vertex with signed distance > 0 is 'above', otherwise 'below' (so a face lying in the
    plane is produced exactly once and the cut area is exact for conforming meshes).

    Returns (elem (k,) indices of the cut tets, poly (k, 4, 3) polygon vertices in 3-D,
    nverts (k,) 3 or 4). Triangles repeat their third vertex as the fourth.
    """
    coords = np.asarray(coords, dtype=np.float64)
    conn = np.asarray(connectivity)
    d = (coords - np.asarray(point, dtype=np.float64)) @ np.asarray(normal, dtype=np.float64)
    above = d[conn] > 0.0                                     # (m, 4)
    mask = above @ np.array([1, 2, 4, 8])                     # 0..15
    elem = np.nonzero((mask != 0) & (mask != 15))[0]
    edges = _EDGE_TABLE[mask[elem]]                           # (k, 4, 2) local vertex numbers
    nodes = conn[elem]                                        # (k, 4)
    ia = np.take_along_axis(nodes, edges[:, :, 0], axis=1)    # (k, 4) global node numbers
    ib = np.take_along_axis(nodes, edges[:, :, 1], axis=1)
    da, db = d[ia], d[ib]
    t = da / (da - db)        # one of da, db is > 0 and the other <= 0: never 0/0
    xa = coords[ia]
    poly = xa + t[:, :, None] * (coords[ib] - xa)
    return elem, poly, _EDGE_NVERTS[mask[elem]]


def polygon_areas(poly2d):
    """Areas of (k, n, 2) polygons (shoelace, absolute value)."""
    x, y = poly2d[:, :, 0], poly2d[:, :, 1]
    return 0.5 * np.abs(np.sum(x * np.roll(y, -1, axis=1) - np.roll(x, -1, axis=1) * y, axis=1))


def part_outlines(poly2d, parts):
    """The outline of each part in a section: the polygon edges that border no other polygon
    of the same part (the body's boundary and the interfaces between parts) -> (m, 2, 2)
    segments. Edges are matched by their end points rounded to 1e-9 of the section's size
    (the cut points of a face two elements share come from the same nodes)."""
    poly2d = np.asarray(poly2d, dtype=float)
    if poly2d.size == 0:
        return np.zeros((0, 2, 2))
    a = poly2d
    b = np.roll(poly2d, -1, axis=1)
    seg = np.stack([a, b], axis=2).reshape(-1, 2, 2)          # (k*n, 2 ends, 2)
    owner = np.repeat(np.asarray(parts), poly2d.shape[1])
    real = np.any(seg[:, 0] != seg[:, 1], axis=1)             # a repeated vertex is no edge
    seg, owner = seg[real], owner[real]
    size = max(float(np.ptp(poly2d.reshape(-1, 2), axis=0).max()), 1e-300)
    q = np.round(seg / (1e-9 * size)).astype(np.int64)
    # the same edge whichever way round: its lower end first
    swap = (q[:, 0, 0] > q[:, 1, 0]) | ((q[:, 0, 0] == q[:, 1, 0]) & (q[:, 0, 1] > q[:, 1, 1]))
    q[swap] = q[swap][:, ::-1]
    key = np.column_stack([q.reshape(-1, 4), owner])
    _, inverse, counts = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    return seg[counts[inverse.ravel()] == 1]


def planar_polygons(coords, connectivity):
    """A 2D mesh's triangles as the section -> (elem (k,), poly2d (k, 4, 2) in m), each
    triangle's third vertex repeated as the fourth (as section_polygons gives cut triangles)."""
    elem = np.arange(connectivity.shape[0])
    return elem, np.asarray(coords)[connectivity][:, [0, 1, 2, 2], :2]


def section_polygons(coords, connectivity, plane):
    """Cut with a ``Plane`` -> (elem (k,), poly2d (k, 4, 2) in m).

    If the plane only touches the mesh from one side (e.g. it is the boundary face of a
    half model lying on the plane's negative side), the cut is retried with the opposite
    vertex classification so that the faces lying in the plane are returned.
    """
    elem, poly, _ = cut_tets(coords, connectivity, plane.point, plane.normal)
    poly2 = plane.to2d(poly)
    if not np.any(polygon_areas(poly2) > 0.0):
        elem_b, poly_b, _ = cut_tets(coords, connectivity, plane.point, -plane.normal)
        poly2_b = plane.to2d(poly_b)
        if np.any(polygon_areas(poly2_b) > 0.0):
            return elem_b, poly2_b
    return elem, poly2


# --------------------------------------------------------------------------------------
# colouring
# --------------------------------------------------------------------------------------

def _pretty_unit(unit, values):
    """(scale factor, display unit) for stresses in Pa -> kPa/MPa/GPa."""
    return ur.si_scale(values, unit) if unit == "Pa" else (1.0, unit)


def element_values(step, name, connectivity):
    """Per-element values of field ``name``: element scalars as is, element vectors as their
    magnitude, node fields averaged over the 4 nodes. Returns (values (n_elems,), label)."""
    fields = step.fields
    if name not in fields:
        elem = fields.elem_fields
        raise SectionError("%s: step %d has no field %r; element fields: %s; node fields: %s "
                           "(or use --color part)" % (step._file.path, step.index, name,
                                                     ", ".join(elem) or "none",
                                                     ", ".join(fields.node_fields) or "none"))
    loc = fields.location(name)
    a = np.asarray(fields[name], dtype=np.float64)
    label = name
    if a.ndim > 1:
        a = np.linalg.norm(a.reshape(a.shape[0], -1), axis=1)
        label = "|%s|" % name
    if loc == "elem":
        return a, label
    if loc == "node":
        return a[connectivity].mean(axis=1), label + " (node average)"
    raise SectionError("%s: field %r has %d entries, neither n_nodes=%d nor n_elems=%d"
                       % (step._file.path, name, a.shape[0], step._file.n_nodes, step._file.n_elems))


# --------------------------------------------------------------------------------------
# particles
# --------------------------------------------------------------------------------------

def particles_in_slab(xyz, plane, half_width):
    """Mask of the points ``xyz`` (n, 3) whose distance from ``plane`` is at most
    ``half_width`` (m): the particles drawn on the section."""
    xyz = np.asarray(xyz, dtype=np.float64).reshape(-1, 3)
    return np.abs(plane.signed_distance(xyz)) <= half_width


def particle_values(particles, color):
    """Values of the particles (``udar_results.Particles``) for the colouring ``color`` ->
    (values (count,) or None when the particles have no such field, label): the part for
    'part', a stored particle field as is (a vector as its magnitude)."""
    if color == "part":
        return (np.asarray(particles["part_id"]) if "part_id" in particles else None), "part"
    if color not in particles or color in ("coordinates", "element"):
        return None, color
    a = np.asarray(particles[color], dtype=np.float64)
    if a.ndim > 1:
        return np.linalg.norm(a.reshape(a.shape[0], -1), axis=1), "|%s|" % color
    return a, color


# --------------------------------------------------------------------------------------
# drawing
# --------------------------------------------------------------------------------------

def render_section(path, out, step=-1, plane=None, color="part", mirror=None, cmap=None,
                   vmin=None, vmax=None, part_names=None, edges=False, undeformed=False,
                   xlim=None, ylim=None, title=None, size=None, dpi=150, time_us=None,
                   verbose=True, particles=True, particle_slab=None, decorate=None):
    """Draw the section of field file ``path`` into image ``out`` (``decorate(ax)``, if given,
    draws more on the axes, in mm, before the file is written). Returns a dict with the
    numbers of cut tets, total cut area (m²), step index and time, and, when the step has
    particles, ``particles`` (how many lie in the slab), ``particles_total``,
    ``particle_slab_m`` and ``particles_xy_mm`` (the markers' picture coordinates, mirrored
    copies included).

    ``particles``: draw the step's particles lying within ``particle_slab`` (m; default half
    the median particle spacing ``udar_results.particle_spacing``) of the plane, coloured as
    the elements where the particles have the field ``color`` (else in a neutral grey).
    They are not drawn with ``undeformed``."""
    plt = ur.agg_pyplot()
    from matplotlib.collections import PolyCollection
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    plane = plane or plane_from_spec("y=0")
    t0 = _time.perf_counter()
    with ur.open_fields(path) as f:
        idx = f.nearest_step(time_us * 1e-6) if time_us is not None else f.resolve_index(step)
        st = f.step(idx)
        coords = f.x0 if undeformed else st.coordinates
        conn = f.connectivity
        planar = f.dim == 2
        if planar:
            plane = plane_from_spec("z=0")
            plane.u_label, plane.v_label, plane.description = "x = r", "y", "2D mesh (z = 0)"
            elem, poly = planar_polygons(coords, conn)
        else:
            elem, poly = section_polygons(coords, conn, plane)
        if elem.size == 0:
            dist = plane.signed_distance(coords)
            raise SectionError("%s: the plane %s does not cut the mesh at step %d (node distances "
                               "from the plane span %.6g .. %.6g mm)" % (
                                   path, plane.description, idx, dist.min() * 1e3, dist.max() * 1e3))
        keep = polygon_areas(poly) > 0.0  # tets touching the plane at an edge or a vertex
        if "fracture_state" in st.fields and not undeformed:
            # eroded elements (state 2) are gone from the calculation: not drawn
            keep &= np.asarray(st.fields["fracture_state"])[elem] < 1.5
        elem, poly = elem[keep], poly[keep]
        if elem.size == 0:
            raise SectionError("%s: the plane %s only touches the mesh at step %d (section area "
                               "0; e.g. an edge of a half or quarter model)" % (path, plane.description, idx))
        file_pids = list(f.part_ids)
        deck_names = f.part_names
        part_values = f.part_id[elem]
        if color == "part":
            values = part_values
        else:
            allvals, label = element_values(st, color, conn)
            values = allvals[elem]
        # particles within the slab: 2-D positions (m), colour values, how many of how many
        pt = st.particles if particles and not undeformed else None
        p2d, pvals, p_total, slab = np.zeros((0, 2)), None, 0, None
        if pt is not None and pt.count:
            slab = particle_slab if particle_slab is not None else 0.5 * ur.particle_spacing(pt)
            if not np.isfinite(slab) or slab < 0.0:
                raise SectionError("%s: cannot estimate the particle spacing from mass/density at "
                                   "step %d; give --particle-slab (m) or --no-particles" % (path, idx))
            p_total = pt.count
            sel = particles_in_slab(pt.coordinates, plane, slab)
            p2d = plane.to2d(pt.coordinates[sel])
            pvals, _ = particle_values(pt, color)
            if pvals is not None:
                pvals = pvals[sel]
        fname = os.path.basename(path)
        ftitle = f.title
        step_time, step_cycle = st.time, st.cycle
    area = float(polygon_areas(poly).sum())
    t_cut = _time.perf_counter() - t0

    poly_mm = poly * 1e3
    mirror_lines = []
    if mirror not in (None, "h", "v", "hv"):
        raise SectionError("mirror must be None, 'h', 'v' or 'hv', not %r" % (mirror,))
    if mirror:
        copies = [poly_mm]
        flips = {"h": [(-1, 1)], "v": [(1, -1)], "hv": [(-1, 1), (1, -1), (-1, -1)]}[mirror]
        for sx, sy in flips:
            copies.append(poly_mm * np.array([sx, sy]))
        poly_mm = np.concatenate(copies)
        values = np.concatenate([values] * len(copies))
        part_values = np.concatenate([part_values] * len(copies))
        mirror_lines = list(mirror)
    p_mm = p2d * 1e3
    n_drawn = len(p_mm)
    if mirror and slab is not None:
        p_mm = np.concatenate([p_mm] + [p_mm * np.array([sx, sy]) for sx, sy in flips])
        if pvals is not None:
            pvals = np.concatenate([pvals] * (len(flips) + 1))

    lo2, hi2 = poly_mm.reshape(-1, 2).min(axis=0), poly_mm.reshape(-1, 2).max(axis=0)
    if len(p_mm):  # the view holds the particles drawn too
        lo2, hi2 = np.minimum(lo2, p_mm.min(axis=0)), np.maximum(hi2, p_mm.max(axis=0))
    if xlim:
        lo2[0], hi2[0] = min(xlim), max(xlim)
    if ylim:
        lo2[1], hi2[1] = min(ylim), max(ylim)
    if size is None:  # fit the figure to the section's aspect ratio
        dx, dy = max(hi2[0] - lo2[0], 1e-12), max(hi2[1] - lo2[1], 1e-12)
        aspect = dy / dx
        if aspect >= 1.0:
            h_ax = 7.0
            w_ax = max(2.5, h_ax / aspect)
        else:
            w_ax = 9.0
            h_ax = max(2.5, w_ax * aspect)
        size = (w_ax + 2.6, h_ax + 1.4)
    fig, ax = plt.subplots(figsize=size, constrained_layout=True)
    lw = 0.3 if edges else 0.6
    p_kw = dict(s=9.0, marker="o", edgecolors="0.1", linewidths=0.3, zorder=3)
    p_neutral = "0.6"
    p_handle = None
    if slab is not None:
        p_label = "particles within %.3g mm of the plane: %s" % (
            slab * 1e3, "%d of %d" % (n_drawn, p_total) if n_drawn else "none of %d" % p_total)
        grey = pvals is None
        if grey:
            p_label += " (no %s: grey)" % color
        p_handle = Line2D([], [], ls="none", marker="o", markersize=4,
                          markerfacecolor=p_neutral if grey else "w",
                          markeredgecolor="0.1", markeredgewidth=0.5, label=p_label)
    if color == "part":
        pids = np.unique(values) if pvals is None else np.union1d(values, pvals)
        cmap_name = "tab10" if len(pids) <= 10 else "tab20"
        palette = plt.get_cmap(cmap_name).colors
        lookup = {p: palette[i % len(palette)] for i, p in enumerate(pids)}
        facecolors = np.array([lookup[p] for p in pids])[np.searchsorted(pids, values)]
        pc = PolyCollection(poly_mm, facecolors=facecolors,
                            edgecolors="0.2" if edges else facecolors, linewidths=lw)
        ax.add_collection(pc)
        names = {p: "%s (part %d)" % (nm, p) for p, nm in deck_names.items()}
        if part_names:
            for i, p in enumerate(file_pids):
                if i < len(part_names):
                    names[p] = part_names[i]
        handles = [Patch(facecolor=lookup[p], edgecolor="0.2",
                         label=names.get(p, "part %d" % p)) for p in pids]
        if len(p_mm):
            ax.scatter(p_mm[:, 0], p_mm[:, 1], **p_kw, c=p_neutral if pvals is None else
                       np.array([lookup[p] for p in pids])[np.searchsorted(pids, pvals)])
        if p_handle is not None:
            handles.append(p_handle)
        ax.legend(handles=handles, loc="best", fontsize="small", framealpha=0.8)
    else:
        import matplotlib.colors as mcolors
        unit = ur.field_unit(color)
        lo = np.nanmin(values) if vmin is None else vmin
        hi = np.nanmax(values) if vmax is None else vmax
        scale, dunit = _pretty_unit(unit, np.array([lo, hi], dtype=float))
        # a field of both signs (pressure, a stress or velocity component): a
        # diverging map with white at zero, unless a map was asked for
        signed = lo < 0.0 < hi
        cm = plt.get_cmap(cmap or ("RdBu_r" if signed else "viridis")).copy()
        cm.set_bad("0.6")
        if signed and cmap is None:
            norm = mcolors.TwoSlopeNorm(vmin=lo * scale, vcenter=0.0, vmax=hi * scale)
        else:
            norm = mcolors.Normalize(vmin=lo * scale, vmax=hi * scale)
        pc = PolyCollection(poly_mm, cmap=cm, norm=norm, linewidths=lw,
                            edgecolors="0.2" if edges else "face")
        pc.set_array(np.ma.masked_invalid(values * scale))
        ax.add_collection(pc)
        cb = fig.colorbar(pc, ax=ax, shrink=0.9)
        cb.set_label("%s (%s)" % (label, dunit) if dunit else label)
        if len(p_mm):  # on the elements' colour scale (beyond it: its end colours)
            if pvals is None:
                ax.scatter(p_mm[:, 0], p_mm[:, 1], c=p_neutral, **p_kw)
            else:
                ax.scatter(p_mm[:, 0], p_mm[:, 1], c=pvals * scale, cmap=cm, norm=norm,
                           plotnonfinite=True, **p_kw)
        if p_handle is not None:
            ax.legend(handles=[p_handle], loc="best", fontsize="small", framealpha=0.8)

    # the parts' outlines (the body's boundary and the interfaces)
    from matplotlib.collections import LineCollection
    outline_parts = part_values if part_values is not None else values
    ax.add_collection(LineCollection(part_outlines(poly_mm, outline_parts), colors="k", linewidths=0.8))
    for m in mirror_lines:
        if m == "h":
            ax.axvline(0.0, color="k", lw=0.6, ls="--", alpha=0.5)
        else:
            ax.axhline(0.0, color="k", lw=0.6, ls="--", alpha=0.5)
    ax.set_aspect("equal")
    pad = 0.03 * max(hi2 - lo2) if np.any(hi2 > lo2) else 1.0
    ax.set_xlim(xlim if xlim else (lo2[0] - pad, hi2[0] + pad))
    ax.set_ylim(ylim if ylim else (lo2[1] - pad, hi2[1] + pad))
    ax.set_xlabel("%s (mm)" % plane.u_label)
    ax.set_ylabel("%s (mm)" % plane.v_label)
    if title is None:
        title = "%s%s\nsection %s\nstep %d (cycle %d), t = %.3f µs%s" % (
            fname, " (%s)" % ftitle if ftitle else "", plane.description, idx, step_cycle,
            step_time * 1e6, ", undeformed" if undeformed else "")
    ax.set_title(title, fontsize="medium")
    if decorate is not None:
        decorate(ax)
    ur.save_figure(fig, out, dpi, SectionError)
    info = {"file": path, "out": out, "step": idx, "cycle": step_cycle, "time_s": step_time,
            "cut_tets": int(elem.size), "area_m2": area, "seconds_cut": t_cut,
            "seconds_total": _time.perf_counter() - t0}
    if slab is not None:
        info.update(particles=n_drawn, particles_total=p_total, particle_slab_m=slab,
                    particles_xy_mm=p_mm)
    if verbose:
        print("%s: step %d (t = %.4f us), plane %s: %d %s, section area %.6g mm^2, %s"
              "wrote %s (%.2f s)" % (path, idx, step_time * 1e6, plane.description, elem.size,
                                     "triangles drawn" if poly.shape[0] and planar else "tets cut",
                                     area * 1e6, "" if slab is None else
                                     "%d of %d particles within %.3g mm of the plane, " % (
                                         n_drawn, p_total, slab * 1e3),
                                     out, info["seconds_total"]))
    return info


# --------------------------------------------------------------------------------------
# self-test
# --------------------------------------------------------------------------------------

def _self_test(verbose=True):
    """Known cut areas of a unit cube of tets, plus an end-to-end render. Returns True if OK."""
    test = ur.SelfTest("section", verbose)
    check = test.check

    # outlines: a unit square as two triangles (third vertex repeated, as cut triangles are)
    square = np.array([[[0, 0], [1, 0], [1, 1], [1, 1]], [[0, 0], [1, 1], [0, 1], [0, 1]]], dtype=float)
    one = part_outlines(square, [1, 1])
    two = part_outlines(square, [1, 2])
    check(len(one) == 4 and abs(np.linalg.norm(one[:, 1] - one[:, 0], axis=1).sum() - 4.0) < 1e-12,
          "one part's outline: the square's 4 sides (perimeter 4)")
    check(len(two) == 6 and abs(np.linalg.norm(two[:, 1] - two[:, 0], axis=1).sum() - 4.0 - 2 * 2 ** 0.5) < 1e-12,
          "two parts: each part's outline, the diagonal between them drawn from both sides")

    def area_of(nodes, conn, point, normal):
        pl = plane_from_normal(normal, point)
        elem, poly2 = section_polygons(nodes, conn, pl)
        dist = np.abs(pl.signed_distance(cut_tets(nodes, conn, pl.point, pl.normal)[1]))
        return polygon_areas(poly2).sum(), len(elem), dist.max() if dist.size else 0.0

    # quads must be ordered around the polygon: a bow-tie ordering would give a smaller area
    cases = [
        ("unit cube 5^3, mid-plane z=0.5 (cuts tet interiors)", (5, 5, 5), (0.5, 0.5, 0.5), (0, 0, 1), 1.0),
        ("unit cube 4^3, mid-plane z=0.5 (through tet faces)", (4, 4, 4), (0.5, 0.5, 0.5), (0, 0, 1), 1.0),
        ("unit cube 4^3, plane x=0.3", (4, 4, 4), (0.3, 0.0, 0.0), (1, 0, 0), 1.0),
        ("unit cube 3x4x5, plane y=0.5 normal -y", (3, 4, 5), (0.0, 0.5, 0.0), (0, -1, 0), 1.0),
        ("unit cube 6^3, diagonal plane x+y=1 (area sqrt 2)", (6, 6, 6), (0.5, 0.5, 0.5), (1, 1, 0), np.sqrt(2.0)),
        ("unit cube 5^3, plane x+y+z=1.5 (hexagon 3*sqrt(3)/4)", (5, 5, 5), (0.5, 0.5, 0.5), (1, 1, 1), 3.0 * np.sqrt(3.0) / 4.0),
        ("unit cube 7^3, oblique plane through the centre", (7, 7, 7), (0.5, 0.5, 0.5), (0.3, -0.2, 1.0), None),
    ]
    for what, n, point, normal, expected in cases:
        nodes, conn = ur.box_tets(*n)
        a, k, dmax = area_of(nodes, conn, point, normal)
        if expected is None:
            nn = np.asarray(normal, float) / np.linalg.norm(normal)
            # plane z = 0.5 - (0.3 x - 0.2 y)/1: stays inside the cube, area = 1/|n_z|
            expected = 1.0 / abs(nn[2])
        check(abs(a - expected) < 1e-12 and dmax < 1e-12,
              "%s: area %.15f (expected %.15f, %d tets cut)" % (what, a, expected, k))

    # random rigid motion of the mesh and plane: area still 1
    rng = np.random.default_rng(12345)
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    shift = rng.normal(size=3)
    nodes, conn = ur.box_tets(6, 5, 4)
    moved = nodes @ q.T + shift
    a, k, _ = area_of(moved, conn, np.array([0.5, 0.5, 0.37]) @ q.T + shift, np.array([0, 0, 1.0]) @ q.T)
    check(abs(a - 1.0) < 1e-12, "rotated and translated cube, plane z=0.37: area %.15f" % a)

    # planes on the boundary faces of the cube: the faces in the plane are the section
    nodes, conn = ur.box_tets(3, 4, 5)
    for spec in ("y=0", "y=1", "x=1", "z=0"):
        pl = plane_from_spec(spec)
        a = polygon_areas(section_polygons(nodes, conn, pl)[1]).sum()
        check(abs(a - 1.0) < 1e-12, "plane %s on a boundary face of the cube: area %.15f" % (spec, a))

    # a plane missing the mesh
    nodes, conn = ur.box_tets(3, 3, 3)
    elem, _, _ = cut_tets(nodes, conn, (0, 0, 2.0), (0, 0, 1))
    check(elem.size == 0, "plane outside the mesh cuts nothing")

    # plane spec parsing
    pl = plane_from_spec("x=-2.5mm")
    check(np.allclose(pl.point, [-2.5e-3, 0, 0]) and pl.u_label == "y" and pl.v_label == "z",
          "plane spec 'x=-2.5mm'")
    test.raises(SectionError, "bad plane spec rejected", plane_from_spec, "q=1")

    # end-to-end: synthetic field file with two parts, pressure, rendering with mirror
    with tempfile.TemporaryDirectory(prefix="udar_section_test_") as tmp:
        R, L = 3.8e-3, 25.4e-3
        nodes, conn = ur.cylinder_tets(R, L, 6, 20, "quarter")
        cen = nodes[conn].mean(axis=1)
        pid = np.where(cen[:, 2] < 0.2 * L, 2, 1).astype(np.int32)
        h5 = os.path.join(tmp, "cyl.h5")
        steps = [{"time": 0.0, "cycle": 0, "coordinates": nodes,
                  "fields": {"pressure": 1e9 * cen[:, 2] / L, "velocity": np.zeros_like(nodes)}},
                 {"time": 2e-5, "cycle": 500, "coordinates": nodes * [1.1, 1.1, 0.8],
                  "fields": {"pressure": 2e9 * cen[:, 0] / R, "velocity": np.ones_like(nodes)}}]
        ur.write_fields(h5, nodes, conn, steps, part_id=pid, title="quarter cylinder")
        out1, out2 = os.path.join(tmp, "a.png"), os.path.join(tmp, "b.png")
        info = render_section(h5, out1, step=0, plane=plane_from_spec("y=0"), color="part",
                              mirror="h", verbose=False)
        check(os.path.getsize(out1) > 1000, "render by part with --mirror")
        check(abs(info["area_m2"] - R * L) < 1e-12 * R * L * 1e3,
              "quarter cylinder section y=0 area R*L: %.9g mm^2 (expected %.9g)"
              % (info["area_m2"] * 1e6, R * L * 1e6))
        info = render_section(h5, out2, step=-1, plane=plane_from_spec("z=10mm"), color="pressure",
                              verbose=False)
        check(os.path.getsize(out2) > 1000 and info["step"] == 1, "render by pressure, step -1")
        render_section(h5, out2, step=-1, plane=plane_from_spec("y=0"), color="velocity", verbose=False)
        check(True, "render by node field (averaged)")
        rc, out, _ = test.run_main(main, [h5, "--step", "-1", "--plane", "z=5mm", "--color", "pressure",
                                   "--mirror-axis", "hv", "--edges", "-o", out2])
        check(rc == 0 and "tets cut" in out, "CLI: --plane z=5mm --mirror-axis hv")
        rc, _, err = test.run_main(main, [h5, "--color", "temperature", "-o", out2])
        check(rc == 1 and "no field 'temperature'" in err, "CLI: unknown field -> exit 1")
        test.raises(SectionError, "unknown field rejected, message lists the fields", render_section,
                    h5, out2, color="nosuchfield", verbose=False, contains="pressure")
        test.raises(SectionError, "plane missing the mesh rejected", render_section, h5, out2,
                    plane=plane_from_spec("z=1"), verbose=False, contains="does not cut")
        info = render_section(h5, out1, color="part", verbose=False)
        check("particles" not in info, "file without particles: no particle keys in the result")

        # particles (step 1): distances from the plane y = 0 of -2h .. 2h, h = the slab
        h = 0.25e-3
        py = np.array([0.0, 0.5, -0.5, 1.0, -1.0, 1.0001, -1.0001, 2.0]) * h
        n = len(py)
        pxyz = np.column_stack([np.linspace(1e-3, 3e-3, n), py, np.linspace(2e-3, 20e-3, n)])
        in_slab = np.abs(py) <= h
        pts = {"coordinates": pxyz, "velocity": np.tile([3.0, 4.0, 0.0], (n, 1)),
               # (mass/density)^(1/3) = 0.4, 0.5 (x6), 0.6 mm: median 0.5 mm, half of it h
               "mass": 7800.0 * np.array([0.4] + [0.5] * (n - 2) + [0.6]) ** 3 * 1e-9,
               "density": np.full(n, 7800.0), "pressure": np.linspace(0.0, 2e9, n),
               "specific_internal_energy": np.ones(n), "temperature": np.full(n, 300.0),
               "plastic_strain": np.full(n, 1.5), "part_id": np.array([1, 2, 3, 1, 2, 1, 2, 1]),
               "element": np.arange(n)}
        psteps = [dict(steps[0], particles={}), dict(steps[1], particles=pts)]
        psteps[1]["fields"] = dict(steps[1]["fields"], von_mises=np.full(len(conn), 1e8))
        h5p = os.path.join(tmp, "cyl_particles.h5")
        ur.write_fields(h5p, nodes, conn, psteps, part_id=pid, title="quarter cylinder")
        pl = plane_from_spec("y=0")
        check(np.array_equal(particles_in_slab(pxyz, pl, h), in_slab),
              "particles_in_slab: |distance| <= h, both sides, h itself included (5 of 8)")
        oblique = plane_from_normal((1, 1, 0), (0, 0, 0))
        q = np.array([[1, 1, 0], [1, 1, 7], [-1, 1, 0], [2, 0, 0], [0, -2, 5]]) * 0.5e-3
        # distances (x + y)/sqrt(2): 0.707, 0.707, 0, 0.707, -0.707 mm
        check(particles_in_slab(q, oblique, 0.75e-3).tolist() == [True] * 5
              and particles_in_slab(q, oblique, 0.7e-3).tolist() == [False, False, True, False, False],
              "particles_in_slab: oblique plane")
        info0 = render_section(h5p, out1, step=0, color="part", verbose=False)
        check("particles" not in info0, "particles group with count 0: nothing drawn, no legend entry")
        info = render_section(h5p, out1, step=1, color="part", verbose=False)
        # (two particles lie exactly h from the plane: whether a slab computed
        # as a cube root takes them is the rounding of this machine's cbrt)
        drawn = particles_in_slab(pxyz, pl, info["particle_slab_m"])
        check(abs(info["particle_slab_m"] - h) < 1e-15 and info["particles"] == drawn.sum()
              and drawn.sum() in (3, 5) and info["particles_total"] == n,
              "default slab half the median spacing: %.6g mm (%.6g), %d of %d particles drawn (3 or 5)"
              % (info["particle_slab_m"] * 1e3, h * 1e3, info["particles"], n))
        check(np.allclose(info["particles_xy_mm"], pxyz[drawn][:, [0, 2]] * 1e3, rtol=0, atol=1e-12),
              "particle markers at their (x, z) in mm")
        info = render_section(h5p, out1, step=1, color="pressure", mirror="h",
                              particle_slab=1.5 * h, verbose=False)
        sel = np.abs(py) <= 1.5 * h
        xz = pxyz[sel][:, [0, 2]] * 1e3
        check(info["particles"] == 7 and np.allclose(info["particles_xy_mm"],
                                                     np.concatenate([xz, xz * [-1, 1]]), atol=1e-12),
              "particle_slab 1.5 h: 7 particles, mirrored with the mesh (14 markers)")
        pv = ur.open_fields(h5p)
        try:
            ppt = pv.step(1).particles
            check(particle_values(ppt, "part")[0].tolist() == [1, 2, 3, 1, 2, 1, 2, 1]
                  and np.allclose(particle_values(ppt, "velocity")[0], 5.0)
                  and particle_values(ppt, "von_mises")[0] is None
                  and np.array_equal(particle_values(ppt, "pressure")[0], pts["pressure"]),
                  "particle_values: part, |velocity|, pressure as stored, none for von_mises")
        finally:
            pv.close()
        render_section(h5p, out2, step=1, plane=plane_from_spec("z=10mm"), color="velocity",
                       particle_slab=2e-3, verbose=False)
        check(os.path.getsize(out2) > 1000, "render by a node field with particles (|velocity|)")
        info = render_section(h5p, out1, step=1, particles=False, verbose=False)
        check("particles" not in info, "particles=False: not drawn")
        rc, out, _ = test.run_main(main, [h5p, "--color", "von_mises", "--mirror", "-o", out2])
        check(rc == 0 and ("%d of 8 particles within 0.25 mm of the plane" % drawn.sum()) in out,
              "CLI: an element field the particles lack (von_mises): particles in grey")
        rc, out, _ = test.run_main(main, [h5p, "--color", "part", "--particle-slab", "1e-3", "-o", out2])
        check(rc == 0 and "8 of 8 particles within 1 mm of the plane" in out,
              "CLI: --particle-slab 1e-3 draws all 8")
        rc, out, _ = test.run_main(main, [h5p, "--no-particles", "-o", out2])
        check(rc == 0 and "particles within" not in out, "CLI: --no-particles")
        test.raises(SystemExit, "CLI: --particle-slab -1 is a usage error", test.run_main, main,
                    [h5p, "--particle-slab", "-1", "-o", out2], contains="2")
        # a 2D file: its triangles are the section, --mirror shows the whole diameter
        nodes, conn = ur.rectangle_tris(4, 10, (0.0, 0.0), (R, L))
        h5 = os.path.join(tmp, "axisymmetric.h5")
        ur.write_fields(h5, nodes, conn, [{"time": 0.0, "cycle": 0, "coordinates": nodes,
                                           "fields": {"pressure": 1e9 * nodes[conn].mean(axis=1)[:, 1] / L}}])
        info = render_section(h5, out1, color="pressure", mirror="h", verbose=False)
        check(os.path.getsize(out1) > 1000 and info["cut_tets"] == 80
              and abs(info["area_m2"] - R * L) < 1e-12 * R * L * 1e3,
              "2D file drawn as it is: 80 triangles, area R*L %.9g mm^2 (expected %.9g)"
              % (info["area_m2"] * 1e6, R * L * 1e6))
    return test.finish()


# --------------------------------------------------------------------------------------
# CLI
# --------------------------------------------------------------------------------------

def build_parser():
    p = ur.cli_parser(
        "section.py",
        "Cut the deformed tetrahedral mesh of a udar field file (<case>.h5) with a "
        "plane and draw the section (axes in mm), coloured by part or by a field.",
        """examples:
  /usr/bin/python3 postproc/section.py out/taylor.h5 -o taylor_parts.png
  /usr/bin/python3 postproc/section.py out/taylor.h5 --step -1 --plane y=0 --color plastic_strain --mirror -o eps.png
  /usr/bin/python3 postproc/section.py out/taylor.h5 --plane z=1.5mm --color pressure --mirror-axis hv -o p.png
  /usr/bin/python3 postproc/section.py out/taylor.h5 --normal 1 -1 0 --point 0 0 0 --color von_mises -o vm.png
  /usr/bin/python3 postproc/section.py out/taylor.h5 --info
  /usr/bin/python3 postproc/section.py out/penetration.h5 --color pressure --particle-slab 0.5e-3 -o p.png
  /usr/bin/python3 postproc/section.py --self-test

Plane values are in metres (suffix 'mm' for millimetres). For an axis plane the picture
axes are the global coordinates: x=c -> (y, z), y=c -> (x, z), z=c -> (x, y).
Element fields are drawn as stored; vector fields as their magnitude; node fields
(e.g. velocity) as the average of the tet's 4 nodes. The particles of a run with
&material eroded = 'particles' within --particle-slab of the plane are drawn as small
markers, coloured like the elements when they have the field (part, pressure, density,
temperature, plastic_strain, velocity, ...), else grey.""")
    p.add_argument("-o", "--output", metavar="OUT.png",
                   help="output image (png/pdf/svg by extension); default <case>_section.png")
    g = ur.add_fields_argument(p)
    g.add_argument("--time", type=float, metavar="T_US",
                   help="use the step nearest to this time in microseconds instead of --step")
    p.add_argument("--plane", metavar="AXIS=VALUE",
                   help="axis-aligned plane, e.g. y=0, z=0.012, x=-2.5mm (default y=0)")
    p.add_argument("--normal", type=float, nargs=3, metavar=("NX", "NY", "NZ"),
                   help="general plane: normal direction (with --point)")
    p.add_argument("--point", type=float, nargs=3, metavar=("PX", "PY", "PZ"),
                   help="general plane: a point on it in metres (default 0 0 0)")
    p.add_argument("--color", "--colour", default="part", metavar="part|FIELD",
                   help="'part' (categorical colours, legend) or a field name such as pressure, "
                        "von_mises, plastic_strain, temperature, density (default part)")
    p.add_argument("--mirror", action="store_true",
                   help="also draw the picture reflected for half/quarter symmetric models, "
                        "across the vertical axis by default (e.g. the x=0 symmetry plane for "
                        "--plane y=0); see --mirror-axis")
    p.add_argument("--mirror-axis", choices=("h", "v", "hv"),
                   help="which picture coordinate --mirror negates (implies --mirror): 'h' the "
                        "horizontal one (default), 'v' the vertical one, 'hv' both (quarter "
                        "model seen in a z=const plane)")
    p.add_argument("--cmap", help="matplotlib colormap for fields (default viridis)")
    p.add_argument("--vmin", type=float, help="colour range minimum, SI units of the field")
    p.add_argument("--vmax", type=float, help="colour range maximum, SI units of the field")
    p.add_argument("--part-names", nargs="+", metavar="NAME",
                   help="legend names for the parts, in increasing part_id order (default: the "
                        "group names of the deck's &part entries, else 'part <id>')")
    p.add_argument("--edges", action="store_true", help="draw the cut tets' outlines")
    p.add_argument("--particle-slab", type=float, metavar="H",
                   help="draw the particles within H metres of the plane (default: half the "
                        "median particle spacing (mass/density)^(1/3))")
    p.add_argument("--no-particles", action="store_true",
                   help="do not draw the particles (eroded = 'particles' runs)")
    p.add_argument("--undeformed", action="store_true",
                   help="cut the initial mesh /mesh/x0 instead of the step's coordinates")
    p.add_argument("--xlim", type=float, nargs=2, metavar=("MIN", "MAX"), help="horizontal range, mm")
    p.add_argument("--ylim", type=float, nargs=2, metavar=("MIN", "MAX"), help="vertical range, mm")
    p.add_argument("--title", help="figure title (default: file, plane, step and time)")
    ur.add_figure_arguments(p, "figure size in inches (default: fitted to the section's shape)")
    p.add_argument("--info", action="store_true", help="list the file's steps and fields, then exit")
    return ur.add_self_test(p, "run the built-in checks (known cut areas), print PASS/FAIL")


def main(argv=None):
    return ur.cli_main(build_parser(), argv, _self_test, _run, errors=(SectionError, IndexError),
                       require=ur.FIELDS_REQUIRED)


def _run(args, p):
    if args.info:
        with ur.open_fields(args.fields) as f:
            print(f.summary())
        return 0
    if args.plane and (args.normal or args.point):
        p.error("give either --plane or --normal/--point, not both")
    if args.point and not args.normal:
        p.error("--point needs --normal")
    if args.normal:
        plane = plane_from_normal(args.normal, args.point or (0.0, 0.0, 0.0))
    else:
        plane = plane_from_spec(args.plane or "y=0")
    if args.particle_slab is not None and not args.particle_slab >= 0.0:
        p.error("--particle-slab must be a length >= 0 (m)")
    if args.cmap:
        import matplotlib
        if args.cmap not in matplotlib.colormaps:
            raise SectionError("unknown colormap %r (for example viridis, plasma, inferno, "
                               "coolwarm, RdBu_r, jet)" % args.cmap)
    out = args.output or os.path.splitext(os.path.basename(args.fields))[0] + "_section.png"
    mirror = args.mirror_axis or ("h" if args.mirror else None)
    render_section(args.fields, out, step=args.step, plane=plane, color=args.color,
                   mirror=mirror, cmap=args.cmap, vmin=args.vmin, vmax=args.vmax,
                   part_names=args.part_names, edges=args.edges, undeformed=args.undeformed,
                   xlim=args.xlim, ylim=args.ylim, title=args.title,
                   size=tuple(args.size) if args.size else None,
                   dpi=args.dpi, time_us=args.time, particles=not args.no_particles,
                   particle_slab=args.particle_slab)


if __name__ == "__main__":
    sys.exit(main())
