#!/usr/bin/python3
"""Read udar output files: the HDF5 field file and the history CSV.

Library use (from another script in postproc/, or with postproc/ on sys.path)::

    import udar_results as ur

    with ur.open_fields("taylor.h5") as f:
        print(f.n_nodes, f.n_elems, len(f.steps))
        last = f.step(-1)                      # negative indices count from the end
        xyz = last.coordinates                 # (n_nodes, 3) float64, read on first use
        p = last.fields["pressure"]            # (n_elems,), read on first use
        pt = last.particles                    # None without a particles group, else Particles
        if pt is not None and pt.count:        # read on first use: count, coordinates (count, 3),
            m = pt["mass"]                     # velocity, mass, density, pressure, part_id, ...
        for info in f.steps:                   # StepInfo(index, name, time, cycle)
            print(info.index, info.cycle, info.time)

    hist = ur.read_history("taylor_history.csv")   # {column name: 1-D numpy array}
    parts = ur.history_parts(hist)                 # part names from the ke_<part> columns

Command line::

    /usr/bin/python3 postproc/udar_results.py FILE.h5|FILE.csv   # print a summary
    /usr/bin/python3 postproc/udar_results.py --self-test

Field file layout (written by the solver; SI units throughout):

* root attributes ``program`` ("udar"), ``version``, ``title``, ``deck``, ``n_nodes``, ``n_elems``
* ``/mesh/node_id`` (n_nodes) int32, ``/mesh/elem_id`` (n_elems) int32,
  ``/mesh/part_id`` (n_elems) int32, ``/mesh/connectivity`` (n_elems, 4) (2D: (n_elems, 3) triangles) int32 0-based node
  indices, ``/mesh/x0`` (n_nodes, 3) float64
* ``/steps/000000``, ``/steps/000001``, ... with attributes ``time`` (s) and ``cycle``;
  dataset ``coordinates`` (n_nodes, 3) and field datasets: node vectors such as ``velocity``
  (n_nodes, 3), element scalars (n_elems) such as ``pressure``; ``/steps`` has attribute ``count``.
* with ``&material eroded = 'particles'``, a group ``/steps/NNNNNN/particles`` with attribute
  ``count`` and (count > 0) ``coordinates``, ``velocity`` (count, 3) and 1-D ``mass``,
  ``density``, ``pressure``, ``specific_internal_energy``, ``temperature``, ``plastic_strain``,
  ``part_id``, ``element`` (read by ``Step.particles``; they are not among ``Step.fields``).

The full contract is doc/output-format.md: ``/steps@count`` is authoritative (groups numbered
>= count are uncommitted and ignored); the fields may differ from step to step; centring
follows from the first dimension (from the NAME.xmf index when n_nodes == n_elems). A file
still locked by the running solver is reopened without HDF5 file locking.

The module also contains small helpers that *write* that layout (``write_fields``) and build
structured tetrahedral meshes (``box_tets``, ``cylinder_tets``); the self-tests of the
post-processing scripts use them to make synthetic files.
"""

import argparse
import csv
import io
import os
import re
import sys
import tempfile
import warnings
from contextlib import redirect_stderr, redirect_stdout
from collections import namedtuple
from collections.abc import Mapping

try:
    import numpy as np
except ImportError:
    # run as a script (this one, or a postproc script that imports it first): one line naming
    # the script instead of a traceback; imported from elsewhere: the ImportError
    _script = getattr(sys.modules.get("__main__"), "__file__", None) or ""
    if __name__ == "__main__" or (_script and os.path.dirname(os.path.realpath(_script))
                                  == os.path.dirname(os.path.realpath(__file__))):
        sys.exit("%s: error: numpy is not installed for %s; run the udar post-processing "
                 "scripts with /usr/bin/python3" % (os.path.basename(_script), sys.executable))
    raise

try:
    import h5py
except ImportError:  # pragma: no cover - depends on the interpreter
    h5py = None

__all__ = [
    "UdarFileError", "open_fields", "FieldFile", "Step", "StepInfo", "Particles",
    "PARTICLE_FIELDS", "particle_spacing", "read_history",
    "history_parts", "write_fields", "box_tets", "cylinder_tets", "FIELD_UNITS",
    "field_unit", "cli_warnings", "deck_groups", "deck_values", "deck_part_names", "wall_heights", "write_history", "si_scale", "agg_pyplot",
    "save_figure", "cli_parser", "add_fields_argument", "add_self_test", "FIELDS_REQUIRED", "cli_main", "SelfTest",
]

#: SI unit of the known fields ("-" = dimensionless).
FIELD_UNITS = {
    "pressure": "Pa",
    "von_mises": "Pa",
    "plastic_strain": "-",
    "plastic_strain_rate": "1/s",
    "temperature": "K",
    "density": "kg/m³",
    "internal_energy": "J/kg",
    "specific_internal_energy": "J/kg",
    "volumetric_strain": "-",
    "sound_speed": "m/s",
    "damage": "-",
    "mass": "kg",
    "volume": "m³",
    "velocity": "m/s",
    "displacement": "m",
    "acceleration": "m/s²",
    "force": "N",
    "coordinates": "m",
    "part": "-",
}

#: Names that are node fields when the size alone cannot tell (n_nodes == n_elems).
_NODE_FIELD_NAMES = {"velocity", "displacement", "acceleration", "force", "nodal_mass",
                     "coordinates", "contact_force"}


def cli_warnings(prog):
    """Make ``warnings.warn`` print one plain line 'prog: warning: message' (for the CLIs)."""
    def _fmt(message, category, filename, lineno, line=None):
        return "%s: warning: %s\n" % (prog, message)
    warnings.formatwarning = _fmt


def field_unit(name):
    """SI unit string of a field name ('' if unknown)."""
    return FIELD_UNITS.get(name, "")


class UdarFileError(Exception):
    """A udar output file is missing, unreadable or does not have the expected layout.

    The message always names the file and the problem.
    """


StepInfo = namedtuple("StepInfo", "index name time cycle")
StepInfo.__doc__ = "One stored output step: position in the file, group name, time (s), cycle."


def _need_h5py():
    if h5py is None:
        raise UdarFileError(
            "the h5py module is not available in %s; run the udar post-processing scripts "
            "with Debian's /usr/bin/python3 (which has numpy, h5py and matplotlib)" % sys.executable)


def _decode(value):
    """HDF5 attribute -> plain Python value (bytes -> str, size-1 arrays -> scalar)."""
    if isinstance(value, np.ndarray):
        if value.size == 1:
            value = value.reshape(-1)[0]
        elif value.dtype.kind in "SO":
            return [_decode(v) for v in value.tolist()]
        else:
            return value
    if isinstance(value, (bytes, np.bytes_)):
        return bytes(value).decode("utf-8", errors="replace").rstrip("\x00 ").strip()
    if isinstance(value, str):
        return value.rstrip("\x00 ").strip()
    if isinstance(value, np.generic):
        return value.item()
    return value


# --------------------------------------------------------------------------------------
# deck text
# --------------------------------------------------------------------------------------

def deck_groups(text):
    """Split namelist text into [(group name (lower case), body text)], with comments removed
    and quoted strings respected (a '/' inside quotes does not end a group)."""
    groups, name, body = [], None, []
    i, n = 0, len(text)
    while i < n:
        ch = text[i]
        if ch in "'\"":
            j = i + 1
            while j < n:
                if text[j] == ch:
                    if j + 1 < n and text[j + 1] == ch:
                        j += 2
                        continue
                    break
                j += 1
            if name is not None:
                body.append(text[i:j + 1])
            i = j + 1
        elif ch == "!":
            while i < n and text[i] != "\n":
                i += 1
        elif ch == "&" and name is None:
            m = re.match(r"&([A-Za-z_]\w*)", text[i:])
            if m:
                name, body = m.group(1).lower(), []
                i += m.end()
            else:
                i += 1
        elif ch == "/" and name is not None:
            groups.append((name, "".join(body)))
            name = None
            i += 1
        else:
            if name is not None:
                body.append(ch)
            i += 1
    return groups


