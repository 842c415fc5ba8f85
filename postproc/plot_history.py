#!/usr/bin/python3
"""Plot a udar history CSV (<case>_history.csv): energies, energy error, momentum, wall
force, and per-part kinetic energy and centre-of-mass displacement, against time in µs;
with --gauges, the gauges' histories (&gauge) instead.

    /usr/bin/python3 postproc/plot_history.py out/taylor_history.csv -o taylor_history.png
    /usr/bin/python3 postproc/plot_history.py out/taylor_history.csv --gauges -o gauges.png
    /usr/bin/python3 postproc/plot_history.py --self-test

Panels whose columns are missing from the file are left out (a warning names them).
Library use: ``plot_history(path, out, ...)``, ``plot_gauges(path, out, ...)``.
"""

import math
import os
import sys
import tempfile
import textwrap
import warnings

if __package__:
    from . import udar_results as ur
else:
    import udar_results as ur  # run as a script, it stops with a message if numpy is missing
import numpy as np


class HistoryError(Exception):
    """Bad history file or request; the message names the file and the problem."""


def decimate(x, y, max_points=20000):
    """Thin a long curve for plotting, keeping each bin's min and max (spikes stay visible)."""
    n = len(x)
    if n <= max_points:
        return x, y
    k = int(math.ceil(n / (max_points / 2.0)))
    nb = n // k
    yb = y[:nb * k].reshape(nb, k)
    base = np.arange(nb) * k
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        lo = base + np.nanargmin(np.where(np.isnan(yb), np.inf, yb), axis=1)
        hi = base + np.nanargmax(np.where(np.isnan(yb), -np.inf, yb), axis=1)
    idx = np.unique(np.concatenate([lo, hi, np.arange(nb * k, n), [0, n - 1]]))
    return x[idx], y[idx]


#: scalar history columns summed over the body (scaled by --whole); momenta are not: the
#: components across a symmetry plane cancel in the whole body
INTEGRATED = {"kinetic", "internal", "plastic_work", "wall_work", "external_work", "total", "wall_force",
              "eroded_energy", "mass", "contact_work", "particle_mass", "particle_kinetic", "particle_internal",
              "conversion_heat"}
INTEGRATED_PREFIXES = ("ke_", "internal_", "plastic_work_", "eroded_energy_", "mass_", "contact_normal_",
                       "contact_friction_")


def case_name(path):
    """'out/taylor_history.csv' -> 'taylor'."""
    stem = os.path.splitext(os.path.basename(path))[0]
    return stem[:-len("_history")] if stem.endswith("_history") and len(stem) > 8 else stem


