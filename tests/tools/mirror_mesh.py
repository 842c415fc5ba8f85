"""Mirror a gmsh 4.1 ASCII mesh through the plane x = 0 (every node's x
negated; tags, elements and groups unchanged): the same problem reflected,
whose space-filling-curve numbering visits the nodes in another order.
udar reorients the then negatively oriented tetrahedra when it reads them.
Usage: mirror_mesh.py IN.msh OUT.msh"""
import sys


def mirror(lines):
    out, i = [], 0
    while i < len(lines):
        out.append(lines[i])
        if lines[i].strip() != '$Nodes':
            i += 1
            continue
        n_blocks = int(lines[i + 1].split()[0])
        out.append(lines[i + 1])
        i += 2
        for _ in range(n_blocks):
            dim, tag, parametric, count = (int(w) for w in lines[i].split())
            out.append(lines[i])
            out.extend(lines[i + 1:i + 1 + count])          # node tags
            for line in lines[i + 1 + count:i + 1 + 2 * count]:
                w = line.split()
                w[0] = repr(-float(w[0]))
                out.append(' '.join(w) + '\n')
            i += 1 + 2 * count
    return out


if __name__ == '__main__':
    with open(sys.argv[1]) as f:
        text = f.readlines()
    if not text[1].startswith('4.1 0'):
        sys.exit(f'{sys.argv[1]}: not a gmsh 4.1 ASCII mesh')
    with open(sys.argv[2], 'w') as f:
        f.writelines(mirror(text))