_DECK_TOKEN = re.compile(r"'(?:[^']|'')*'|\"(?:[^\"]|\"\")*\"|![^\n]*|=|[^\s,=!]+")


def _deck_scalar(tok):
    if tok[0] in "'\"":
        return tok[1:-1].replace(tok[0] * 2, tok[0])
    low = tok.lower()
    if low in (".true.", "t", ".t."):
        return True
    if low in (".false.", "f", ".f."):
        return False
    try:
        return float(low.replace("d", "e"))      # Fortran 1.0d3
    except ValueError:
        return tok


def deck_values(body):
    """{variable (lower case): value} of one group body from ``deck_groups``: quoted strings
    as str, numbers as float, logicals as bool, a list for several comma-separated values."""
    toks = [t for t in _DECK_TOKEN.findall(body) if t[0] != "!"]     # comments dropped
    values, name, vals = {}, None, []
    for k, tok in enumerate(toks):
        if tok == "=":
            continue
        if k + 1 < len(toks) and toks[k + 1] == "=":   # a name starts the next assignment
            if name is not None:
                values[name] = vals[0] if len(vals) == 1 else vals
            name, vals = tok.lower(), []
        elif name is not None:
            vals.append(_deck_scalar(tok))
    if name is not None:
        values[name] = vals[0] if len(vals) == 1 else vals
    return values


def deck_part_names(text):
    """Part names (the ``group`` of each &part, in deck order) from a deck text; the solver's
    part_id k (1-based) is the k-th &part. Returns [] if there are none."""
    names = [deck_values(body).get("group") for g, body in deck_groups(text or "") if g == "part"]
    return names if all(isinstance(n, str) for n in names) else []


def wall_heights(x, axis, wall):
    """Heights of the points ``x`` (n, 3) above the plane ``x[:, axis] = wall`` on the side
    where their mean lies -> (heights, side +1/-1): bodies on either side measure alike."""
    s = np.asarray(x, dtype=np.float64)[:, axis] - wall
    side = 1.0 if np.mean(s) >= 0.0 else -1.0
    return side * s, side


# --------------------------------------------------------------------------------------
# field file
# --------------------------------------------------------------------------------------

class _LazyMapping(Mapping):
    """Read-only mapping name -> numpy array over self._names, each read once by
    self._read(name) on first access; an unknown name raises KeyError listing them
    (self._missing(name) says where)."""

    def __getitem__(self, name):
        if name in self._cache:
            return self._cache[name]
        if name not in self._names:
            raise KeyError("%s (available: %s)" % (self._missing(name), ", ".join(self._names) or "none"))
        data = self._read(name)
        self._cache[name] = data
        return data

    def __iter__(self):
        return iter(self._names)

    def __len__(self):
        return len(self._names)


class LazyFields(_LazyMapping):
    """Read-only mapping field name -> numpy array; each dataset is read on first access."""

    def __init__(self, step):
        self._step = step
        group = step._group
        self._names = sorted(k for k, v in group.items()
                             if k != "coordinates" and isinstance(v, h5py.Dataset))
        self._cache = {}

    def _missing(self, name):
        return "%s: step %s has no field %r" % (self._step._file.path, self._step.name, name)

    def _read(self, name):
        return self._step._file._read_dataset(self._step._group, name)

    def __repr__(self):
        return "LazyFields(%s)" % ", ".join(self._names)

    def shape(self, name):
        """Shape of a field without reading it (after the orientation fix of the reader)."""
        if name not in self._names:
            self[name]  # raises the KeyError with the list of fields
        shp = tuple(self._step._group[name].shape)
        f = self._step._file
        if len(shp) == 2 and shp[0] in (3, 4, 6, 9) and shp[1] in (f.n_nodes, f.n_elems) \
                and shp[0] not in (f.n_nodes, f.n_elems):
            shp = (shp[1], shp[0])
        return shp

    def location(self, name):
        """'node', 'elem' or 'other' (first dimension matches neither count)."""
        n = self.shape(name)[0] if self.shape(name) else -1
        f = self._step._file
        is_node, is_elem = n == f.n_nodes, n == f.n_elems
        if is_node and is_elem:  # n_nodes == n_elems: ask the .xmf index, else guess by name
            center = f.xmf_centers().get(name)
            if center in ("node", "elem"):
                return center
            return "node" if name in _NODE_FIELD_NAMES else "elem"
        if is_node:
            return "node"
        if is_elem:
            return "elem"
        return "other"

    @property
    def node_fields(self):
        return [n for n in self._names if self.location(n) == "node"]

    @property
    def elem_fields(self):
        return [n for n in self._names if self.location(n) == "elem"]


#: The datasets of a step's particles group (count > 0), in the order of doc/output-format.md.
PARTICLE_FIELDS = ("coordinates", "velocity", "mass", "density", "pressure",
                   "specific_internal_energy", "temperature", "plastic_strain", "part_id", "element",
                   "von_mises", "strength_kept")
_PARTICLE_INTEGERS = ("part_id", "element")     # stored as float64, returned as int64
_PARTICLE_VECTORS = ("coordinates", "velocity")


class Particles(_LazyMapping):
    """The particles of one step (``Step.particles``): a read-only mapping dataset name ->
    numpy array, each read on first access, with ``count`` (int) and the properties
    ``coordinates`` ((count, 3), m) and ``velocity`` ((count, 3), m/s).

    ``part_id`` and ``element`` (stored as float64) come back as int64. With count 0 the
    group has no datasets; the names of ``PARTICLE_FIELDS`` then give empty arrays ((0, 3)
    or (0,)), so code written for particles needs no special case.
    """

    def __init__(self, step, group):
        self._group = group
        self._where = "%s: /steps/%s/particles" % (step._file.path, step.name)
        if "count" in group.attrs:
            self.count = int(_decode(group.attrs["count"]))
        elif "coordinates" in group:  # no count attribute (not udar 0.6.0): the rows
            self.count = int(group["coordinates"].shape[0])
        else:
            raise UdarFileError("%s has neither a count attribute nor coordinates" % self._where)
        if self.count < 0:
            raise UdarFileError("%s has count %d" % (self._where, self.count))
        if self.count:
            self._names = sorted(k for k, v in group.items() if isinstance(v, h5py.Dataset))
            if "coordinates" not in self._names:
                raise UdarFileError("%s: count = %d but no coordinates dataset"
                                    % (self._where, self.count))
        else:
            self._names = list(PARTICLE_FIELDS)
        self._cache = {}

    def _missing(self, name):
        return "%s has no dataset %r" % (self._where, name)

    def _read(self, name):
        if self.count == 0:
            data = np.zeros((0, 3) if name in _PARTICLE_VECTORS else (0,),
                            dtype=np.int64 if name in _PARTICLE_INTEGERS else np.float64)
        else:
            try:
                data = self._group[name][()]
            except Exception as err:
                raise UdarFileError("%s: cannot read %s: %s" % (self._where, name, err)) from None
            if data.ndim == 2 and data.shape[0] == 3 and data.shape[1] == self.count != 3:
                warnings.warn("%s/%s stored transposed as %s; using its transpose"
                              % (self._where, name, data.shape))
                data = data.T.copy()
            if data.ndim == 0 or data.shape[0] != self.count:
                raise UdarFileError("%s/%s has shape %s, expected %d rows (the count attribute)"
                                    % (self._where, name, data.shape, self.count))
            if name in _PARTICLE_INTEGERS:
                data = np.rint(data).astype(np.int64)
        return data

    def __repr__(self):
        return "Particles(count=%d: %s)" % (self.count, ", ".join(self._names))

    @property
    def coordinates(self):
        """Particle positions (count, 3) in m."""
        return self["coordinates"]

    @property
    def velocity(self):
        """Particle velocities (count, 3) in m/s."""
        return self["velocity"]