def plot_history(path, out, title=None, error_limit=None, size=None, dpi=150, verbose=True, whole=None):
    """Read the history CSV ``path`` and write the figure ``out``. Returns a summary dict.

    The integrated quantities (energies, momenta, the wall force) are those of the model, as
    the history's note says (a quarter model holds a quarter of the rod); ``whole`` multiplies
    the energies, masses and forces by that factor (4 for a quarter model; not the momenta,
    whose components across a symmetry plane cancel in the whole body) and the title says so."""
    plt = ur.agg_pyplot()
    h = ur.read_history(path)
    note = ur.history_note(path)
    if whole is not None:
        if not (whole > 0 and math.isfinite(whole)):
            raise HistoryError("--whole must be a positive factor, got %r" % whole)
        for c in list(h):
            if c in INTEGRATED or c.startswith(INTEGRATED_PREFIXES):
                h[c] = h[c] * whole
    if "time" not in h:
        raise HistoryError("%s: no 'time' column (columns: %s)" % (path, ", ".join(h)))
    n = len(h["time"])
    if n == 0:
        raise HistoryError("%s: no data rows after the header" % path)
    t_us = h["time"] * 1e6
    parts = ur.history_parts(h)
    missing = []

    def have(*cols):
        return all(c in h for c in cols)

    panels = []

    # 1. energies
    ecols = [("kinetic", "kinetic", "-"), ("internal", "internal", "-"),
             ("plastic_work", "plastic work", "--"), ("total", "total", "-")]
    present = [c for c in ecols if c[0] in h]
    for c, lab in (("external_work", "external work"), ("wall_work", "wall work")):
        if c in h and np.any(h[c] != 0.0):
            present.append((c, lab, ":"))
    if present:
        def p_energy(ax):
            f, u = ur.si_scale(np.concatenate([h[c] for c, _, _ in present]), "J")
            for c, lab, ls in present:
                kw = {"color": "k", "lw": 1.6} if c == "total" else {}
                ax.plot(*decimate(t_us, h[c] * f), ls=ls, label=lab, **kw)
            ax.set_ylabel("energy (%s)" % u)
            ax.set_title("energies")
            ax.legend(fontsize="small")
        panels.append(p_energy)
    missing += [c for c, _, _ in ecols if c not in h]

    # 2. energy error (relative, dimensionless)
    if "energy_error" in h:
        def p_error(ax):
            ax.plot(*decimate(t_us, h["energy_error"] * 100.0), color="C3")
            if error_limit:
                for s in (1, -1):
                    ax.axhline(s * error_limit * 100.0, color="k", ls="--", lw=0.8)
            ax.axhline(0.0, color="0.5", lw=0.5)
            ax.set_ylabel("relative energy error (%)")
            ax.set_title("energy error")
        panels.append(p_error)
    else:
        missing.append("energy_error")

    # 3. momentum
    mcols = [c for c in ("momentum_x", "momentum_y", "momentum_z") if c in h]
    if mcols:
        def p_mom(ax):
            for c in mcols:
                ax.plot(*decimate(t_us, h[c]), label=c.split("_")[1])
            ax.set_ylabel("momentum (kg m/s)")
            ax.set_title("momentum")
            ax.legend(fontsize="small")
        panels.append(p_mom)
    missing += [c for c in ("momentum_x", "momentum_y", "momentum_z") if c not in h]

    # 4. wall force
    if "wall_force" in h:
        def p_wall(ax):
            f, u = ur.si_scale(h["wall_force"], "N")
            ax.plot(*decimate(t_us, h["wall_force"] * f), color="C4")
            ax.set_ylabel("wall force (%s)" % u)
            ax.set_title("rigid wall force")
        panels.append(p_wall)
    else:
        missing.append("wall_force")

    # 5. per-part kinetic energy
    if parts:
        def p_ke(ax):
            f, u = ur.si_scale(np.concatenate([h["ke_" + p] for p in parts]), "J")
            for k, p in enumerate(parts):
                ax.plot(*decimate(t_us, h["ke_" + p] * f), color="C%d" % (k % 10), label=p)
            ax.set_ylabel("kinetic energy (%s)" % u)
            ax.set_title("kinetic energy per part")
            ax.legend(fontsize="small")
        panels.append(p_ke)

    # 6. per-part centre-of-mass displacement
    com = [(p, ax_) for p in parts for ax_ in "xyz" if "com_%s_%s" % (ax_, p) in h]
    if com:
        def p_com(ax):
            disp = {(p, a): (h["com_%s_%s" % (a, p)] - h["com_%s_%s" % (a, p)][0]) * 1e3
                    for p, a in com}
            big = max([np.nanmax(np.abs(d)) for d in disp.values()] + [0.0])
            styles = {"x": "-", "y": "--", "z": ":"}
            drawn = 0
            for (p, a), d in disp.items():
                if big > 0.0 and np.nanmax(np.abs(d)) < 1e-6 * big:
                    continue  # a component that does not move
                k = parts.index(p)
                ax.plot(*decimate(t_us, d), color="C%d" % (k % 10), ls=styles[a], label="%s %s" % (p, a))
                drawn += 1
            if drawn == 0:
                ax.plot(t_us, np.zeros_like(t_us), color="0.5", label="no motion")
            ax.set_ylabel("centre of mass displacement (mm)")
            ax.set_title("centre of mass per part")
            ax.legend(fontsize="small")
        panels.append(p_com)

    if not panels:
        raise HistoryError("%s: none of the expected columns (kinetic, internal, energy_error, "
                           "momentum_x, wall_force, ke_<part>, ...) is present; columns: %s"
                           % (path, ", ".join(h)))
    if missing:
        warnings.warn("%s: missing column(s) %s; their curves are left out" % (path, ", ".join(missing)))

    ncols = 1 if len(panels) == 1 else 2
    nrows = int(math.ceil(len(panels) / ncols))
    fig, axes = plt.subplots(nrows, ncols, figsize=size or (6.0 * ncols, 3.2 * nrows + 0.6),
                             sharex=True, squeeze=False, constrained_layout=True)
    flat = axes.ravel()
    for ax, draw in zip(flat, panels):
        draw(ax)
        ax.grid(True, lw=0.4, alpha=0.5)
    for ax in flat[len(panels):]:
        ax.remove()
    for c in range(ncols):  # time label on the lowest panel of each column
        col = [flat[r * ncols + c] for r in range(nrows) if r * ncols + c < len(panels)]
        if col:
            col[-1].set_xlabel("time (µs)")
            col[-1].xaxis.set_tick_params(labelbottom=True)
    head = title or "%s — history" % case_name(path)
    if whole is not None:
        head += "\nenergies, masses and forces x %g: the whole body (momenta: the model's)" % whole
    elif note:
        # what the integrated curves stand for (the modelled part, per revolution, per metre)
        head += "\n" + "\n".join(textwrap.wrap(note.replace("udar history: ", ""), 110))
    fig.suptitle(head, fontsize="medium")
    ur.save_figure(fig, out, dpi, HistoryError)

    summary = {"rows": n, "t_end_s": float(h["time"][-1]), "parts": parts, "panels": len(panels),
               "title": head}
    if "kinetic" in h:
        summary["kinetic_0"] = float(h["kinetic"][0])
    if "energy_error" in h and np.any(np.isfinite(h["energy_error"])):
        k = int(np.nanargmax(np.abs(h["energy_error"])))
        summary["max_abs_energy_error"] = float(abs(h["energy_error"][k]))
        summary["max_abs_energy_error_time_s"] = float(h["time"][k])
        summary["final_energy_error"] = float(h["energy_error"][-1])
    if verbose:
        line = "%s: %d rows, t = 0 .. %.4f us, parts: %s" % (
            path, n, summary["t_end_s"] * 1e6, ", ".join(parts) or "none")
        if "max_abs_energy_error" in summary:
            line += "; max |energy error| %.3g %% at %.4f us, final %.3g %%" % (
                summary["max_abs_energy_error"] * 100, summary["max_abs_energy_error_time_s"] * 1e6,
                summary["final_energy_error"] * 100)
        print(line)
        print("wrote %s" % out)
    return summary


