"""Geometry helpers of the contact checks."""
import numpy as np


def deepest_inside(points, x, tets, in_plane=None):
    """Largest depth (m) of any point inside any tetrahedron (or 2D
    triangle: tets with 3 columns, points in z = 0), 0 if none: the depth of
    a point is its smallest barycentric coordinate times the element's
    smallest altitude (positive only when it is strictly inside). in_plane
    (one row per element, a column per corner): the face opposite that
    corner lies in a symmetry plane, where the mirrored body goes on, so a
    point on it is inside (its coordinate there is left out of the
    smallest)."""
    depth = depths_inside(points, x, tets, in_plane)
    return depth.max() if len(depth) else 0.0


def faces_in_planes(tets, x0):
    """(elements, corners) booleans: the face opposite each corner lies in a
    symmetry plane of the mesh, a coordinate plane x, y or z = 0 that the
    whole mesh lies on one side of (the planes of udar's half and quarter
    models)."""
    in_plane = np.zeros(tets.shape, bool)
    d = tets.shape[1] - 1
    tol = 1e-9 * np.ptp(x0[:, :d], axis=0).max()    # (gmsh puts some plane nodes at 1e-19)
    for a in range(d):
        if abs(x0[:, a].min()) > tol and abs(x0[:, a].max()) > tol:
            continue
        on = np.abs(x0[:, a]) <= tol
        for k in range(d + 1):
            others = [j for j in range(d + 1) if j != k]
            in_plane[:, k] |= np.all(on[tets[:, others]], axis=1)
    return in_plane


def depths_inside(points, x, tets, in_plane=None):
    """Each point's depth (m) inside the tetrahedra (or 2D triangles) as
    deepest_inside measures it: the largest over the elements, 0 where it
    is in none."""
    d = tets.shape[1] - 1                                 # 3 (tetrahedra) or 2 (triangles)
    corners = [x[tets[:, k], :d] for k in range(d + 1)]
    a = corners[0]
    m = np.stack([c - a for c in corners[1:]], axis=2)    # (nt, d, d), columns are edges
    inv = np.linalg.inv(m)
    size = np.abs(np.linalg.det(m))                       # 6 V, or 2 A
    if d == 3:
        b, c, e = corners[1:]
        faces = [np.cross(c - b, e - b), np.cross(e - a, c - a), np.cross(b - a, e - a), np.cross(c - a, b - a)]
        h_min = size / np.max([np.linalg.norm(f, axis=1) for f in faces], axis=0)
    else:
        b, c = corners[1:]
        h_min = size / np.max([np.linalg.norm(f, axis=1) for f in (b - a, c - b, a - c)], axis=0)
    lo, hi = np.minimum.reduce(corners), np.maximum.reduce(corners)
    depths = np.zeros(len(points))
    if len(tets) == 0:
        return depths
    points = points[:, :d]
    # the (point, element) pairs whose element box holds the point, through
    # a grid of cells as large as the largest box (a box meets at most two
    # cells an axis): each element is listed in the cells its box meets
    cell = np.maximum((hi - lo).max(axis=0), 1e-300)
    origin = lo.min(axis=0)
    c_lo = np.floor((lo - origin) / cell).astype(np.int64)
    c_hi = np.floor((hi - origin) / cell).astype(np.int64)
    span = c_hi.max(axis=0) + 2
    keys, elems = [], []
    for off in np.ndindex(*([2] * d)):
        c = c_lo + np.array(off)
        ok = np.all(c <= c_hi, axis=1)
        keys.append(np.ravel_multi_index(c[ok].T, span))
        elems.append(np.nonzero(ok)[0])
    keys, elems = np.concatenate(keys), np.concatenate(elems)
    order = np.argsort(keys, kind='stable')
    keys, elems = keys[order], elems[order]
    cp = np.floor((points - origin) / cell).astype(np.int64)
    inside_grid = np.all((cp >= 0) & (cp < span), axis=1)
    pts = np.nonzero(inside_grid)[0]
    pk = np.ravel_multi_index(cp[pts].T, span)
    first, last = np.searchsorted(keys, pk, 'left'), np.searchsorted(keys, pk, 'right')
    count = last - first
    pi = np.repeat(pts, count)
    # (each pair's element: its point's run of the sorted lists)
    ei = elems[np.repeat(first, count) + np.arange(len(pi)) - np.repeat(np.cumsum(count) - count, count)]
    near = np.all((points[pi] >= lo[ei]) & (points[pi] <= hi[ei]), axis=1)
    pi, ei = pi[near], ei[near]
    if len(pi) == 0:
        return depths
    lam = np.einsum('nij,nj->ni', inv[ei], points[pi] - a[ei])
    bary = np.column_stack([1.0 - lam.sum(axis=1), lam])
    if in_plane is not None:
        # on a face in a symmetry plane (to rounding): inside the mirrored body
        bary = np.where(in_plane[ei] & (bary >= -1e-12), np.inf, bary)
        bary[np.all(np.isinf(bary), axis=1)] = 0.0
    np.maximum.at(depths, pi, bary.min(axis=1) * h_min[ei])
    return depths
    # only the points within the elements' overall box can be inside one
    points = points[:, :d]
    boxed = np.nonzero(np.all((points >= lo.min(axis=0)) & (points <= hi.max(axis=0)), axis=1))[0]
    for i in boxed:
        p = points[i]
        near = np.all((p >= lo) & (p <= hi), axis=1)
        if not near.any():
            continue
        lam = np.einsum('nij,nj->ni', inv[near], p - a[near])
        bary = np.column_stack([1.0 - lam.sum(axis=1), lam])
        if in_plane is not None:
            # on a face in a symmetry plane (to rounding): inside the mirrored body
            bary = np.where(in_plane[near] & (bary >= -1e-12), np.inf, bary)
            bary[np.all(np.isinf(bary), axis=1)] = 0.0
        depths[i] = max((bary.min(axis=1) * h_min[near]).max(), 0.0)
    return depths