def particle_spacing(particles):
    """Median of the particles' (mass/density)^(1/3) in m: the spacing they would have
    packed at their density (about the size of the elements they were); nan when there are
    no particles with a positive mass and density."""
    if particles is None or particles.count == 0 or "mass" not in particles \
            or "density" not in particles:
        return float("nan")
    m, rho = np.asarray(particles["mass"]), np.asarray(particles["density"])
    ok = np.isfinite(m) & np.isfinite(rho) & (m > 0.0) & (rho > 0.0)
    return float(np.median(np.cbrt(m[ok] / rho[ok]))) if ok.any() else float("nan")


class Step:
    """One output step. ``coordinates``, ``fields[name]`` and ``particles`` are read on first
    access."""

    def __init__(self, fieldfile, info):
        self._file = fieldfile
        self.index = info.index
        self.name = info.name
        self.time = info.time
        self.cycle = info.cycle
        self._group = fieldfile._h5["steps"][info.name]
        self._coords = None
        self._particles = None
        self.fields = LazyFields(self)

    @property
    def coordinates(self):
        """Deformed nodal coordinates (n_nodes, 3) in m."""
        if self._coords is None:
            if "coordinates" not in self._group:
                raise UdarFileError("%s: step group /steps/%s has no 'coordinates' dataset "
                                    "(incomplete step?)" % (self._file.path, self.name))
            c = self._file._read_dataset(self._group, "coordinates")
            if c.shape != (self._file.n_nodes, 3):
                raise UdarFileError("%s: /steps/%s/coordinates has shape %s, expected (%d, 3)"
                                    % (self._file.path, self.name, c.shape, self._file.n_nodes))
            self._coords = np.asarray(c, dtype=np.float64)
        return self._coords

    @property
    def displacement(self):
        return self.coordinates - self._file.x0

    @property
    def particles(self):
        """The step's particles (``Particles``: count, coordinates, velocity, mass, ...), or
        None when the step has no particles group (a run without eroded = 'particles')."""
        if self._particles is None and "particles" in self._group:
            g = self._group["particles"]
            if not isinstance(g, h5py.Group):
                raise UdarFileError("%s: /steps/%s/particles is not a group"
                                    % (self._file.path, self.name))
            self._particles = Particles(self, g)
        return self._particles

    def __repr__(self):
        return "Step(index=%d, name=%r, time=%g, cycle=%d, fields=[%s])" % (
            self.index, self.name, self.time, self.cycle, ", ".join(self.fields))