# the gauge quantities drawn by default (those some gauge has and that are not 0 throughout)
GAUGE_DEFAULT = ("vx", "vy", "vz", "ux", "uy", "uz", "pressure", "von_mises", "plastic_strain", "temperature")
GAUGE_LABELS = {"ux": "displacement x", "uy": "displacement y", "uz": "displacement z", "vx": "velocity x",
                "vy": "velocity y", "vz": "velocity z", "x": "position x", "y": "position y", "z": "position z",
                "pressure": "pressure", "sxx": "stress xx", "syy": "stress yy", "szz": "stress zz",
                "sxy": "stress xy", "syz": "stress yz", "szx": "stress zx", "von_mises": "von Mises stress",
                "plastic_strain": "plastic strain", "temperature": "temperature", "density": "density"}
# drawn in these units (SI in the file)
GAUGE_SCALE = {"m": (1e3, "mm"), "Pa": (1e-6, "MPa")}


def plot_gauges(path, out, names=None, quantities=None, title=None, size=None, dpi=150, verbose=True):
    """The gauges' histories (&gauge) of the history CSV ``path``: a panel per quantity, a
    curve per gauge, against time in µs; where a gauge's element eroded (state 2) or became
    a particle (state 3) its curve is marked. ``names``: the gauges (default all);
    ``quantities``: what to draw (default GAUGE_DEFAULT, those present and not all 0).
    Returns a summary dict."""
    plt = ur.agg_pyplot()
    h = ur.read_history(path)
    units = ur.history_units(path)
    gauges = ur.history_gauges(h)
    if not gauges:
        raise HistoryError("%s: no gauge columns (gauge_<name>_<quantity>; a deck's &gauge groups "
                           "make them)" % path)
    for g in names or []:
        if g not in gauges:
            raise HistoryError("%s: no gauge %r (gauges: %s)" % (path, g, ", ".join(gauges)))
    names = list(names or gauges)
    for q in quantities or []:
        if q not in GAUGE_LABELS:
            raise HistoryError("unknown gauge quantity %r (known: %s)" % (q, ", ".join(GAUGE_LABELS)))
    wanted = quantities or [q for q in GAUGE_DEFAULT
                            if any(q in gauges[g] and np.any(h["gauge_%s_%s" % (g, q)] != 0.0) for g in names)]
    wanted = [q for q in wanted if any(q in gauges[g] for g in names)]
    if not wanted:
        raise HistoryError("%s: the gauges %s have none of %s" % (path, ", ".join(names),
                                                                  ", ".join(quantities or GAUGE_DEFAULT)))
    t_us = h["time"] * 1e6
    ncols = 1 if len(wanted) == 1 else 2
    nrows = int(math.ceil(len(wanted) / ncols))
    fig, axes = plt.subplots(nrows, ncols, figsize=size or (6.0 * ncols, 3.0 * nrows + 0.6),
                             sharex=True, squeeze=False, constrained_layout=True)
    flat = axes.ravel()
    marked = set()
    for ax, q in zip(flat, wanted):
        unit = units.get("gauge_%s_%s" % (names[0], q), "") or "-"
        scale, shown = GAUGE_SCALE.get(unit, (1.0, unit))
        for k, g in enumerate(names):
            if q not in gauges[g]:
                continue
            y = h["gauge_%s_%s" % (g, q)] * scale
            line, = ax.plot(*decimate(t_us, y), lw=1.0, label=g, color="C%d" % (k % 10))
            if "state" in gauges[g]:
                state = h["gauge_%s_state" % g]
                for s, marker, what in ((2, "x", "eroded"), (3, "o", "became a particle")):
                    hit = np.flatnonzero(state == s)
                    if len(hit):
                        ax.plot(t_us[hit[0]], y[hit[0]], marker, color=line.get_color(), mfc="none", ms=7)
                        marked.add((marker, what))
        ax.set_ylabel("%s (%s)" % (GAUGE_LABELS[q], shown) if shown != "-" else GAUGE_LABELS[q])
        ax.grid(True, lw=0.4, alpha=0.5)
    flat[0].legend(fontsize="small")
    for ax in flat[len(wanted):]:
        ax.remove()
    for c in range(ncols):
        col = [flat[r * ncols + c] for r in range(nrows) if r * ncols + c < len(wanted)]
        if col:
            col[-1].set_xlabel("time (µs)")
            col[-1].xaxis.set_tick_params(labelbottom=True)
    head = title or "%s — gauges" % case_name(path)
    if marked:
        head += "\n" + ", ".join("%s: the element %s" % (m, w) for m, w in sorted(marked, reverse=True))
    fig.suptitle(head, fontsize="medium")
    ur.save_figure(fig, out, dpi, HistoryError)
    if verbose:
        print("%s: gauges %s, quantities %s" % (path, ", ".join(names), ", ".join(wanted)))
        print("wrote %s" % out)
    return {"gauges": names, "quantities": wanted, "panels": len(wanted), "marked": sorted(marked)}


