#!/usr/bin/env python3
"""Writes a corpus of malformed decks and meshes for tests/cli/malformed_corpus.sh.

Usage: malformed_corpus.py <folder>

In <folder>: a small valid mesh (ok22.msh, ok41.msh: a unit cube of 6
tetrahedra, volume group 'body', surface group 'bottom'), a valid deck
(ok.nml), and one deck per case: d_<name>.nml (a broken deck) or
m_<name>.nml (a valid deck that reads the broken mesh m_<name>.msh). Plus
cases.tsv, one line per case: kind (deck|mesh), deck argument, and an
extended regular expression that udar's error output must match: it names
the file and, for a deck mistake, the deck line.
"""
import os
import re
import sys

# ---------------------------------------------------------------- the mesh
NODES = [(1 + x + 2 * y + 4 * z, (float(x), float(y), float(z)))
         for z in (0, 1) for y in (0, 1) for x in (0, 1)]
NODES.sort()
# extra nodes for the elements that must be refused (prism, hex, ...)
EXTRA = [(9 + i, (2.0 + (i % 2), float((i // 2) % 2), float(i // 4))) for i in range(10)]
# the cube as 6 tetrahedra (Kuhn): 0, e_a, e_a + e_b, 7 for each axis order
TETS = []
for a, b in ((1, 2), (1, 4), (2, 1), (2, 4), (4, 1), (4, 2)):
    TETS.append((1, 1 + a, 1 + a + b, 8))
TRIS = [(1, 2, 4), (1, 4, 3)]            # bottom face z = 0


def elements(extra=(), tets=None, tet_tags=None):
    """(tag, gmsh type, dim, physical tag, nodes) of the base mesh plus extra."""
    tets = TETS if tets is None else tets
    tags = tet_tags or list(range(3, 3 + len(tets)))
    els = [(1 + i, 2, 2, 2, t) for i, t in enumerate(TRIS)]
    els += [(tags[i], 4, 3, 1, t) for i, t in enumerate(tets)]
    return els + list(extra)


def msh22(nodes=None, els=None, names=True, version='2.2 0 8'):
    nodes = NODES if nodes is None else nodes
    els = elements() if els is None else els
    s = '$MeshFormat\n%s\n$EndMeshFormat\n' % version
    if names:
        s += '$PhysicalNames\n2\n2 2 "bottom"\n3 1 "body"\n$EndPhysicalNames\n'
    s += '$Nodes\n%d\n' % len(nodes)
    s += ''.join('%d %r %r %r\n' % ((t,) + tuple(x)) for t, x in nodes)
    s += '$EndNodes\n$Elements\n%d\n' % len(els)
    s += ''.join('%d %d 2 %d 1 %s\n' % (t, ty, ph, ' '.join(map(str, n))) for t, ty, d, ph, n in els)
    return s + '$EndElements\n'


def msh41(nodes=None, els=None):
    nodes = NODES if nodes is None else nodes
    els = elements() if els is None else els
    s = '$MeshFormat\n4.1 0 8\n$EndMeshFormat\n'
    s += '$PhysicalNames\n2\n2 2 "bottom"\n3 1 "body"\n$EndPhysicalNames\n'
    s += '$Entities\n0 0 1 1\n1 0 0 0 1 1 0 1 2 0\n1 0 0 0 3 1 2 1 1 1 1\n$EndEntities\n'
    tags = [t for t, _ in nodes]
    s += '$Nodes\n1 %d %d %d\n3 1 0 %d\n' % (len(nodes), min(tags), max(tags), len(nodes))
    s += ''.join('%d\n' % t for t in tags)
    s += ''.join('%r %r %r\n' % tuple(x) for _, x in nodes)
    s += '$EndNodes\n'
    # one block per (dim, type), in order of appearance
    blocks = []
    for e in els:
        key = (e[2], e[1])
        if not blocks or blocks[-1][0] != key:
            blocks.append((key, []))
        blocks[-1][1].append(e)
    alltags = [e[0] for e in els]
    s += '$Elements\n%d %d %d %d\n' % (len(blocks), len(els), min(alltags), max(alltags))
    for (dim, ty), bl in blocks:
        s += '%d 1 %d %d\n' % (dim, ty, len(bl))
        s += ''.join('%d %s\n' % (e[0], ' '.join(map(str, e[4]))) for e in bl)
    return s + '$EndElements\n'


# ---------------------------------------------------------------- the deck
DECK = """&run t_end = 1e-7 /
&mesh file = 'ok22.msh' /
&material name = 'steel', rho0 = 7850, youngs_modulus = 200e9, poisson_ratio = 0.3 /
&part group = 'body', material = 'steel' /
&boundary kind = 'symmetry', surface = 'bottom' /
&output directory = 'out' /
"""
LINES = DECK.splitlines(keepends=True)


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    cases = []

    def put(name, data, mode='w'):
        with open(os.path.join(out, name), mode) as f:
            f.write(data)

    def deck(name, text, pattern, line=None, raw=False):
        """A broken deck; pattern must appear in the output, after 'd_<name>.nml:<line>:'
        when line is given."""
        fname = 'd_%s.nml' % name
        put(fname, text, 'wb' if raw else 'w')
        where = re.escape(fname) + ('(:%d:)' % line if line else '') + '.*'
        cases.append(('deck', fname, where + pattern))

    def edit(n, old, new):
        """The base deck with line n (1-based) edited."""
        lines = list(LINES)
        assert old in lines[n - 1], (n, old)
        lines[n - 1] = lines[n - 1].replace(old, new)
        return ''.join(lines)

    def add(text):
        return DECK + text

    def mesh(name, text, pattern, raw=False):
        """A broken mesh, read by the base deck."""
        mname = 'm_%s.msh' % name
        put(mname, text, 'wb' if raw else 'w')
        put('m_%s.nml' % name, edit(2, 'ok22.msh', mname))
        cases.append(('mesh', 'm_%s.nml' % name, re.escape(mname) + '.*' + pattern))

    put('ok22.msh', msh22())
    put('ok41.msh', msh41())
    put('ok.nml', DECK)

    # ---------------------------------------------------------- meshes
    prism = (40, 6, 3, 1, (9, 10, 11, 12, 13, 14))
    hexa = (41, 5, 3, 1, (9, 10, 15, 11, 12, 13, 16, 14))
    pyramid = (42, 7, 3, 1, (9, 10, 15, 11, 17))
    tet10 = (43, 11, 3, 1, tuple(range(9, 19)))
    nodes = NODES + EXTRA
    for fmt, writer in (('22', msh22), ('41', msh41)):
        w = lambda els, n=nodes: writer(n, els)
        mesh('prism_' + fmt, w(elements([prism])), r'element 40 is a 6-node prism \(gmsh type 6\)')
        mesh('hex_' + fmt, w(elements([hexa])), r'element 41 is an 8-node hexahedron \(gmsh type 5\)')
        mesh('pyramid_' + fmt, w(elements([pyramid])), r'element 42 is a 5-node pyramid \(gmsh type 7\)')
        mesh('tet10_' + fmt, w(elements([tet10])), r'element 43 is a 10-node .*-order 1')
        mesh('all_tet10_' + fmt, w([(1, 2, 2, 2, TRIS[0]), (50, 11, 3, 1, tuple(range(9, 19))),
                                    (51, 11, 3, 1, tuple(range(8, 18)))]), r'element 50 is a 10-node')
        mesh('dup_tag_' + fmt, w(elements(tet_tags=[3, 4, 5, 6, 7, 3])), r'element tag 3 is used by a tetrahedron')
        mesh('dup_tet_tri_' + fmt, w(elements(tet_tags=[3, 4, 5, 6, 7, 1])), r'element tag 1 is used by')
        mesh('coord_1e308_' + fmt, writer([(t, (1e308, y, z) if t == 8 else (x, y, z)) for t, (x, y, z) in NODES],
                                          elements()), r'node 8 has coordinates out of range')
        mesh('unknown_node_' + fmt, w(elements(tets=TETS[:5] + [(1, 2, 3, 99)])), r'unknown node tag 99')
        mesh('no_tets_' + fmt, writer(NODES, [(1, 2, 2, 2, TRIS[0])]), r'no 4-node tetrahedra')
        if fmt == '22':
            mesh('type999_22', w(elements([(44, 999, 3, 1, (1, 2, 3))])), r'element 44 has element type 999')
            mesh('type999_tri_22', w(elements([(44, 999, 2, 2, (1, 2, 3))])), r'element 44 has element type 999')
            mesh('type11_one_22', w(elements([(45, 11, 3, 0, tuple(range(9, 19)))])), r'element 45 is a 10-node')
        else:
            mesh('type999_41', w(elements([(44, 999, 3, 1, (1, 2, 3))])), r'element 44 has element type 999')
            mesh('triangle_in_volume_block_41', w(elements([(47, 2, 3, 1, (1, 2, 3))])),
                 r'element 47 is a 2D element in a block of volume elements')
            mesh('tet_in_surface_block_41', w(elements([(46, 4, 2, 2, (1, 2, 3, 5))])), r'element 46 is a tetrahedron')
        good = writer(NODES, elements())
        k = good.index('$Elements')
        mesh('truncated_elements_' + fmt, good[:k + 40], r'(end of file|truncated)')
        mesh('truncated_nodes_' + fmt, good[:good.index('$Nodes') + 40], r'(end of file|truncated)')
        mesh('no_end_elements_' + fmt, good.replace('$EndElements\n', ''), r'EndElements')
        mesh('no_end_nodes_' + fmt, good.replace('$EndNodes\n', ''), r'EndNodes')
        if fmt == '22':
            mesh('negative_nodes_22', good.replace('$Nodes\n8\n', '$Nodes\n-8\n'), r'invalid node count -8')
            mesh('nonnumeric_coord_22', good.replace('\n3 0.0 1.0 0.0\n', '\n3 0.0 abc 0.0\n'), r'abc')
            mesh('nonnumeric_tag_22', good.replace('\n3 4 2 1 1', '\nx 4 2 1 1'), r'element tag')
            mesh('nan_coord_22', good.replace('\n3 0.0 1.0 0.0\n', '\n3 0.0 nan 0.0\n'), r'(nan|coordinate)')
            mesh('huge_count_22', good.replace('$Elements\n8\n', '$Elements\n99999999999999\n'),
                 r'invalid element count')
            mesh('dup_node_22', good.replace('\n3 0.0 1.0 0.0\n', '\n2 0.0 1.0 0.0\n'), r'duplicate node tag 2')
            mesh('no_physical_22', msh22(els=[(t, ty, d, 0, n) for t, ty, d, ph, n in elements()]),
                 r'(no physical volume group|no 4-node tetrahedra belong to a physical volume)')
            mesh('version_30', good.replace('2.2 0 8', '3.0 0 8'), r'unsupported MSH format')
            mesh('flat_tets_22', msh22([(t, (x, y, 0.0)) for t, (x, y, z) in NODES]), r'degenerate')
            mesh('missing_nodes_section_22', good[:good.index('$Nodes')] + good[good.index('$Elements'):],
                 r'no \$Nodes section')
        else:
            mesh('negative_nodes_41', good.replace('$Nodes\n1 8 1 8\n', '$Nodes\n1 -8 1 8\n'), r'negative number of nodes')
            mesh('nonnumeric_coord_41', good.replace('\n0.0 1.0 0.0\n', '\n0.0 abc 0.0\n'), r'abc')
            mesh('negative_block_41', good.replace('\n3 1 4 6\n', '\n3 1 4 -6\n'), r'negative number of elements')
            mesh('huge_block_41', good.replace('\n3 1 4 6\n', '\n3 1 4 99999999999\n'), r'invalid element block size')
            mesh('binary_garbage_41', good.replace('4.1 0 8', '4.1 1 8').split('$Nodes')[0] +
                 '$Nodes\n' + '\x07\xff\x00' * 40, r'byte order')
    mesh('empty', '', r'empty')
    # a volume group with a name but no elements, used by a part
    put('m_empty_group.msh', msh22().replace('$PhysicalNames\n2\n', '$PhysicalNames\n3\n3 3 "hollow"\n'))
    put('m_empty_group.nml', edit(2, 'ok22.msh', 'm_empty_group.msh') + "&part group = 'hollow', material = 'steel' /\n")
    cases.append(('mesh', 'm_empty_group.nml', r"m_empty_group\.nml:7: &part #2 'hollow': group = 'hollow': the physical "
                  r"volume group has no 4-node tetrahedra in .*m_empty_group\.msh"))
    mesh('not_a_mesh', 'hello world\n', r'MeshFormat')
    mesh('only_format', '$MeshFormat\n2.2 0 8\n$EndMeshFormat\n', r'no \$Nodes section')

    # meshes that are not files: refused at the &mesh line of the deck
    os.mkfifo(os.path.join(out, 'fifo.msh'))
    put('m_fifo.nml', edit(2, 'ok22.msh', 'fifo.msh'))
    cases.append(('mesh', 'm_fifo.nml', r'm_fifo\.nml:2: &mesh: file.*FIFO'))
    os.mkdir(os.path.join(out, 'dir.msh'))
    put('m_directory.nml', edit(2, 'ok22.msh', 'dir.msh'))
    cases.append(('mesh', 'm_directory.nml', r'm_directory\.nml:2: &mesh: file.*directory'))
    put('m_device.nml', edit(2, 'ok22.msh', '/dev/zero'))
    cases.append(('mesh', 'm_device.nml', r'm_device\.nml:2: &mesh: file.*character device'))
    put('m_missing.nml', edit(2, 'ok22.msh', 'nowhere.msh'))
    cases.append(('mesh', 'm_missing.nml', r'm_missing\.nml:2: &mesh: file.*not found'))

    # ---------------------------------------------------------- decks
    os.mkfifo(os.path.join(out, 'd_fifo.nml'))
    cases.append(('deck', 'd_fifo.nml', r'd_fifo\.nml.*FIFO'))
    os.mkdir(os.path.join(out, 'd_directory.nml'))
    cases.append(('deck', 'd_directory.nml', r'd_directory\.nml.*directory'))
    cases.append(('deck', '/dev/null', r'/dev/null.*character device'))
    cases.append(('deck', 'd_missing.nml', r'd_missing\.nml'))
    deck('empty', '', r'missing required group')
    deck('comments_only', '! nothing here\n', r'missing required group')
    deck('binary', '\x00\x01\x02&run\xff\xfe t_end = 1 /\n' * 3, r'missing required group')
    deck('bom', '\ufeff' + DECK, r'text outside any group', line=1)
    deck('long_string', edit(1, 't_end = 1e-7', "t_end = 1e-7, title = '" + 'x' * 1000000 + "'"),
         r'title = .*too long \(1000000 characters', line=1)
    # not decks at all: the scan stops after a few problems, quickly
    deck('mesh_as_deck', msh22(NODES * 5000), r'more than 20 problems: the rest of the file is not read')
    deck('many_assignments', '&run ' + 'x = 1 ' * 100000 + '/\n', r'more problems, not listed')
    deck('long_line', edit(1, 't_end = 1e-7', 't_end = ' + ' ' * 300000 + '1e-7 x'), r't_end = 1e-7 x : not a valid real number', line=1)
    deck('unterminated_quote', edit(3, "'steel',", "'steel,"), r"&material: name = 'steel, .*unterminated string: add the closing '", line=3)
    deck('unterminated_last', edit(6, "'out' /", "'out /"), r"&output: directory = 'out /.*unterminated", line=6)
    deck('bad_logical_1', add('&numerics anti_locking = 1 /\n'), r'anti_locking = 1 : not a valid logical: use \.true\. or \.false\.', line=7)
    deck('bad_logical_yes', add('&numerics anti_locking = yes /\n'), r'anti_locking = yes : not a valid logical', line=7)
    deck('bad_logical_contact', add("&contact master = 'body', slave = 'body', symmetric = 2 /\n"), r'symmetric = 2 : not a valid logical', line=7)
    deck('case_name_slash', edit(6, "'out'", "'out', case_name = 'a/b'"), r"case_name = 'a/b' : a case name is a file name", line=6)
    deck('case_name_dotdot', edit(6, "'out'", "'out', case_name = '../../escaped'"), r"case_name = '\.\./\.\./escaped' : a case name", line=6)
    # an absolute name outside the run folder, inside the scratch tree the test watches
    absolute = os.path.abspath(os.path.join(out, '..', '..', 'abs_case'))
    deck('case_name_absolute', edit(6, "'out'", "'out', case_name = '%s'" % absolute),
         r"case_name = '%s' : a case name" % re.escape(absolute), line=6)
    deck('case_name_dot', edit(6, "'out'", "'out', case_name = '.'"), r"case_name = '\.' : '\.' and '\.\.' are folders", line=6)
    deck('case_name_twodots', edit(6, "'out'", "'out', case_name = '..'"), r"case_name = '\.\.' : '\.' and '\.\.' are folders", line=6)
    deck('case_name_empty', edit(6, "'out'", "'out', case_name = ''"), r'case_name.*non-empty', line=6)
    deck('directory_control', edit(6, "'out'", "'o\x1bu'"), r'directory = .* : contains a control character \(code 27\)', line=6)
    deck('directory_tab', edit(6, "'out'", "'o\tu'"), r'directory = .* : contains a control character \(code 9\)', line=6)
    deck('case_name_control', edit(6, "'out'", "'out', case_name = 'a\x07b'"), r'case_name = .* : contains a control character \(code 7\)', line=6)
    deck('directory_empty', edit(6, "'out'", "''"), r'directory', line=6)
    deck('scale_1e300', edit(2, "'ok22.msh'", "'ok22.msh', scale = 1e300"), r'node [0-9]+ has coordinates out of range.*scale = 1.0+e300')
    deck('scale_zero', edit(2, "'ok22.msh'", "'ok22.msh', scale = 0"), r'scale = 0', line=2)
    deck('scale_negative', edit(2, "'ok22.msh'", "'ok22.msh', scale = -1"), r'scale = -1', line=2)
    deck('unknown_part_group', edit(4, "'body'", "'rod'"), r"&part #1 'rod': group = 'rod': no physical volume group .*'body'", line=4)
    deck('unknown_surface', edit(5, "'bottom'", "'top'"), r"surface = 'top': no physical surface group .*'bottom'", line=5)
    deck('group_used_twice', add("&part group = 'body', material = 'steel' /\n"), r"group = 'body' : the same mesh group is already used by &part #1", line=7)
    deck('unknown_contact_surface', add("&contact master = 'nothing', slave = 'body' /\n"), r"master", line=7)
    deck('missing_slash', edit(3, '0.3 /', '0.3'), r"&material \(line 3\) has no closing '/'", line=3)
    deck('missing_slash_end', edit(6, "'out' /", "'out'"), r"no closing '/'", line=6)
    deck('unknown_group', edit(3, '&material', '&materail'), r'unknown group &materail', line=3)
    deck('misspelled_variable', edit(3, 'rho0', 'rhoo'), r"rhoo.*rho0", line=3)
    deck('duplicate_variable', edit(1, 't_end = 1e-7', 't_end = 1e-7, t_end = 2e-7'), r'assigned a second time', line=1)
    deck('duplicate_group', add('&run t_end = 1 /\n'), r'&run appears again', line=7)
    deck('text_outside', add('stray words\n'), r'text outside any group', line=7)
    deck('ampersand_alone', add('& /\n'), r"'&' must be followed by a group name", line=7)
    deck('missing_equals', edit(1, 't_end = 1e-7', 't_end 1e-7'), r"(missing '='|t_end)", line=1)
    deck('no_value', edit(1, 't_end = 1e-7', 't_end = '), r'no value given', line=1)
    deck('real_as_string', edit(3, 'rho0 = 7850', "rho0 = 'abc'"), r'rho0 = .abc. : not a valid real number', line=3)
    deck('real_garbage', edit(3, 'rho0 = 7850', 'rho0 = 78x50'), r'rho0 = 78x50 : not a valid real number', line=3)
    deck('real_as_logical', edit(1, 't_end = 1e-7', 't_end = .true.'), r't_end', line=1)
    deck('integer_as_real', edit(1, 't_end = 1e-7', 't_end = 1e-7, max_cycles = 1.5'), r'max_cycles = 1\.5 : not a valid integer', line=1)
    deck('integer_overflow', edit(1, 't_end = 1e-7', 't_end = 1e-7, max_cycles = 99999999999'), r'max_cycles.*(too large|integer)', line=1)
    deck('string_unquoted', edit(3, "name = 'steel'", 'name = steel'), r'name = steel.*quotes', line=3)
    deck('string_as_number', edit(4, "material = 'steel'", 'material = 5'), r'material = 5', line=4)
    deck('too_many_values', edit(4, "'steel' /", "'steel', velocity = 1, 2, 3, 4 /"), r'velocity', line=4)
    deck('subscript_out', edit(4, "'steel' /", "'steel', velocity(4) = 1 /"), r'subscript out of range', line=4)
    deck('subscript_scalar', edit(1, 't_end = 1e-7', 't_end(2) = 1e-7'), r'not an array', line=1)
    deck('nan_value', edit(3, 'rho0 = 7850', 'rho0 = NaN'), r'rho0 = NaN : not a finite number', line=3)
    deck('inf_value', edit(1, 't_end = 1e-7', 't_end = Inf'), r'not a finite number', line=1)
    deck('overflow_value', edit(1, 't_end = 1e-7', 't_end = 1e400'), r't_end', line=1)
    deck('t_end_zero', edit(1, 't_end = 1e-7', 't_end = 0'), r't_end = 0 : must be > 0', line=1)
    deck('t_end_negative', edit(1, 't_end = 1e-7', 't_end = -1'), r't_end = -1 : must be > 0', line=1)
    deck('rho0_negative', edit(3, 'rho0 = 7850', 'rho0 = -7850'), r'rho0 = -7850', line=3)
    deck('youngs_zero', edit(3, 'youngs_modulus = 200e9', 'youngs_modulus = 0'), r'youngs_modulus = 0', line=3)
    deck('poisson_half', edit(3, 'poisson_ratio = 0.3', 'poisson_ratio = 0.5'), r'poisson_ratio = 0\.5', line=3)
    deck('dt_safety_2', edit(1, 't_end = 1e-7', 't_end = 1e-7, dt_safety = 2'), r'dt_safety = 2', line=1)
    deck('dt_field_negative', edit(6, "'out'", "'out', dt_field = -1"), r'dt_field = -1 : must be >= 0', line=6)
    deck('dt_initial_above_max', edit(1, 't_end = 1e-7', 't_end = 1e-7, dt_initial = 1e-6, dt_max = 1e-8'), r'dt_initial', line=1)
    deck('unknown_material', edit(4, "material = 'steel'", "material = 'brass'"), r"material = 'brass' : no &material of that name", line=4)
    deck('material_name_twice', add("&material name = 'steel', rho0 = 1, bulk_modulus = 1, shear_modulus = 1 /\n"), r'already used', line=7)
    deck('unknown_choice', edit(3, "name = 'steel'", "name = 'steel', eos = 'mie'"), r"eos = 'mie'.*unknown choice", line=3)
    deck('mg_without_c0', edit(3, "name = 'steel'", "name = 'steel', eos = 'mie_gruneisen'"), r'c0', line=3)
    deck('jc_without_a', edit(3, "name = 'steel'", "name = 'steel', strength = 'johnson_cook'"), r'jc_a', line=3)
    deck('bulk_disagrees', edit(3, "name = 'steel'", "name = 'steel', bulk_modulus = 1e9"), r'bulk_modulus = 1e9 : disagrees', line=3)
    deck('unknown_boundary_kind', edit(5, "'symmetry'", "'sticky'"), r"kind = 'sticky'", line=5)
    deck('wall_zero_normal', add("&boundary kind = 'rigid_wall', point = 0, 0, 0, normal = 0, 0, 0 /\n"), r'normal', line=7)
    deck('missing_run', ''.join(LINES[1:]), r'missing required group &run')
    deck('missing_mesh', LINES[0] + ''.join(LINES[2:]), r'missing required group &mesh')
    deck('missing_material', ''.join(LINES[:2] + LINES[3:]), r'missing required group &material')
    deck('missing_part', ''.join(LINES[:3] + LINES[4:]), r'missing required group &part')
    deck('mesh_file_empty_name', edit(2, "'ok22.msh'", "''"), r'file', line=2)
    deck('initial_temperature_zero', edit(3, "name = 'steel'", "name = 'steel', initial_temperature = 0"), r'initial_temperature = 0', line=3)

    with open(os.path.join(out, 'cases.tsv'), 'w') as f:
        for kind, arg, pat in cases:
            f.write('%s\t%s\t%s\n' % (kind, arg, pat))


if __name__ == '__main__':
    main()