class FieldFile:
    """An open udar HDF5 field file (use ``open_fields``). Close it or use ``with``.

    Attributes: ``path``, ``attrs`` (root attributes, decoded), ``program``, ``version``,
    ``title``, ``deck``, ``n_nodes``, ``n_elems``, ``node_id``, ``elem_id``, ``part_id``,
    ``connectivity`` (0-based, (n_elems, 4)), ``x0`` ((n_nodes, 3), m), ``steps`` (list of
    ``StepInfo``), ``times`` (s) and ``cycles`` arrays.
    """

    def __init__(self, path):
        _need_h5py()
        self.path = str(path)
        if not os.path.exists(self.path):
            raise UdarFileError("%s: no such file" % self.path)
        if os.path.isdir(self.path):
            raise UdarFileError("%s: is a directory, expected a udar .h5 field file" % self.path)
        self._h5 = self._open(self.path)
        try:
            self._load()
        except Exception:
            self._h5.close()
            raise

    @staticmethod
    def _open(path):
        try:
            return h5py.File(path, "r")
        except OSError as err:
            msg = str(err)
            if "lock" in msg.lower():
                # the solver may still have the file open for writing
                try:
                    return h5py.File(path, "r", locking=False)
                except Exception:
                    pass
            try:
                is_h5 = h5py.is_hdf5(path)
            except Exception:
                is_h5 = False
            if not is_h5:
                raise UdarFileError("%s: not an HDF5 file (%s)" % (path, msg)) from None
            raise UdarFileError("%s: cannot open HDF5 file: %s (if the simulation is still "
                                "writing it, try HDF5_USE_FILE_LOCKING=FALSE)" % (path, msg)) from None

    def _fail(self, what):
        raise UdarFileError("%s: %s" % (self.path, what))

    def _read_dataset(self, group, name):
        """Read a dataset; fix a (k, n) Fortran-order transposition of (n, k) data."""
        try:
            data = group[name][()]
        except Exception as err:
            self._fail("cannot read dataset %s/%s: %s" % (group.name, name, err))
        if data.ndim == 2 and data.shape[0] in (3, 4, 6, 9) \
                and data.shape[1] in (self.n_nodes, self.n_elems) \
                and data.shape[0] not in (self.n_nodes, self.n_elems):
            warnings.warn("%s: %s/%s stored transposed as %s; using its transpose" % (
                self.path, group.name, name, data.shape))
            data = data.T.copy()
        return data

    def _load(self):
        h5 = self._h5
        self.attrs = {k: _decode(v) for k, v in h5.attrs.items()}
        self.program = str(self.attrs.get("program", ""))
        if self.program and self.program != "udar":
            warnings.warn("%s: root attribute program=%r (expected 'udar')" % (self.path, self.program))
        self.version = str(self.attrs.get("version", ""))
        self.title = str(self.attrs.get("title", ""))
        self.deck = str(self.attrs.get("deck", ""))
        if "mesh" not in h5 or not isinstance(h5["mesh"], h5py.Group):
            self._fail("no /mesh group - not a udar field file? (top-level items: %s)"
                       % (", ".join(h5.keys()) or "none"))
        mesh = h5["mesh"]
        for name in ("connectivity", "x0"):
            if name not in mesh:
                self._fail("missing dataset /mesh/%s" % name)
        x0 = np.asarray(mesh["x0"][()], dtype=np.float64)
        if x0.ndim == 2 and x0.shape[0] == 3 and x0.shape[1] != 3:
            warnings.warn("%s: /mesh/x0 stored transposed; using its transpose" % self.path)
            x0 = x0.T.copy()
        if x0.ndim != 2 or x0.shape[1] != 3:
            self._fail("/mesh/x0 has shape %s, expected (n_nodes, 3)" % (x0.shape,))
        conn = np.asarray(mesh["connectivity"][()])
        if conn.ndim == 2 and conn.shape[0] == 4 and conn.shape[1] != 4:
            warnings.warn("%s: /mesh/connectivity stored transposed; using its transpose" % self.path)
            conn = conn.T.copy()
        if conn.ndim != 2 or conn.shape[1] not in (3, 4):
            self._fail("/mesh/connectivity has shape %s, expected (n_elems, 4) or, 2D, (n_elems, 3)"
                       % (conn.shape,))
        if conn.dtype.kind not in "iu":
            self._fail("/mesh/connectivity has type %s, expected integers" % conn.dtype)
        self.n_nodes = int(self.attrs.get("n_nodes", x0.shape[0]))
        self.n_elems = int(self.attrs.get("n_elems", conn.shape[0]))
        if x0.shape[0] != self.n_nodes:
            self._fail("/mesh/x0 has %d rows but attribute n_nodes = %d" % (x0.shape[0], self.n_nodes))
        if conn.shape[0] != self.n_elems:
            self._fail("/mesh/connectivity has %d rows but attribute n_elems = %d"
                       % (conn.shape[0], self.n_elems))
        if conn.size:
            cmin, cmax = int(conn.min()), int(conn.max())
            if cmin < 0 or cmax >= self.n_nodes:
                hint = " (looks 1-based; the layout requires 0-based node indices)" \
                    if cmin >= 1 and cmax == self.n_nodes else ""
                self._fail("/mesh/connectivity node indices span %d..%d, outside 0..%d%s"
                           % (cmin, cmax, self.n_nodes - 1, hint))
        self.x0 = x0
        self.connectivity = conn.astype(np.int64, copy=False)
        # 2: a 2D (axisymmetric or plane-strain) mesh of triangles in z = 0; 3: tetrahedra
        self.dim = 2 if conn.shape[1] == 3 else 3

        def opt(name, n, default):
            if name in mesh:
                a = np.asarray(mesh[name][()]).reshape(-1)
                if a.shape[0] != n:
                    self._fail("/mesh/%s has %d entries, expected %d" % (name, a.shape[0], n))
                return a
            return default

        self.node_id = opt("node_id", self.n_nodes, np.arange(1, self.n_nodes + 1, dtype=np.int32))
        self.elem_id = opt("elem_id", self.n_elems, np.arange(1, self.n_elems + 1, dtype=np.int32))
        self.part_id = opt("part_id", self.n_elems, np.ones(self.n_elems, dtype=np.int32))

        steps = []
        if "steps" in h5:
            sg = h5["steps"]
            names = sorted((k for k in sg.keys() if k.isdigit() and isinstance(sg[k], h5py.Group)),
                           key=int)
            # /steps@count is authoritative: groups 000000 .. count-1 are the committed steps;
            # a group numbered >= count is a step the writer began but did not finish.
            if "count" in sg.attrs:
                count = int(_decode(sg.attrs["count"]))
                partial = [n for n in names if int(n) >= count]
                names = [n for n in names if int(n) < count]
                if partial:
                    warnings.warn("%s: ignoring uncommitted step group(s) %s (/steps@count = %d)"
                                  % (self.path, ", ".join("/steps/" + n for n in partial), count))
                if len(names) != count:
                    warnings.warn("%s: /steps@count = %d but only %d of the groups 000000..%06d exist"
                                  % (self.path, count, len(names), count - 1))
            for i, name in enumerate(names):
                a = sg[name].attrs
                t = float(_decode(a["time"])) if "time" in a else float("nan")
                c = int(_decode(a["cycle"])) if "cycle" in a else -1
                steps.append(StepInfo(i, name, t, c))
        self.steps = steps
        self.times = np.array([s.time for s in steps], dtype=np.float64)
        self.cycles = np.array([s.cycle for s in steps], dtype=np.int64)

    def xmf_centers(self):
        """{field name: 'node' | 'elem'} from the XDMF index next to the file (NAME.xmf), used
        only when n_nodes == n_elems makes the centring ambiguous; {} if there is none."""
        if getattr(self, "_xmf_centers", None) is None:
            self._xmf_centers = {}
            xmf = os.path.splitext(self.path)[0] + ".xmf"
            if os.path.exists(xmf):
                try:
                    import xml.etree.ElementTree as ET
                    for att in ET.parse(xmf).getroot().iter("Attribute"):
                        c = att.get("Center", "")
                        if c in ("Node", "Cell") and att.get("Name"):
                            self._xmf_centers[att.get("Name")] = "node" if c == "Node" else "elem"
                except Exception as err:  # a damaged index only matters in the ambiguous case
                    warnings.warn("%s: cannot read %s: %s" % (self.path, xmf, err))
        return self._xmf_centers

    # ---- public API
    @property
    def n_steps(self):
        return len(self.steps)

    def __len__(self):
        return len(self.steps)

    def resolve_index(self, i):
        """Step index (negative allowed, -1 = last) -> 0-based index; IndexError if out of range."""
        n = len(self.steps)
        try:
            ii = int(i)
        except (TypeError, ValueError):
            raise IndexError("%s: step index %r is not an integer" % (self.path, i)) from None
        if n == 0:
            raise IndexError("%s: the file has no output steps (no /steps/NNNNNN groups)" % self.path)
        if not -n <= ii < n:
            raise IndexError("%s: step %d out of range; the file has %d step%s (0..%d, or -%d..-1)"
                             % (self.path, ii, n, "" if n == 1 else "s", n - 1, n))
        return ii % n

    def step(self, i=-1):
        """The ``Step`` at index i (negative indices count from the end)."""
        return Step(self, self.steps[self.resolve_index(i)])

    def nearest_step(self, time):
        """Index of the step whose time is closest to ``time`` (s)."""
        if not self.steps:
            raise IndexError("%s: the file has no output steps" % self.path)
        return int(np.nanargmin(np.abs(self.times - time)))

    @property
    def part_ids(self):
        return np.unique(self.part_id)

    @property
    def has_particles(self):
        """True when a step of the file has a particles group (the run turns eroded elements
        into particles), even if none has been made yet."""
        return any("particles" in self._h5["steps"][s.name] for s in self.steps)

    @property
    def part_names(self):
        """{part_id: name} from the &part groups of the deck attribute (part_id k is the k-th
        &part); {} when the deck does not give a name to every part id in the mesh."""
        names = deck_part_names(self.deck)
        ids = [int(p) for p in self.part_ids]
        if not names or not ids or min(ids) < 1 or max(ids) > len(names):
            return {}
        return {k + 1: nm for k, nm in enumerate(names)}

    def summary(self):
        lines = ["%s: program=%s version=%s" % (self.path, self.program or "?", self.version or "?"),
                 "  title: %s" % (self.title or "-"),
                 "  mesh: %d nodes, %d tetrahedra, parts %s" % (
                     self.n_nodes, self.n_elems, ", ".join(
                         "%d (%s)" % (p, self.part_names[p]) if p in self.part_names else str(p)
                         for p in self.part_ids)),
                 "  bounding box (x0, m): " + "  ".join(
                     "%s [%.6g, %.6g]" % (ax, lo, hi) for ax, lo, hi in
                     zip("xyz", self.x0.min(axis=0), self.x0.max(axis=0))) if self.n_nodes else "",
                 "  steps: %d" % len(self.steps)]
        for s in self.steps:
            lines.append("    %4d  /steps/%s  cycle %8d  t = %.6g s (%.4f us)" % (
                s.index, s.name, s.cycle, s.time, s.time * 1e6))
        if self.steps:
            st = self.step(-1)
            desc = []
            for n in st.fields:
                desc.append("%s %s %s" % (n, st.fields.location(n), st.fields.shape(n)))
            lines.append("  fields (last step): " + ("; ".join(desc) or "none"))
            pt = st.particles
            if pt is not None:
                per_part = ""
                if pt.count and "mass" in pt and "part_id" in pt:
                    pids, counts = np.unique(pt["part_id"], return_counts=True)
                    per_part = ", %.6g kg; per part %s" % (float(np.sum(pt["mass"])), ", ".join(
                        "%d: %d" % (p, n) for p, n in zip(pids, counts)))
                lines.append("  particles (last step): %d%s" % (pt.count, per_part))
        return "\n".join(l for l in lines if l)

    def close(self):
        if getattr(self, "_h5", None) is not None:
            self._h5.close()
            self._h5 = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    def __repr__(self):
        return "FieldFile(%r, n_nodes=%d, n_elems=%d, steps=%d)" % (
            self.path, self.n_nodes, self.n_elems, len(self.steps))


def open_fields(path):
    """Open a udar HDF5 field file; returns a ``FieldFile`` (usable in ``with``).

    Raises ``UdarFileError`` (message names the file) if it is missing or malformed.
    """
    return FieldFile(path)


# --------------------------------------------------------------------------------------
# history CSV
# --------------------------------------------------------------------------------------

_FORTRAN_EXP = re.compile(r"^([+-]?(?:\d+\.?\d*|\.\d+))([+-]\d{2,4})$")


def _to_float(text):
    """float() that also accepts Fortran's exponent-without-E ('1.5-100') and '****'."""
    s = text.strip()
    try:
        return float(s)
    except ValueError:
        pass
    s2 = s.replace("D", "E").replace("d", "e")
    m = _FORTRAN_EXP.match(s2)
    if m:
        s2 = m.group(1) + "E" + m.group(2)
    try:
        return float(s2)
    except ValueError:
        if s and set(s) == {"*"}:  # Fortran field overflow
            return float("nan")
        raise


def _is_note(line):
    """A comment line before a history's header: '#', no comma."""
    return line.startswith("#") and "," not in line


def history_note(path):
    """The comment line before a history's header, without its '# ' ('' if none): in 2D
    what the integrated columns stand for (per revolution, per metre of depth)."""
    with open(str(path)) as fh:
        for line in fh:
            if not line.strip():
                continue
            return line.strip().lstrip("#").strip() if _is_note(line) else ""
    return ""