# --------------------------------------------------------------------------------------
# self-test
# --------------------------------------------------------------------------------------

def _write_synthetic(path, parts=("rod", "anvil_plate"), n=400, columns=None):
    """A history CSV of an impact with the given parts (all columns, or ``columns``)."""
    t = np.linspace(0.0, 8e-5, n)
    ke0 = 2000.0
    ke = ke0 * np.exp(-t / 2e-5)
    pw = 0.8 * (ke0 - ke)
    ie = ke0 - ke
    cols = {
        "time": t, "cycle": np.arange(n) * 100, "dt": np.full(n, 2e-9),
        "kinetic": ke, "internal": ie, "plastic_work": pw, "wall_work": -0.01 * (ke0 - ke),
        "total": ke + ie, "energy_error": 1e-3 * np.sin(t / 1e-5),
        "momentum_x": np.zeros(n), "momentum_y": np.zeros(n), "momentum_z": -10.0 * np.exp(-t / 2e-5),
        "wall_force": 2e5 * np.exp(-t / 1e-5),
    }
    for k, p in enumerate(parts):
        cols["ke_" + p] = ke * (0.9 if k == 0 else 0.1)
        cols["com_x_" + p] = np.zeros(n)
        cols["com_y_" + p] = np.zeros(n)
        cols["com_z_" + p] = 0.0127 + k * 0.01 - 1e-3 * (1 - np.exp(-t / 2e-5))
    ur.write_history(path, cols, columns)


