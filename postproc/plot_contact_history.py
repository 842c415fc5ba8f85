#!/usr/bin/python3
"""Plot the contact side of a udar history CSV (<case>_history.csv): contact normal and
friction force per interface, centre-of-mass velocity and kinetic energy per part, against
time in µs; print the contact numbers (duration, impulses, friction/normal impulse ratio,
velocities after the contact, final energy error).

    /usr/bin/python3 postproc/plot_contact_history.py out/blocks_head_on_history.csv -o h.png
    /usr/bin/python3 postproc/plot_contact_history.py --self-test

Columns used: time, dt, energy_error, ke_<part>, com_{x,y,z}_<part>,
contact_normal_<interface>, contact_friction_<interface>. Library use:
``contact_summary(hist)``, ``plot_contact_history(path, out, ...)``.
"""

import os
import sys
import tempfile

if __package__:
    from . import udar_results as ur
else:
    import udar_results as ur  # run as a script, it stops with a message if numpy is missing
import numpy as np


class HistoryError(Exception):
    """Bad history file or request; the message names the file and the problem."""


def interfaces(hist):
    """Contact interface names from the ``contact_normal_<name>`` columns (file order)."""
    p = "contact_normal_"
    return [k[len(p):] for k in hist if k.startswith(p) and len(k) > len(p)]


def com_velocity(hist, part, axis):
    """Centre-of-mass velocity of ``part`` along ``axis`` ('x', 'y', 'z'), d(com)/dt."""
    t, x = hist["time"], hist["com_%s_%s" % (axis, part)]
    return np.gradient(x, t) if len(t) > 1 else np.zeros_like(x)


def contact_summary(hist):
    """{interface: {...}} with first/last time the normal force is positive, duration,
    normal and friction impulses (sum of force * dt) and their ratio; plus 'parts':
    {part: {axis: velocity after the last contact}} (straight-line fit of the centre of mass
    over the rows after it, None when fewer than 3) and 'energy_error' (last row)."""
    t, dt = hist["time"], hist["dt"]
    out, last_contact = {}, None
    for name in interfaces(hist):
        fn = hist["contact_normal_" + name]
        ft = hist.get("contact_friction_" + name, np.zeros_like(fn))
        on = np.nonzero(fn > 0.0)[0]
        s = {"cycles": int(on.size), "impulse_normal": float((fn * dt).sum()),
             "impulse_friction": float((ft * dt).sum()),
             "max_normal": float(fn.max()) if fn.size else 0.0}
        s["impulse_ratio"] = (s["impulse_friction"] / s["impulse_normal"]
                              if s["impulse_normal"] != 0.0 else float("nan"))
        if on.size:
            s["t_first"], s["t_last"] = float(t[on[0]]), float(t[on[-1]])
            s["duration"] = s["t_last"] - s["t_first"]
            last_contact = on[-1] if last_contact is None else max(last_contact, on[-1])
        out[name] = s
    parts = {}
    after = slice(last_contact + 1, None) if last_contact is not None else slice(0, None)
    for p in ur.history_parts(hist):
        parts[p] = {}
        for a in "xyz":
            c = "com_%s_%s" % (a, p)
            if c in hist:
                ta, xa = t[after], hist[c][after]
                parts[p][a] = float(np.polyfit(ta, xa, 1)[0]) if ta.size > 2 else None
    out_all = {"interfaces": out, "parts": parts}
    if "energy_error" in hist and len(t):
        out_all["energy_error"] = float(hist["energy_error"][-1])
    return out_all