#: A history column's unit after its name (0.9.0 on): 'kinetic [J]'.
_HEADER_UNIT = re.compile(r"\s*\[[^\]]*\]$")


def history_units(path):
    """{column name: unit} from a udar history CSV's header ('kinetic [J]' -> 'J'; '' for a
    column without one, as in files before 0.9.0)."""
    with open(str(path), "r", newline="") as fh:
        for line in fh:
            if line.strip() and not _is_note(line):
                break
        else:
            return {}
    units = {}
    for h in next(csv.reader([line.lstrip("#")])):
        h = h.strip()
        m = _HEADER_UNIT.search(h)
        if h:
            units[_HEADER_UNIT.sub("", h)] = m.group(0).strip()[1:-1] if m else ""
    return units


def read_history(path):
    """Read a udar history CSV -> dict {column name: 1-D float64 numpy array} (file order).

    The first line holds the column names, each with its unit in brackets since 0.9.0
    ('kinetic [J]': the key is 'kinetic'; ``history_units`` gives the units; a leading '#'
    is ignored), after an optional
    comment line ('# ' and no comma: a 2D run says there that its integrated columns are
    per revolution or per metre; ``history_note`` returns it). An incomplete *last* line
    (a run still writing) is dropped with a warning. Raises ``UdarFileError``.
    """
    path = str(path)
    if not os.path.exists(path):
        raise UdarFileError("%s: no such file" % path)
    if os.path.isdir(path):
        raise UdarFileError("%s: is a directory, expected a udar history .csv file" % path)
    try:
        with open(path, "r", newline="") as fh:
            text = fh.read()
    except UnicodeDecodeError:
        raise UdarFileError("%s: not a text file (expected a udar history CSV)" % path) from None
    except OSError as err:
        raise UdarFileError("%s: cannot read: %s" % (path, err)) from None
    lines = text.splitlines()
    while lines and (not lines[0].strip() or _is_note(lines[0])):
        lines.pop(0)
    if not lines:
        raise UdarFileError("%s: empty file (expected a header line with column names)" % path)
    header = next(csv.reader([lines[0].lstrip("#")]))
    names = [_HEADER_UNIT.sub("", h.strip()) for h in header]
    if names and names[-1] == "":
        names.pop()  # trailing comma
    if not names or any(n == "" for n in names):
        raise UdarFileError("%s: header line has empty column names: %r" % (path, lines[0]))
    dup = sorted({n for n in names if names.count(n) > 1})
    if dup:
        raise UdarFileError("%s: duplicate column names in header: %s" % (path, ", ".join(dup)))
    try:
        float(names[0])
        raise UdarFileError("%s: the first line looks numeric; expected a header line with "
                            "column names such as time,cycle,dt,..." % path)
    except ValueError:
        pass
    ncol = len(names)
    body = [(i + 2, l) for i, l in enumerate(lines[1:]) if l.strip()]

    data = None
    if body:
        try:  # fast path: plain numeric CSV
            data = np.loadtxt([l for _, l in body], delimiter=",", dtype=np.float64, ndmin=2)
            if data.shape[1] != ncol:
                data = None
        except ValueError:
            data = None
    if data is None:
        rows = []
        for k, (lineno, line) in enumerate(body):
            fields = [f for f in next(csv.reader([line]))]
            if len(fields) == ncol + 1 and fields[-1].strip() == "":
                fields.pop()
            if len(fields) != ncol:
                if k == len(body) - 1:
                    warnings.warn("%s: line %d has %d values, expected %d; dropping the "
                                  "incomplete last line" % (path, lineno, len(fields), ncol))
                    break
                raise UdarFileError("%s: line %d has %d values, expected %d (columns: %s)"
                                    % (path, lineno, len(fields), ncol, ",".join(names)))
            try:
                rows.append([_to_float(f) for f in fields])
            except ValueError:
                if k == len(body) - 1:
                    warnings.warn("%s: line %d is not numeric; dropping the incomplete last line"
                                  % (path, lineno))
                    break
                bad = [f for f in fields if not _is_number(f)]
                raise UdarFileError("%s: line %d: non-numeric value(s) %s" % (
                    path, lineno, ", ".join(repr(b) for b in bad[:5]))) from None
        data = np.array(rows, dtype=np.float64).reshape(-1, ncol)
    if data is None:
        data = np.zeros((0, ncol))
    return {name: data[:, j].copy() for j, name in enumerate(names)}


def _is_number(s):
    try:
        _to_float(s)
        return True
    except ValueError:
        return False


def history_parts(hist):
    """Part names found in a history dict, from its ``ke_<part>`` columns (file order)."""
    return [k[3:] for k in hist if k.startswith("ke_") and len(k) > 3]


GAUGE_QUANTITIES = ("ux", "uy", "uz", "vx", "vy", "vz", "x", "y", "z", "pressure", "sxx", "syy", "szz", "sxy",
                    "syz", "szx", "von_mises", "plastic_strain", "temperature", "density", "state")


def history_gauges(hist):
    """{gauge name: [its quantities]} from a history dict's ``gauge_<name>_<quantity>`` columns
    (file order; a name may hold underscores)."""
    out = {}
    by_length = sorted(GAUGE_QUANTITIES, key=len, reverse=True)
    for k in hist:
        if not k.startswith("gauge_"):
            continue
        q = next((q for q in by_length if k.endswith("_" + q) and len(k) > len(q) + 7), None)
        if q is not None:
            out.setdefault(k[6:-len(q) - 1], []).append(q)
    return out


# --------------------------------------------------------------------------------------
# synthetic data helpers (used by the self-tests)
# --------------------------------------------------------------------------------------

def _fix_orientation(nodes, conn):
    """Swap two vertices of the tets with negative volume (in place); returns conn."""
    a, b, c, d = (nodes[conn[:, k]] for k in range(4))
    vol = np.einsum("ij,ij->i", np.cross(b - a, c - a), d - a)
    neg = vol < 0
    conn[neg, 1], conn[neg, 2] = conn[neg, 2].copy(), conn[neg, 1].copy()
    return conn


def box_tets(nx, ny, nz, lo=(0.0, 0.0, 0.0), hi=(1.0, 1.0, 1.0)):
    """Structured conforming tet mesh of a box: each hex split into 6 tets (Kuhn).

    Returns (nodes (n, 3) float64, connectivity (6*nx*ny*nz, 4) int32, 0-based).
    """
    xs = [np.linspace(lo[k], hi[k], n + 1) for k, n in enumerate((nx, ny, nz))]
    X, Y, Z = np.meshgrid(*xs, indexing="ij")
    nodes = np.column_stack([X.ravel(), Y.ravel(), Z.ravel()])

    def nid(i, j, k):
        return (i * (ny + 1) + j) * (nz + 1) + k

    I, J, K = np.meshgrid(np.arange(nx), np.arange(ny), np.arange(nz), indexing="ij")
    I, J, K = I.ravel(), J.ravel(), K.ravel()
    unit = np.eye(3, dtype=int)
    tets = []
    for perm in ((0, 1, 2), (0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0)):
        off = np.zeros(3, dtype=int)
        verts = [nid(I, J, K)]
        for ax in perm:
            off = off + unit[ax]
            verts.append(nid(I + off[0], J + off[1], K + off[2]))
        tets.append(np.column_stack(verts))
    conn = np.stack(tets, axis=1).reshape(-1, 4).astype(np.int32)
    return nodes, _fix_orientation(nodes, conn)