def _self_test(verbose=True):
    test = ur.SelfTest("plot_history", verbose)
    check = test.check
    with tempfile.TemporaryDirectory(prefix="udar_history_test_") as tmp:
        csvp = os.path.join(tmp, "impact_history.csv")
        _write_synthetic(csvp)
        h = ur.read_history(csvp)
        check(len(h["time"]) == 400 and ur.history_parts(h) == ["rod", "anvil_plate"],
              "read synthetic history with 2 parts")
        out = os.path.join(tmp, "h.png")
        s = plot_history(csvp, out, error_limit=0.2, verbose=False)
        check(os.path.getsize(out) > 5000 and s["panels"] == 6, "full figure with 6 panels")
        check(abs(s["max_abs_energy_error"] - 1e-3) < 1e-5, "energy error summary")
        check(case_name(csvp) == "impact", "title from the file name")
        s4 = plot_history(csvp, out, verbose=False, whole=4.0)
        check(s4["kinetic_0"] == 4.0 * s["kinetic_0"] and "x 4" in s4["title"],
              "--whole 4: energies four times the model's, and the title says so")
        xx = np.arange(100001, dtype=float)
        yy = np.zeros_like(xx)
        yy[54321], yy[77] = 5.0, -3.0
        xd, yd = decimate(xx, yy)
        check(len(xd) <= 20010 and yd.max() == 5.0 and yd.min() == -3.0 and xd[-1] == 1e5,
              "decimation of long curves keeps spikes and end points")
        part = os.path.join(tmp, "partial_history.csv")
        _write_synthetic(part, columns=["time", "kinetic", "internal"])
        with warnings.catch_warnings(record=True) as w:
            warnings.simplefilter("always")
            s = plot_history(part, out, verbose=False)
        check(s["panels"] == 1 and any("missing column" in str(x.message) for x in w),
              "missing columns: remaining panels drawn, warning given")
        empty = os.path.join(tmp, "empty_history.csv")
        with open(empty, "w") as fh:
            fh.write("time,kinetic\n")
        test.raises(HistoryError, "header-only file rejected", plot_history, empty, out,
                    verbose=False, contains=("empty_history.csv", "no data rows"))
        rc, _, _ = test.run_main(main, [os.path.join(tmp, "nope.csv"), "-o", out])
        check(rc == 1, "missing file: exit code 1")
        # gauges: a node gauge and a point gauge whose element becomes a particle
        gp = os.path.join(tmp, "gauged_history.csv")
        t = np.linspace(0.0, 1e-5, 200)
        cols = {"time": t, "kinetic": np.ones_like(t)}
        for q in ("ux", "uy", "uz", "vx", "vy", "vz"):
            cols["gauge_rear_face_" + q] = (t * 10.0 if q == "uz" else 10.0 + 0 * t) if q[1] == "z" else 0 * t
        for q in ur.GAUGE_QUANTITIES[6:]:
            cols["gauge_nose_" + q] = 1e8 * np.sin(t / 1e-6) if q == "pressure" else 0 * t
        cols["gauge_nose_state"] = np.where(t > 5e-6, 3.0, 0.0)
        ur.write_history(gp, cols)
        check(ur.history_gauges(ur.read_history(gp)) == {"rear_face": ["ux", "uy", "uz", "vx", "vy", "vz"],
                                                         "nose": list(ur.GAUGE_QUANTITIES[6:])},
              "gauge names (with underscores) and quantities from the columns")
        g = plot_gauges(gp, out, verbose=False)
        check(g["quantities"] == ["vz", "uz", "pressure"] and g["marked"] == [("o", "became a particle")],
              "gauge figure: the quantities not 0 throughout, the particle marked")
        test.raises(HistoryError, "unknown gauge named", plot_gauges, gp, out, names=["tail"], verbose=False,
                    contains=("no gauge 'tail'", "rear_face"))
        rc, _, _ = test.run_main(main, [gp, "--gauges", "nose", "--quantities", "pressure,temperature", "-o", out])
        check(rc == 0 and os.path.getsize(out) > 5000, "--gauges nose --quantities pressure,temperature")
    return test.finish()