def element_measures(conn, x0, signed=False):
    """Each element's reference measure: a tetrahedron's volume (m3), or a
    triangle's area in the (x, y) plane (m2: per metre of depth in plane
    strain; times 2 pi rbar for the volume per revolution). signed: a
    tetrahedron's signed volume (negative when inside out)."""
    if conn.shape[1] == 4:
        a, b, c, d = (x0[conn[:, k]] for k in range(4))
        v = np.einsum('ij,ij->i', b - a, np.cross(c - a, d - a)) / 6.0
        return v if signed else np.abs(v)
    a, b, c = (x0[conn[:, k]] for k in range(3))
    return 0.5 * np.abs((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (c[:, 0] - a[:, 0]) * (b[:, 1] - a[:, 1]))


def slave_and_master(f, slave_part, master_part):
    """From an open field file: connectivity, x0, the slave part's nodes,
    the master part's element mask and its median edge length (h)."""
    part = f['mesh/part_id'][...]
    conn = f['mesh/connectivity'][...]
    x0 = f['mesh/x0'][...]
    master = part == master_part
    h = np.median(np.linalg.norm(x0[conn[master, 1]] - x0[conn[master, 0]], axis=1))
    return conn, x0, np.unique(conn[part == slave_part]), master, h


def frames_inside(f, slave_part, master_part, remaining_only=False):
    """For each field step of an open field file, in time order: the step's
    group, its coordinates and the depth (m) of the deepest node of part
    slave_part inside a tetrahedron of part master_part that is still there
    (not eroded, where the file has fracture states). Where the slave
    part's eroded elements became particles, its slave points are the
    nodes of its remaining elements and its particles (a node whose
    elements all became particles has no mass and is no slave node).
    remaining_only: only the nodes of the slave part's remaining elements
    (not its free nodes, not its particles). A point on a master face in a
    symmetry plane is inside the mirrored body (faces_in_planes; before
    0.9.4 such points counted 0 deep)."""
    conn, x0, slave_nodes, master, _ = slave_and_master(f, slave_part, master_part)
    in_plane = faces_in_planes(conn, x0)
    slave = f['mesh/part_id'][...] == slave_part
    for k in sorted(f['steps'].keys(), key=lambda k: f['steps'][k].attrs['time']):
        g = f['steps'][k]
        alive = master
        slave_alive = slave
        if 'fracture_state' in g:
            state = g['fracture_state'][...]
            alive = master & (state < 1.5)
            slave_alive = slave & (state < 1.5)
        x = g['coordinates'][...]
        points = x[slave_nodes]
        p = g['particles'] if 'particles' in g else None
        if remaining_only:
            points = x[np.unique(conn[slave_alive])]
        elif p is not None and int(p.attrs['count']) > 0:
            mine = p['part_id'][...] == slave_part
            if mine.any():
                points = np.vstack([x[np.unique(conn[slave_alive])], p['coordinates'][...][mine]])
        yield g, x, deepest_inside(points, x, conn[alive], in_plane[alive])