def rectangle_tris(nx, ny, lo=(0.0, 0.0), hi=(1.0, 1.0)):
    """Structured triangle mesh of a rectangle in z = 0: each cell split into two
    counter-clockwise triangles. Returns (nodes (n, 3) float64, connectivity (2*nx*ny, 3)
    int32, 0-based): a 2D (axisymmetric or plane-strain) mesh as udar writes it."""
    xs, ys = np.linspace(lo[0], hi[0], nx + 1), np.linspace(lo[1], hi[1], ny + 1)
    X, Y = np.meshgrid(xs, ys, indexing="ij")
    nodes = np.column_stack([X.ravel(), Y.ravel(), np.zeros(X.size)])
    I, J = np.meshgrid(np.arange(nx), np.arange(ny), indexing="ij")
    a = (I * (ny + 1) + J).ravel()
    b, c, d = a + (ny + 1), a + (ny + 1) + 1, a + 1
    conn = np.concatenate([np.column_stack([a, b, c]), np.column_stack([a, c, d])]).astype(np.int32)
    return nodes, conn


def cylinder_tets(radius, length, n_cross=8, n_len=20, sector="full", axis=2, base=0.0):
    """Tet mesh of a solid cylinder (axis through the origin along ``axis``), from a box mesh
    whose square cross-section is mapped onto the disc (boundary nodes lie exactly on r = radius).

    ``sector``: 'full', 'half' (second transverse coordinate >= 0) or 'quarter' (both >= 0).
    The cylinder spans [base, base + length] along the axis. Returns (nodes, connectivity).
    """
    lo = {"full": (-1, -1), "half": (-1, 0), "quarter": (0, 0)}[sector]
    na = n_cross if sector == "quarter" else 2 * n_cross
    nb = n_cross if sector in ("half", "quarter") else 2 * n_cross
    nodes, conn = box_tets(na, nb, n_len, (lo[0], lo[1], 0.0), (1.0, 1.0, 1.0))
    a, b, t = nodes[:, 0], nodes[:, 1], nodes[:, 2]
    u = a * np.sqrt(np.maximum(0.0, 1.0 - 0.5 * b * b))
    v = b * np.sqrt(np.maximum(0.0, 1.0 - 0.5 * a * a))
    # put boundary nodes exactly on the circle
    rr = np.hypot(u, v)
    on_edge = (np.abs(a) == 1.0) | (np.abs(b) == 1.0)
    u[on_edge] /= rr[on_edge]
    v[on_edge] /= rr[on_edge]
    out = np.empty_like(nodes)
    others = [k for k in range(3) if k != axis]
    out[:, others[0]] = radius * u
    out[:, others[1]] = radius * v
    out[:, axis] = base + length * t
    return out, _fix_orientation(out, conn)


def write_fields(path, x0, connectivity, steps, part_id=None, title="synthetic", deck="",
                 version="0.0-test", fixed_length_strings=False):
    """Write a field file in the udar layout (for tests and examples).

    ``steps``: list of dicts with keys ``time``, ``cycle``, ``coordinates`` and optionally
    ``fields`` (dict name -> array) and ``particles`` (dict name -> array, e.g. coordinates,
    velocity, mass, density, part_id, element: a particles group whose ``count`` is the rows
    of ``coordinates``, all datasets float64 as the solver writes them; ``{}`` gives a group
    with count 0 and no datasets). ``fixed_length_strings`` stores string attributes as
    fixed-length byte strings, as a Fortran writer typically does.
    """
    _need_h5py()
    x0 = np.asarray(x0, dtype=np.float64)
    conn = np.asarray(connectivity, dtype=np.int32)
    n_nodes, n_elems = x0.shape[0], conn.shape[0]
    if part_id is None:
        part_id = np.ones(n_elems, dtype=np.int32)

    def s(v):
        return np.bytes_(v.encode()) if fixed_length_strings else v

    with h5py.File(path, "w") as h5:
        h5.attrs["program"] = s("udar")
        h5.attrs["version"] = s(version)
        h5.attrs["title"] = s(title)
        h5.attrs["deck"] = s(deck or "&run t_end = 1e-5 /")
        h5.attrs["n_nodes"] = np.int32(n_nodes)
        h5.attrs["n_elems"] = np.int32(n_elems)
        m = h5.create_group("mesh")
        m["node_id"] = np.arange(1, n_nodes + 1, dtype=np.int32)
        m["elem_id"] = np.arange(1, n_elems + 1, dtype=np.int32)
        m["part_id"] = np.asarray(part_id, dtype=np.int32)
        m["connectivity"] = conn
        m["x0"] = x0
        sg = h5.create_group("steps")
        sg.attrs["count"] = np.int32(len(steps))
        for i, st in enumerate(steps):
            g = sg.create_group("%06d" % i)
            g.attrs["time"] = np.float64(st["time"])
            g.attrs["cycle"] = np.int32(st["cycle"])
            g["coordinates"] = np.asarray(st["coordinates"], dtype=np.float64)
            for name, val in st.get("fields", {}).items():
                g[name] = np.asarray(val)
            if st.get("particles") is not None:
                pg = g.create_group("particles")
                pts = st["particles"]
                count = len(pts["coordinates"]) if "coordinates" in pts else 0
                pg.attrs["count"] = np.int64(count)
                if count:
                    for name, val in pts.items():
                        pg[name] = np.asarray(val, dtype=np.float64)


def write_history(path, columns, names=None):
    """Write a history CSV (header line, then one row per entry, ``%.10E``) from ``columns``
    {name: 1-D array}; ``names`` picks and orders the columns (default: all, dict order)."""
    names = list(names or columns)
    with open(path, "w") as fh:
        fh.write(",".join(names) + "\n")
        for i in range(len(columns[names[0]])):
            fh.write(",".join("%.10E" % columns[c][i] for c in names) + "\n")


# --------------------------------------------------------------------------------------
# pieces shared by the postproc scripts: figures, the CLI frame, self-test checks
# --------------------------------------------------------------------------------------

def si_scale(values, unit, prefixes=((1e9, "G"), (1e6, "M"), (1e3, "k"))):
    """(factor, unit with SI prefix) so that the largest finite |value| reads below 1000."""
    finite = np.asarray(values, dtype=float)
    finite = finite[np.isfinite(finite)]
    m = float(np.max(np.abs(finite))) if finite.size else 0.0
    for f, p in prefixes:
        if m >= f:
            return 1.0 / f, p + unit
    return 1.0, unit