def plot_contact_history(path, out, title=None, size=None, dpi=150, verbose=True):
    """Read the history CSV ``path``, write the figure ``out``; returns contact_summary."""
    plt = ur.agg_pyplot()
    h = ur.read_history(path)
    for c in ("time", "dt"):
        if c not in h:
            raise HistoryError("%s: no '%s' column" % (path, c))
    if len(h["time"]) < 2:
        raise HistoryError("%s: fewer than 2 data rows" % path)
    names, parts = interfaces(h), ur.history_parts(h)
    if not names:
        raise HistoryError("%s: no contact_normal_<interface> column (no &contact?)" % path)
    tus = h["time"] * 1e6
    fig, ax = plt.subplots(3, 1, sharex=True, figsize=size or (8, 9), constrained_layout=True)
    # contact forces
    forces = np.concatenate([h["contact_normal_" + n] for n in names]
                            + [h["contact_friction_" + n] for n in names
                               if "contact_friction_" + n in h])
    k, unit = ur.si_scale(forces, "N")
    for n in names:
        ax[0].plot(tus, h["contact_normal_" + n] * k, label="normal, " + n)
        if "contact_friction_" + n in h and np.any(h["contact_friction_" + n] != 0.0):
            ax[0].plot(tus, h["contact_friction_" + n] * k, label="friction, " + n)
    ax[0].set_ylabel("contact force (%s)" % unit)
    ax[0].set_title("contact forces")
    # centre-of-mass velocity: components that move
    vel = {(p, a): com_velocity(h, p, a) for p in parts for a in "xyz"
           if "com_%s_%s" % (a, p) in h}
    vmax = max([np.abs(v).max() for v in vel.values()] + [0.0])
    styles = {"x": "--", "y": ":", "z": "-"}
    for i, p in enumerate(parts):
        for a in "xyz":
            v = vel.get((p, a))
            if v is not None and np.abs(v).max() > 1e-2 * vmax:
                ax[1].plot(tus, v, styles[a], color="C%d" % i, label="%s %s" % (p, a))
    ax[1].set_ylabel("velocity (m/s)")
    ax[1].set_title("centre-of-mass velocity per part")
    # kinetic energy per part
    for i, p in enumerate(parts):
        ax[2].plot(tus, h["ke_" + p], color="C%d" % i, label=p)
    ax[2].set_ylabel("kinetic energy (J)")
    ax[2].set_title("kinetic energy per part")
    ax[2].set_xlabel("time (µs)")
    for a in ax:
        a.grid(True, alpha=0.3)
        if a.get_legend_handles_labels()[0]:
            a.legend(fontsize="small")
    case = os.path.basename(path).replace("_history.csv", "")
    fig.suptitle(title or case + " — contact history")
    ur.save_figure(fig, out, dpi, error=HistoryError)
    s = contact_summary(h)
    if verbose:
        print(format_summary(path, s))
        print("wrote %s" % out)
    return s


def format_summary(path, s):
    lines = ["%s:" % path]
    for n, c in s["interfaces"].items():
        if "duration" in c:
            lines.append("  %s: contact from %.4f to %.4f us (%.4f us, %d rows), max normal "
                         "force %.5g N" % (n, c["t_first"] * 1e6, c["t_last"] * 1e6,
                                           c["duration"] * 1e6, c["cycles"], c["max_normal"]))
        else:
            lines.append("  %s: never in contact" % n)
        lines.append("  %s: impulse normal %.6g N s, friction %.6g N s, friction/normal %.5f"
                     % (n, c["impulse_normal"], c["impulse_friction"], c["impulse_ratio"]))
    for p, v in s["parts"].items():
        lines.append("  %s: centre-of-mass velocity after the contact (fit) %s m/s" % (
            p, ", ".join("%s %s" % (a, "n/a" if x is None else "%.4f" % x) for a, x in v.items())))
    if "energy_error" in s:
        lines.append("  energy error (last row) %.4g %%" % (100 * s["energy_error"]))
    return "\n".join(lines)


