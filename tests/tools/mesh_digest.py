#!/usr/bin/python3
"""Node and tetrahedron counts and a content hash of a gmsh mesh (ASCII MSH
4.1 or 2.2), to tie a documented number to the mesh it was computed on.

    mesh_digest.py mesh.msh
        prints "nodes N tetrahedra T sha256 H"
    mesh_digest.py mesh.msh --manifest doc/validation/meshes.csv --geo G [--options "..."]
        compares with the manifest row of that .geo and gmsh options;
        exit 0 when equal, 1 (and says what differs) when not, 2 when the
        manifest has no such row, 3 when the mesh cannot be read

The hash does not depend on node or element numbering, element orientation
or the file format, so that a gmsh that only renumbers gives the same hash:
it is the sha256 of the sorted lines
    N x y z                         every node
    E group x1 y1 z1 ... x4 y4 z4   every tetrahedron and physical-surface
                                    triangle, its vertices sorted, with the
                                    names of its physical groups
where coordinates are integers in units of 1e-9 of the file's length unit
(1e-9 m for the metre meshes, 1e-9 mm for the Taylor bars)."""
import csv
import hashlib
import shlex
import sys

ROUND = 1e9


def _sections(path):
    with open(path) as f:
        lines = f.read().split('\n')
    if not lines or lines[0].strip() != '$MeshFormat':
        raise SystemExit(f'{path}: not an ASCII gmsh mesh')
    sec, name = {}, None
    for ln in lines:
        if ln.startswith('$End'):
            name = None
        elif ln.startswith('$'):
            name = ln[1:].strip()
            sec[name] = []
        elif name is not None:
            sec[name].append(ln)
    return sec


def read(path):
    """nodes {tag: (ix, iy, iz)}, tets and tris [(group names, node tags)]"""
    sec = _sections(path)
    version, binary = sec['MeshFormat'][0].split()[:2]
    if binary != '0':
        raise SystemExit(f'{path}: binary MSH is not supported')
    names = {}
    for ln in sec.get('PhysicalNames', [])[1:]:
        if ln.strip():
            dim, tag, nm = ln.split(maxsplit=2)
            names[(int(dim), int(tag))] = nm.strip('"')
    rnd = lambda v: int(round(float(v) * ROUND))
    nodes, tets, tris = {}, [], []
    if version.startswith('4'):
        ent = sec['Entities']
        counts = [int(v) for v in ent[0].split()]
        phys, i = {}, 1
        for dim in range(4):
            for _ in range(counts[dim]):
                w = ent[i].split(); i += 1
                tag = int(w[0])
                k = 4 if dim == 0 else 7     # after tag and the (bounding) box
                nph = int(w[k])
                phys[(dim, tag)] = tuple(sorted(names.get((dim, abs(int(p))), str(p))
                                                for p in w[k + 1:k + 1 + nph]))
        nd, i = sec['Nodes'], 1
        while i < len(nd) and nd[i].strip():
            _, _, param, n = (int(v) for v in nd[i].split()); i += 1
            tags = [int(nd[i + j]) for j in range(n)]
            for j, t in enumerate(tags):
                x = nd[i + n + j].split()
                nodes[t] = tuple(rnd(v) for v in x[:3])
            i += 2 * n
        el, i = sec['Elements'], 1
        while i < len(el) and el[i].strip():
            dim, etag, etype, n = (int(v) for v in el[i].split()); i += 1
            grp = phys.get((dim, etag), ())
            for j in range(n):
                w = [int(v) for v in el[i + j].split()]
                if etype == 4:
                    tets.append((grp, w[1:5]))
                elif etype == 2 and grp:
                    tris.append((grp, w[1:4]))
            i += n
    elif version.startswith('2'):
        for ln in sec['Nodes'][1:]:
            w = ln.split()
            if w:
                nodes[int(w[0])] = tuple(rnd(v) for v in w[1:4])
        for ln in sec['Elements'][1:]:
            w = [int(v) for v in ln.split()]
            if not w:
                continue
            etype, ntag = w[1], w[2]
            dim = 3 if etype == 4 else 2
            grp = (names.get((dim, w[3]), str(w[3])),) if ntag else ()
            if etype == 4:
                tets.append((grp, w[3 + ntag:7 + ntag]))
            elif etype == 2 and grp:
                tris.append((grp, w[3 + ntag:6 + ntag]))
    else:
        raise SystemExit(f'{path}: MSH version {version} is not supported')
    return nodes, tets, tris


def digest(path):
    nodes, tets, tris = read(path)
    out = ['N %d %d %d' % c for c in nodes.values()]
    for grp, conn in tets + tris:
        pts = sorted(nodes[t] for t in conn)
        out.append('E ' + ','.join(grp) + ' ' + ' '.join('%d %d %d' % p for p in pts))
    out.sort()
    h = hashlib.sha256('\n'.join(out).encode()).hexdigest()
    return len(nodes), len(tets), h


def _same_options(a, b):
    """gmsh option strings equal token by token, numbers compared as numbers
    (so "-setnumber h 1e-3" matches "-setnumber h 1.0e-3")"""
    ta, tb = shlex.split(a), shlex.split(b)
    if len(ta) != len(tb):
        return False
    for x, y in zip(ta, tb):
        try:
            if float(x) != float(y):
                return False
        except ValueError:
            if x != y:
                return False
    return True


def manifest_row(manifest, geo, options):
    with open(manifest) as f:
        rows = [r for r in csv.DictReader(row for row in f if not row.startswith('#'))]
    for r in rows:
        if r['geo'] == geo and _same_options(r['gmsh_options'], options):
            return r
    return None


def main(argv):
    args = list(argv)
    opt = {}
    for key in ('--manifest', '--geo', '--options'):
        if key in args:
            i = args.index(key)
            opt[key] = args[i + 1]
            del args[i:i + 2]
    if len(args) != 1:
        print(__doc__)
        return 2
    try:
        n, t, h = digest(args[0])
    except (OSError, ValueError, IndexError, KeyError) as e:
        print(f'{args[0]}: cannot read the mesh ({type(e).__name__}: {e})')
        return 3
    if '--manifest' not in opt:
        print(f'nodes {n} tetrahedra {t} sha256 {h}')
        return 0
    geo, options = opt['--geo'], opt.get('--options', '')
    r = manifest_row(opt['--manifest'], geo, options)
    if r is None:
        print(f'{geo} with gmsh options "{options}" has no row in {opt["--manifest"]}: '
              f'nodes {n} tetrahedra {t} sha256 {h}')
        return 2
    exp = (int(r['nodes']), int(r['tetrahedra']), r['sha256'])
    if exp == (n, t, h):
        print(f'mesh {r["deck"]} ({" ".join([geo, options]).strip()}) as in the manifest: '
              f'{n} nodes, {t} tetrahedra, sha256 {h[:16]}')
        return 0
    print(f'MESH DIFFERS from {opt["--manifest"]} for {r["deck"]} ({geo}, gmsh options "{options}"):\n'
          f'  expected {exp[0]} nodes, {exp[1]} tetrahedra, sha256 {exp[2]}\n'
          f'  actual   {n} nodes, {t} tetrahedra, sha256 {h}\n'
          f'  The numbers documented for this deck were computed on the expected mesh.')
    return 1


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