def agg_pyplot():
    """``matplotlib.pyplot`` on the Agg backend (no display needed)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def save_figure(fig, out, dpi, error=UdarFileError):
    """Write ``fig`` to ``out`` (format from the extension) and close it; a failure raises
    ``error("cannot write OUT: reason")``."""
    import matplotlib.pyplot as plt
    try:
        # the whole figure, labels and titles included (an equal-aspect axes can push them out)
        fig.savefig(out, dpi=dpi, bbox_inches="tight", pad_inches=0.1)
    except (OSError, ValueError) as e:
        raise error("cannot write %s: %s" % (out, e)) from None
    finally:
        plt.close(fig)


def cli_parser(prog, description, epilog):
    """The argument parser of a postproc script (``epilog``: examples, shown as written)."""
    return argparse.ArgumentParser(prog=prog, description=description, epilog=epilog,
                                   formatter_class=argparse.RawDescriptionHelpFormatter)


#: ``cli_main(..., require=FIELDS_REQUIRED)`` for the scripts using ``add_fields_argument``
FIELDS_REQUIRED = ("fields", "the FIELDS.h5 argument is required (or --self-test)")


def add_fields_argument(parser):
    """Add the FIELDS.h5 argument of the scripts that read a field file and a mutually
    exclusive group holding --step (add the alternatives to it); returns the group."""
    parser.add_argument("fields", nargs="?", metavar="FIELDS.h5", help="udar HDF5 field file")
    group = parser.add_mutually_exclusive_group()
    group.add_argument("--step", type=int, default=-1,
                       help="output step index, negative from the end (default -1 = last)")
    return group


def add_figure_arguments(parser, size_help="figure size in inches"):
    """Add the --size W H and --dpi options every plotting script takes; returns the parser."""
    parser.add_argument("--size", type=float, nargs=2, metavar=("W", "H"), help=size_help)
    parser.add_argument("--dpi", type=int, default=150, help="image resolution (default 150)")
    return parser


def add_self_test(parser, help="run the built-in checks, print PASS/FAIL"):
    """Add the --self-test option that ``cli_main`` acts on (last, as in every script's
    --help); returns the parser."""
    parser.add_argument("--self-test", action="store_true", help=help)
    return parser


def cli_main(parser, argv, self_test, run, errors=(), require=None):
    """The frame of the postproc command-line scripts; returns the exit status.

    Parses ``argv`` (argparse usage errors exit with 2), makes warnings print one line
    'prog: warning: ...', runs ``self_test()`` for --self-test (0 on PASS, else 1), stops with
    a usage error ``require[1]`` when the positional argument ``require[0]`` (its dest) is
    missing, then returns ``run(args, parser)`` (None = 0). ``UdarFileError``, the exception
    types in ``errors`` and a missing module (ImportError) print one line
    'prog: error: <message>' on stderr and give 1.
    """
    args = parser.parse_args(argv)
    prog = parser.prog
    cli_warnings(prog)
    if args.self_test:
        return 0 if self_test() else 1
    if require and not getattr(args, require[0]):
        parser.error(require[1])
    try:
        return run(args, parser) or 0
    except (UdarFileError,) + tuple(errors) as e:
        print("%s: error: %s" % (prog, e.args[0] if e.args else e), file=sys.stderr)
    except ImportError as e:  # matplotlib missing
        print("%s: error: %s (run the udar post-processing scripts with /usr/bin/python3)"
              % (prog, e), file=sys.stderr)
    return 1


class SelfTest:
    """The checks of a script's --self-test: ``check`` records one (and prints 'ok'/'FAIL'
    with its description when verbose); ``finish`` prints 'NAME self-test: PASS' (or
    'FAIL (n)') and returns True when every check passed."""

    def __init__(self, name, verbose=True):
        self.name, self.verbose, self.failures = name, verbose, []

    def check(self, cond, what):
        if self.verbose:
            print("  %s  %s" % ("ok  " if cond else "FAIL", what))
        if not cond:
            self.failures.append(what)

    def raises(self, exc, what, func, *args, contains=(), **kwargs):
        """Check that ``func(*args, **kwargs)`` raises ``exc`` whose text has every string
        of ``contains`` (a string or a tuple of strings)."""
        try:
            func(*args, **kwargs)
        except exc as e:
            words = (contains,) if isinstance(contains, str) else contains
            self.check(all(w in str(e) for w in words), what)
        else:
            self.check(False, what)

    @staticmethod
    def run_main(main, argv):
        """Call a script's ``main(argv)`` capturing its output -> (status, stdout, stderr)."""
        out, err = io.StringIO(), io.StringIO()
        with redirect_stdout(out), redirect_stderr(err):
            rc = main(argv)
        return rc, out.getvalue(), err.getvalue()

    def finish(self):
        ok = not self.failures
        print("%s self-test: %s" % (self.name, "PASS" if ok else "FAIL (%d)" % len(self.failures)))
        return ok


# --------------------------------------------------------------------------------------
# self-test and CLI
# --------------------------------------------------------------------------------------