def _self_test(verbose=True):
    test = ur.SelfTest("plot_contact_history", verbose)
    check = test.check
    # two blocks: contact for 2 us with 1 kN normal, 0.1 kN friction; the striker's centre
    # of mass moves at 10 m/s then stops, the target's starts at 10 m/s
    t = np.linspace(0.0, 10e-6, 1001)
    dt = np.full_like(t, t[1] - t[0])
    on = (t >= 2e-6) & (t < 4e-6)
    fn, ft = np.where(on, 1e3, 0.0), np.where(on, 1e2, 0.0)
    vs = np.where(t < 2e-6, 10.0, np.where(t < 4e-6, 10.0 * (4e-6 - t) / 2e-6, 0.0))
    vt = 10.0 - vs
    zs = np.concatenate([[0.0], np.cumsum(0.5 * (vs[1:] + vs[:-1]) * np.diff(t))])
    zt = np.concatenate([[0.0], np.cumsum(0.5 * (vt[1:] + vt[:-1]) * np.diff(t))]) + 0.02
    zero = np.zeros_like(t)
    cols = {"time": t, "cycle": np.arange(t.size, dtype=float), "dt": dt,
            "energy_error": np.full_like(t, -1e-3),
            "ke_a": 0.5 * vs ** 2, "com_x_a": zero, "com_y_a": zero, "com_z_a": zs,
            "ke_b": 0.5 * vt ** 2, "com_x_b": zero, "com_y_b": zero, "com_z_b": zt,
            "contact_normal_a_on_b": fn, "contact_friction_a_on_b": ft}
    with tempfile.TemporaryDirectory(prefix="udar_contact_test_") as tmp:
        csvp = os.path.join(tmp, "two_history.csv")
        ur.write_history(csvp, cols)
        h = ur.read_history(csvp)
        check(interfaces(h) == ["a_on_b"], "interface name from contact_normal_ column")
        out = os.path.join(tmp, "c.png")
        s = plot_contact_history(csvp, out, verbose=False)
        check(os.path.getsize(out) > 5000, "figure written")
        c = s["interfaces"]["a_on_b"]
        check(abs(c["duration"] - 1.99e-6) < 1e-9, "contact duration %.4g s" % c["duration"])
        check(abs(c["impulse_ratio"] - 0.1) < 1e-12, "friction/normal impulse ratio 0.1")
        check(abs(c["impulse_normal"] - 2e-3) < 1e-8, "normal impulse 2e-3 N s")
        check(abs(s["parts"]["a"]["z"]) < 1e-6 and abs(s["parts"]["b"]["z"] - 10.0) < 1e-6,
              "velocities after the contact 0 and 10 m/s")
        check(abs(com_velocity(h, "b", "z")[-1] - 10.0) < 1e-6, "com velocity by gradient")
        check(abs(s["energy_error"] + 1e-3) < 1e-12, "last energy error")
    return test.finish()


def build_parser():
    p = ur.cli_parser(
        "plot_contact_history.py",
        "Plot the contact side of a udar history CSV: contact normal and friction force per "
        "interface, centre-of-mass velocity and kinetic energy per part, against time in µs; "
        "print contact duration, impulses and their ratio, velocities after the contact and "
        "the final energy error.",
        """examples:
  /usr/bin/python3 postproc/plot_contact_history.py out/blocks_head_on_history.csv -o h.png
  /usr/bin/python3 postproc/plot_contact_history.py --self-test

The contact duration is the time between the first and the last row with a positive
normal force; impulses are the sums of force * dt over the rows (dt_history = 0 gives
one row per cycle, which makes them exact sums over the cycles).""")
    p.add_argument("history", nargs="?", metavar="HISTORY.csv", help="udar history CSV file")
    p.add_argument("-o", "--output", metavar="OUT.png",
                   help="output image (png/pdf/svg by extension); default "
                        "<case>_contact_history.png")
    p.add_argument("--title", help="figure title (default: case name from the file name)")
    ur.add_figure_arguments(p)
    return ur.add_self_test(p)


def main(argv=None):
    return ur.cli_main(build_parser(), argv, _self_test, _run, errors=(HistoryError,),
                       require=("history", "the HISTORY.csv argument is required (or --self-test)"))


def _run(args, p):
    stem = os.path.splitext(os.path.basename(args.history))[0]
    out = args.output or stem.replace("_history", "") + "_contact_history.png"
    if os.path.abspath(out) == os.path.abspath(args.history):
        p.error("the output file would overwrite the input")
    plot_contact_history(args.history, out, title=args.title,
                         size=tuple(args.size) if args.size else None, dpi=args.dpi)


if __name__ == "__main__":
    sys.exit(main())