# --------------------------------------------------------------------------------------
# CLI
# --------------------------------------------------------------------------------------

def build_parser():
    p = ur.cli_parser(
        "plot_history.py",
        "Plot a udar history CSV: energies (kinetic, internal, plastic work, total), "
        "relative energy error, momentum components, rigid-wall force, kinetic "
        "energy and centre-of-mass displacement per part, against time in µs.",
        """examples:
  /usr/bin/python3 postproc/plot_history.py out/taylor_history.csv -o taylor_history.png
  /usr/bin/python3 postproc/plot_history.py out/taylor_history.csv --error-limit 0.2 -o h.pdf
  /usr/bin/python3 postproc/plot_history.py out/elastic_bar_history.csv --gauges -o gauges.png
  /usr/bin/python3 postproc/plot_history.py --self-test

The energy_error column is taken as relative (dimensionless) and drawn in percent.""")
    p.add_argument("history", nargs="?", metavar="HISTORY.csv", help="udar history CSV file")
    p.add_argument("-o", "--output", metavar="OUT.png",
                   help="output image (png/pdf/svg by extension); default <case>_history.png")
    p.add_argument("--title", help="figure title (default: case name from the file name)")
    p.add_argument("--error-limit", type=float, metavar="FRAC",
                   help="draw +-FRAC lines on the energy error panel (e.g. 0.2, the run's limit)")
    p.add_argument("--gauges", nargs="*", metavar="NAME",
                   help="draw the gauges' histories instead (&gauge; the named ones, default all): a panel "
                        "per quantity, a curve per gauge, marked where its element eroded or became a particle")
    p.add_argument("--quantities", metavar="Q,Q",
                   help="with --gauges: the quantities to draw, e.g. vz,pressure,szz (default: velocities, "
                        "displacements, pressure, von Mises stress, plastic strain, temperature, those not 0)")
    p.add_argument("--whole", type=float, metavar="F",
                   help="multiply the energies, masses and forces by F: the whole body of a model cut "
                        "by symmetry planes (4 for a quarter model; the history's note gives the factor; "
                        "momenta stay the model's)")
    ur.add_figure_arguments(p)
    return ur.add_self_test(p)


def main(argv=None):
    return ur.cli_main(build_parser(), argv, _self_test, _run, errors=(HistoryError,),
                       require=("history", "the HISTORY.csv argument is required (or --self-test)"))


def _run(args, p):
    out = args.output or os.path.splitext(os.path.basename(args.history))[0] + ".png"
    if os.path.abspath(out) == os.path.abspath(args.history):
        p.error("the output file would overwrite the input")
    if args.gauges is not None:
        plot_gauges(args.history, out, names=args.gauges, title=args.title,
                    quantities=args.quantities.split(",") if args.quantities else None,
                    size=tuple(args.size) if args.size else None, dpi=args.dpi)
        return
    if args.quantities:
        p.error("--quantities goes with --gauges")
    plot_history(args.history, out, title=args.title, error_limit=args.error_limit,
                 size=tuple(args.size) if args.size else None, dpi=args.dpi, whole=args.whole)


if __name__ == "__main__":
    sys.exit(main())