def _self_test(verbose=True):
    """Round-trip synthetic files through the readers. Returns True if all checks pass."""
    test = SelfTest("udar_results", verbose)
    check = test.check
    with tempfile.TemporaryDirectory(prefix="udar_results_test_") as tmp:
        nodes, conn = box_tets(2, 3, 4)
        check(conn.shape == (6 * 24, 4), "box_tets element count")
        a, b, c, d = (nodes[conn[:, k]] for k in range(4))
        vol = np.einsum("ij,ij->i", np.cross(b - a, c - a), d - a) / 6.0
        check(abs(vol.sum() - 1.0) < 1e-12 and vol.min() > 0, "box_tets volumes positive, sum 1")
        cn, cc = cylinder_tets(0.5, 2.0, 4, 5, "quarter")
        r = np.hypot(cn[:, 0], cn[:, 1])
        check(abs(r.max() - 0.5) < 1e-15 and cn[:, 0].min() == 0.0, "cylinder_tets quarter radius")

        h5path = os.path.join(tmp, "case.h5")
        pid = np.where(np.arange(len(conn)) < len(conn) // 2, 1, 2).astype(np.int32)
        steps = []
        for i in range(3):
            steps.append({"time": 1e-6 * i, "cycle": 10 * i, "coordinates": nodes * (1 + 0.1 * i),
                          "fields": {"pressure": np.full(len(conn), float(i)),
                                     "velocity": np.zeros((len(nodes), 3))}})
        write_fields(h5path, nodes, conn, steps, part_id=pid, fixed_length_strings=True)
        with open_fields(h5path) as f:
            check(f.program == "udar" and f.title == "synthetic", "string attributes decoded")
            check(f.n_nodes == len(nodes) and f.n_elems == len(conn), "counts")
            check(len(f.steps) == 3 and f.steps[2].cycle == 20, "step list")
            s = f.step(-1)
            check(s.index == 2 and abs(s.time - 2e-6) < 1e-20, "negative step index")
            check(np.allclose(s.coordinates, nodes * 1.2), "coordinates")
            check(set(s.fields) == {"pressure", "velocity"}, "field names")
            check(s.fields.location("pressure") == "elem" and s.fields.location("velocity") == "node",
                  "field locations")
            check(float(s.fields["pressure"][0]) == 2.0, "lazy field read")
            test.raises(IndexError, "out-of-range step raises IndexError", f.step, 3,
                        contains="out of range")
            test.raises(KeyError, "unknown field raises KeyError listing fields",
                        s.fields.__getitem__, "nope", contains="available")

        with h5py.File(h5path, "a") as h5:  # a crashed writer: partial group 000003
            g = h5["steps"].create_group("000003")
            g.attrs["time"] = 3e-6
        with warnings.catch_warnings(record=True) as w:
            warnings.simplefilter("always")
            with open_fields(h5path) as f:
                n = len(f.steps)
        check(n == 3 and any("uncommitted" in str(x.message) for x in w),
              "group numbered >= /steps@count ignored")

        amb = os.path.join(tmp, "amb.h5")  # n_nodes == n_elems: centring from the .xmf
        an = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
        ac = np.array([[0, 1, 2, 3]] * 4, dtype=np.int32)
        write_fields(amb, an, ac, [{"time": 0.0, "cycle": 0, "coordinates": an,
                                    "fields": {"q": np.zeros(4), "velocity": np.zeros((4, 3))}}])
        with open_fields(amb) as f:
            guess = f.step(0).fields.location("q")
        with open(os.path.join(tmp, "amb.xmf"), "w") as fh:
            fh.write('<Xdmf Version="3.0"><Domain><Grid><Grid><Attribute Name="q" '
                     'AttributeType="Scalar" Center="Node"/></Grid></Grid></Domain></Xdmf>')
        with open_fields(amb) as f:
            check(guess == "elem" and f.step(0).fields.location("q") == "node"
                  and f.step(0).fields.location("velocity") == "node",
                  "n_nodes == n_elems: centring from the .xmf index")

        deck = ("! udar resolved input deck\n&mesh\n  file = 'a/b.msh'  ! path with / inside\n/\n"
                "&part\n  group = 'rod'   ! (default)\n  material = 'cu'\n/\n"
                "&part group = \"it's plate\", velocity = 0, 0, -1 /\n")
        check(deck_part_names(deck) == ["rod", "it's plate"], "part names from the deck text")
        vals = deck_values("\n  name = 'a = b, c'  ! (default)\n  rho0 = 8.93d3, c0 = 3940.0\n"
                           "  velocity = 0.0, 0.0, -500.0  ! m/s\n  anti_locking = .false.\n")
        check(vals == {"name": "a = b, c", "rho0": 8930.0, "c0": 3940.0,
                       "velocity": [0.0, 0.0, -500.0], "anti_locking": False},
              "deck_values: strings with '=' and ',', Fortran exponents, lists, logicals")
        h, side = wall_heights([[0, 0, -1.0], [0, 0, -3.0]], 2, -0.5)
        check(side == -1.0 and h.tolist() == [0.5, 2.5], "wall_heights: body below the wall")
        write_fields(h5path, nodes, conn, steps, part_id=pid, deck=deck)
        with open_fields(h5path) as f:
            check(f.part_names == {1: "rod", 2: "it's plate"}, "FieldFile.part_names")
            check(not f.has_particles and f.step(-1).particles is None
                  and "particles" not in f.summary(), "no particles group: particles None")

        # particles: none at step 0 (count 0, no datasets), 3 then 4 at steps 1 and 2
        pxyz = np.array([[0.1, 0.2, 0.3], [0.4, 0.5, 0.6], [0.7, 0.8, 0.9], [1.0, 1.1, 1.2]])
        psteps = [dict(st) for st in steps]
        psteps[0]["particles"] = {}
        for i, n in ((1, 3), (2, 4)):
            psteps[i]["particles"] = {
                "coordinates": pxyz[:n], "velocity": -pxyz[:n] * 1e3,
                "mass": 8e-9 * 7800.0 * np.arange(1, n + 1) ** 3, "density": np.full(n, 7800.0),
                "pressure": np.linspace(0, 1e9, n), "specific_internal_energy": np.ones(n),
                "temperature": np.full(n, 300.0), "plastic_strain": np.zeros(n),
                "part_id": np.array([1, 2, 1, 2][:n], float), "element": np.arange(n) * 7.0}
        ph5 = os.path.join(tmp, "particles.h5")
        write_fields(ph5, nodes, conn, psteps, part_id=pid, deck=deck)
        with open_fields(ph5) as f:
            check(f.has_particles and len(f.steps) == 3, "FieldFile.has_particles")
            p0, p2 = f.step(0).particles, f.step(-1).particles
            check(p0 is not None and p0.count == 0 and p0.coordinates.shape == (0, 3)
                  and p0["mass"].shape == (0,) and p0["part_id"].dtype == np.int64
                  and set(p0) == set(PARTICLE_FIELDS), "count 0: empty arrays of every field")
            check(p2.count == 4 and not p2._cache, "particles: count, nothing read before use")
            check(np.array_equal(p2.coordinates, pxyz) and np.array_equal(p2.velocity, -pxyz * 1e3)
                  and set(p2._cache) == {"coordinates", "velocity"}, "particle coordinates, velocity")
            check(p2["part_id"].dtype == np.int64 and p2["part_id"].tolist() == [1, 2, 1, 2]
                  and p2["element"].tolist() == [0, 7, 14, 21], "part_id, element as int64")
            check(abs(particle_spacing(p2) - 5e-3) < 1e-15 and np.isnan(particle_spacing(p0))
                  and np.isnan(particle_spacing(None)),
                  "particle_spacing: median (mass/density)^(1/3) of 2, 4, 6, 8 mm: %.17g (5e-3)" % particle_spacing(p2))
            check(f.step(1).particles.count == 3 and "particles" not in f.step(1).fields,
                  "step 1: 3 particles, not among the fields")
            check("particles (last step): 4, " in f.summary() and "per part 1: 2, 2: 2" in f.summary(),
                  "summary line of the particles")
            test.raises(KeyError, "unknown particle dataset raises KeyError listing them",
                        p2.__getitem__, "von_mises", contains=("available", "mass"))
        with h5py.File(ph5, "a") as h5:  # a transposed vector, a dataset with too few rows
            g = h5["steps/000002/particles"]
            del g["velocity"], g["mass"]
            g["velocity"] = (-pxyz * 1e3).T.copy()
            g["mass"] = np.ones(3)
        with open_fields(ph5) as f:
            with warnings.catch_warnings(record=True) as w:
                warnings.simplefilter("always")
                v = f.step(2).particles.velocity
            check(np.array_equal(v, -pxyz * 1e3) and any("transposed" in str(x.message) for x in w),
                  "particle velocity stored (3, count): transposed back with a warning")
            test.raises(UdarFileError, "particle dataset with the wrong row count rejected",
                        f.step(2).particles.__getitem__, "mass", contains=("mass", "4 rows"))

        bad = os.path.join(tmp, "bad.h5")
        with open(bad, "w") as fh:
            fh.write("not hdf5")
        test.raises(UdarFileError, "non-HDF5 file rejected", open_fields, bad,
                    contains=("bad.h5", "not an HDF5"))
        test.raises(UdarFileError, "missing file rejected", open_fields,
                    os.path.join(tmp, "missing.h5"), contains="no such file")
        one = os.path.join(tmp, "onebased.h5")
        write_fields(one, nodes, conn + 1, steps[:1])
        test.raises(UdarFileError, "1-based connectivity rejected", open_fields, one,
                    contains="1-based")

        csvpath = os.path.join(tmp, "case_history.csv")
        with open(csvpath, "w") as fh:
            fh.write("time,cycle,dt,kinetic,ke_rod,com_z_rod\n")
            fh.write("0.0,0,1e-9,100.0,100.0,0.01\n")
            fh.write("1.0E-06,100,1.0E-09,9.9E+01,9.9E+01,1.0-102\n")
            fh.write("2.0E-06,200,1.0E-09,9.8E+01,9.8\n")  # truncated last line
        with warnings.catch_warnings(record=True) as w:
            warnings.simplefilter("always")
            h = read_history(csvpath)
        check(len(h["time"]) == 2 and h["cycle"][1] == 100.0, "history rows (truncated last dropped)")
        check(abs(h["com_z_rod"][1] - 1e-102) < 1e-115, "Fortran exponent without E")
        check(any("incomplete" in str(x.message) for x in w), "warning for truncated line")
        check(history_parts(h) == ["rod"], "history_parts")
        check(history_note(csvpath) == "", "no note in a 3D history")
        with open(csvpath, "w") as fh:
            fh.write("# udar history: axisymmetric (x = r; y the axis): per revolution (2 pi rad)\n")
            fh.write("time,cycle,kinetic\n0,0,1\n1e-6,10,2\n")
        h = read_history(csvpath)
        check(list(h) == ["time", "cycle", "kinetic"] and h["kinetic"][1] == 2.0, "history after a 2D note")
        check(history_note(csvpath).endswith("per revolution (2 pi rad)"), "history_note")
        with open(csvpath, "w") as fh:
            fh.write("time,kinetic\n0,1\n1,abc\n2,3\n")
        test.raises(UdarFileError, "non-numeric history rejected with line number", read_history,
                    csvpath, contains="line 3")
    return test.finish()


def _summarize_history(path):
    h = read_history(path)
    n = len(next(iter(h.values()))) if h else 0
    print("%s: %d rows, %d columns" % (path, n, len(h)))
    print("  parts: %s" % (", ".join(history_parts(h)) or "none"))
    for k, v in h.items():
        if n:
            print("  %-20s first %-14.6g last %-14.6g min %-14.6g max %.6g"
                  % (k, v[0], v[-1], np.nanmin(v), np.nanmax(v)))
        else:
            print("  %-20s (no rows)" % k)


def main(argv=None):
    p = cli_parser(
        "udar_results.py",
        "Summarize a udar output file: an HDF5 field file (<case>.h5: mesh, steps, "
        "fields) or a history CSV (<case>_history.csv: columns with first/last/min/max). "
        "Mainly a library for the other postproc scripts.",
        "examples:\n  /usr/bin/python3 postproc/udar_results.py out/taylor.h5\n"
        "  /usr/bin/python3 postproc/udar_results.py out/taylor_history.csv\n"
        "  /usr/bin/python3 postproc/udar_results.py --self-test")
    p.add_argument("file", nargs="?", help="a udar .h5 field file or _history.csv file")
    return cli_main(add_self_test(p), argv, _self_test, _summarize, errors=(IndexError, KeyError),
                    require=("file", "give a FILE (or --self-test)"))


def _summarize(args, parser):
    if args.file.lower().endswith(".csv"):
        _summarize_history(args.file)
    else:
        with open_fields(args.file) as f:
            print(f.summary())


if __name__ == "__main__":
    sys.exit(main())
