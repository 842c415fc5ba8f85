#!/usr/bin/python3
"""Plate-impact shock measurements from a udar field file: the Lagrangian shock speed and
the plateau pressure behind the shock, against the Hugoniot of the deck's material.

The body strikes a rigid wall (the symmetry plane of a symmetric impact at twice its speed)
at the plane ``coordinate[--axis] = --wall``; each element's Lagrangian position is its
initial centroid's distance from the body's impact face. At every output step:

* plateau pressure = mean element pressure between ``--margin`` from the impact face and
  ``--margin`` behind a first estimate of the front (the last element at half the peak);
* front = where the pressure falls to half the plateau (linear interpolation between the
  last element at or above it and the next one, in Lagrangian order);

steps before the front has run 2 margins, or after it is within a margin of the far end
(the reflection), are left out. Shock speed = least-squares slope of front against time;
the plateau pressure compared is the last step's.

Hugoniot for the particle velocity u_p (the body's speed towards the wall from the deck,
or ``--impact-speed V`` / 2 for a symmetric impact at closing speed V):

* ``eos = 'mie_gruneisen'``: U_s = c0 + s u_p, p = rho0 U_s u_p;
* ``eos = 'linear'`` (p = K (rho/rho0 - 1)): with ``strength = 'elastic'`` the elastic
  (acoustic, u_p << c) wave U = sqrt((K + 4G/3)/rho0), p = K u_p / U; otherwise the jump
  conditions of that EOS, U = u_p/2 + sqrt(u_p^2/4 + K/rho0), p = rho0 U u_p.

Strength is not in the hydrodynamic Hugoniots (a warning says so when the part has one).

    /usr/bin/python3 postproc/shock.py out/plate_impact.h5
    /usr/bin/python3 postproc/shock.py out/plate_impact.h5 --axis z --wall 0 --margin 2e-3 --json
    /usr/bin/python3 postproc/shock.py --self-test

Library use: ``measure_file(path, ...)`` -> dict (SI units), ``hugoniot(material, up)``.
"""

import json
import math
import os
import sys
import tempfile
import warnings

if __package__:
    from . import udar_results as ur
else:
    import udar_results as ur  # run as a script, it stops with a message if numpy is missing
import numpy as np

AXES = "xyz"


class ShockError(Exception):
    """Bad measurement request or a file it cannot measure; the message says why."""


# --------------------------------------------------------------------------------------
# the deck's material and its Hugoniot
# --------------------------------------------------------------------------------------

def deck_part_material(deck, part=None):
    """(part index 1-based, &part values, &material values) of the part named ``part`` (or
    the only part) in a deck text."""
    groups = [(g, ur.deck_values(body)) for g, body in ur.deck_groups(deck or "")]
    parts = [v for g, v in groups if g == "part"]
    if not parts:
        raise ShockError("the deck has no &part group")
    if part is None:
        if len(parts) > 1:
            raise ShockError("the deck has %d parts (%s): choose one with --part"
                             % (len(parts), ", ".join(str(p.get("group")) for p in parts)))
        k = 0
    else:
        names = [str(p.get("group", "")).lower() for p in parts]
        if part.lower() not in names:
            raise ShockError("no part '%s' in the deck (parts: %s)" % (part, ", ".join(names)))
        k = names.index(part.lower())
    mat_name = str(parts[k].get("material", "")).lower()
    mats = [v for g, v in groups if g == "material" and str(v.get("name", "")).lower() == mat_name]
    if not mats:
        raise ShockError("no &material '%s' (of part '%s') in the deck"
                         % (mat_name, parts[k].get("group")))
    return k + 1, parts[k], mats[0]


def _positive(mat, key):
    v = mat.get(key)
    return float(v) if isinstance(v, float) and v > 0.0 else None


def hugoniot(mat, up):
    """{'shock_speed_m_s', 'pressure_pa', 'model'} of the material values ``mat`` (from
    ``deck_values``) for the particle velocity ``up`` (m/s); see the module text."""
    rho0 = _positive(mat, "rho0")
    if rho0 is None:
        raise ShockError("material '%s': no rho0" % mat.get("name"))
    eos = str(mat.get("eos", "linear")).lower()
    strength = str(mat.get("strength", "elastic")).lower()
    if eos == "mie_gruneisen":
        c0, s = _positive(mat, "c0"), float(mat.get("s", 0.0))
        if c0 is None:
            raise ShockError("material '%s': Mie-Grueneisen without c0" % mat.get("name"))
        us = c0 + s * up
        return {"shock_speed_m_s": us, "pressure_pa": rho0 * us * up,
                "model": "mie_gruneisen: rho0 %g kg/m3, c0 %g m/s, s %g; U_s = c0 + s u_p, "
                         "p = rho0 U_s u_p" % (rho0, c0, s)}
    if eos != "linear":
        raise ShockError("material '%s': unknown eos '%s'" % (mat.get("name"), eos))
    E, nu = _positive(mat, "youngs_modulus"), mat.get("poisson_ratio")
    from_e = E is not None and isinstance(nu, float) and -1.0 < nu < 0.5
    k = _positive(mat, "bulk_modulus") or (E / (3.0 * (1.0 - 2.0 * nu)) if from_e else None)
    if k is None:
        raise ShockError("material '%s': linear EOS without bulk_modulus (or E and nu)"
                         % mat.get("name"))
    if strength == "elastic":
        g = _positive(mat, "shear_modulus") or (E / (2.0 * (1.0 + nu)) if from_e else None)
        if g is None:
            raise ShockError("material '%s': elastic without shear_modulus (or E and nu)"
                             % mat.get("name"))
        c = math.sqrt((k + 4.0 * g / 3.0) / rho0)
        return {"shock_speed_m_s": c, "pressure_pa": k * up / c,
                "model": "linear EOS, elastic: rho0 %g kg/m3, K %g Pa, G %g Pa; acoustic "
                         "U = sqrt((K + 4G/3)/rho0), p = K u_p / U" % (rho0, k, g)}
    # p = K mu with mu = u/(U - u) (mass) and p = rho0 U u (momentum): U (U - u) = K/rho0
    us = 0.5 * up + math.sqrt(0.25 * up * up + k / rho0)
    return {"shock_speed_m_s": us, "pressure_pa": rho0 * us * up,
            "model": "linear EOS: rho0 %g kg/m3, K %g Pa; U = u_p/2 + sqrt(u_p^2/4 + K/rho0), "
                     "p = rho0 U u_p" % (rho0, k)}


# --------------------------------------------------------------------------------------
# measurement
# --------------------------------------------------------------------------------------

def front_and_plateau(d, p, margin):
    """(front position, plateau pressure) of one step from element positions ``d`` (sorted,
    increasing from the impact face) and pressures ``p``; None when the front has not run
    two margins yet or is within a margin of the far end."""
    rough = d[np.nonzero(p >= 0.5 * p.max())[0][-1]]
    band = (d > d[0] + margin) & (d < rough - margin)
    if not band.any() or rough > d[-1] - margin:
        return None
    plateau = p[band].mean()
    k = np.nonzero(p >= 0.5 * plateau)[0][-1]
    if k + 1 == len(d):
        return None
    front = d[k] + (d[k + 1] - d[k]) * (p[k] - 0.5 * plateau) / (p[k] - p[k + 1])
    return float(front), float(plateau)


def measure_file(path, axis=2, wall=0.0, part=None, margin=2e-3, impact_speed=None, deck=None):
    """Measure a field file -> dict (SI): steps [{time_s, front_m, plateau_pa}], skipped
    (times left out), shock_speed_m_s, pressure_pa (last step's plateau), particle_velocity_m_s,
    hugoniot (see ``hugoniot``), material, part, and the relative differences."""
    if not margin > 0.0:
        raise ShockError("--margin must be > 0")
    with ur.open_fields(path) as f:
        text = deck if deck is not None else f.deck
        pid, pvals, mat = deck_part_material(text, part)
        elems = np.nonzero(f.part_id == pid)[0] if part is not None else np.arange(f.n_elems)
        if elems.size == 0:
            raise ShockError("%s: part %d has no elements" % (path, pid))
        conn = f.connectivity[elems]
        nodes_h, _ = ur.wall_heights(f.x0[np.unique(conn)], axis, wall)
        h, _ = ur.wall_heights(f.x0[conn].mean(axis=1), axis, wall)
        order = np.argsort(h, kind="stable")
        d = h[order] - nodes_h.min()            # Lagrangian distance from the impact face
        steps, skipped = [], []
        for info in f.steps:
            if info.time <= 0.0:
                continue
            p = f.step(info.index).fields["pressure"][elems][order]
            r = front_and_plateau(d, p, margin)
            if r is None:
                skipped.append(info.time)
            else:
                steps.append({"time_s": info.time, "front_m": r[0], "plateau_pa": r[1]})
    if len(steps) < 2:
        raise ShockError("%s: %d step(s) with a measurable front (need 2; steps left out at "
                         "t = %s us)" % (path, len(steps), ", ".join("%.3g" % (t * 1e6) for t in skipped)))
    if impact_speed is not None:
        up, up_from = 0.5 * impact_speed, "symmetric impact at %g m/s" % impact_speed
    else:
        v = pvals.get("velocity", 0.0)
        up = abs(float(v[axis] if isinstance(v, list) else v))
        up_from = "part '%s' at %g m/s onto the wall" % (pvals.get("group"), up)
    if not up > 0.0:
        raise ShockError("part '%s' does not move along %s in the deck: give --impact-speed"
                         % (pvals.get("group"), AXES[axis]))
    if str(mat.get("strength", "elastic")).lower() not in ("none", "elastic"):
        warnings.warn("material '%s' has strength '%s': the Hugoniot compared is "
                      "hydrodynamic (no strength)" % (mat.get("name"), mat.get("strength")))
    hug = hugoniot(mat, up)
    t = np.array([s["time_s"] for s in steps])
    us = float(np.polyfit(t, [s["front_m"] for s in steps], 1)[0])
    pm = steps[-1]["plateau_pa"]
    return {"steps": steps, "skipped_s": skipped, "shock_speed_m_s": us, "pressure_pa": pm,
            "particle_velocity_m_s": up, "particle_velocity_from": up_from,
            "material": mat.get("name"), "part": pvals.get("group"), "hugoniot": hug,
            "shock_speed_difference": us / hug["shock_speed_m_s"] - 1.0,
            "pressure_difference": pm / hug["pressure_pa"] - 1.0}


def report_lines(m):
    """Per-step lines, the machine-readable line and the measured-vs-Hugoniot lines."""
    h = m["hugoniot"]
    lines = ["t = %.2f us: plateau %.3f GPa, front at %.3f mm"
             % (s["time_s"] * 1e6, s["plateau_pa"] / 1e9, s["front_m"] * 1e3) for s in m["steps"]]
    lines.append("shock_speed_m_s=%.9g hugoniot_shock_speed_m_s=%.9g pressure_pa=%.9g "
                 "hugoniot_pressure_pa=%.9g particle_velocity_m_s=%.9g" % (
                     m["shock_speed_m_s"], h["shock_speed_m_s"], m["pressure_pa"],
                     h["pressure_pa"], m["particle_velocity_m_s"]))
    lines.append("material '%s' (%s), u_p = %g m/s (%s)" % (
        m["material"], h["model"], m["particle_velocity_m_s"], m["particle_velocity_from"]))
    lines.append("shock speed: measured %.1f m/s, Hugoniot %.1f m/s, difference %+.2f %% "
                 "(fit over %.2f-%.2f us, %d steps)" % (
                     m["shock_speed_m_s"], h["shock_speed_m_s"], 100 * m["shock_speed_difference"],
                     m["steps"][0]["time_s"] * 1e6, m["steps"][-1]["time_s"] * 1e6, len(m["steps"])))
    lines.append("plateau pressure: measured %.3f GPa, Hugoniot %.3f GPa, difference %+.2f %% "
                 "(at %.2f us)" % (m["pressure_pa"] / 1e9, h["pressure_pa"] / 1e9,
                                   100 * m["pressure_difference"], m["steps"][-1]["time_s"] * 1e6))
    return lines


# --------------------------------------------------------------------------------------
# self-test
# --------------------------------------------------------------------------------------

MG_DECK = """&material name = 'Cu', rho0 = 8930.0, eos = 'mie_gruneisen', c0 = 3940.0, s = 1.489,
  strength = 'none' /
&part group = 'column', material = 'cu', velocity = 0.0, 0.0, -500.0 /
"""


def _self_test(verbose=True):
    """A synthetic shock with known speed and plateau in a column; Hugoniots by hand."""
    test = ur.SelfTest("shock", verbose)
    check = test.check

    def close(a, b, tol=1e-9):
        return abs(a - b) <= tol * abs(b)

    # Hugoniots against hand-computed values
    h = hugoniot(ur.deck_values("rho0 = 8930.0, eos = 'mie_gruneisen', c0 = 3940.0, s = 1.489"), 500.0)
    check(close(h["shock_speed_m_s"], 4684.5) and close(h["pressure_pa"], 8930.0 * 4684.5 * 500.0),
          "Mie-Grueneisen copper at 500 m/s: U_s 4684.5 m/s, p 20.916 GPa")
    # linear EOS, no strength: K/rho0 = 16e6 (m/s)^2, u = 600: U = 300 + sqrt(90000 + 16e6)
    h = hugoniot({"rho0": 8000.0, "eos": "linear", "bulk_modulus": 128e9, "strength": "none"}, 600.0)
    u_exact = 300.0 + math.sqrt(16.09e6)
    check(close(h["shock_speed_m_s"], u_exact) and close(h["pressure_pa"], 8000.0 * u_exact * 600.0)
          and close(128e9 * (u_exact / (u_exact - 600.0) - 1.0), h["pressure_pa"]),
          "linear EOS, no strength: jump conditions of p = K (rho/rho0 - 1)")
    # elastic from E and nu: E 200 GPa, nu 0.25 -> K 133.3 GPa, G 80 GPa, K + 4G/3 = 240 GPa
    h = hugoniot({"rho0": 7500.0, "youngs_modulus": 200e9, "poisson_ratio": 0.25}, 10.0)
    check(close(h["shock_speed_m_s"], math.sqrt(240e9 / 7500.0))
          and close(h["pressure_pa"], 200e9 / 1.5 * 10.0 / math.sqrt(32e6)),
          "linear EOS, elastic (default strength), K and G from E and nu: acoustic values")

    # a column 1 x 1 x 20 mm (0.1 mm cells) on the wall z = 0; a shock 1 % faster and a
    # plateau 2 % lower than the Hugoniot; the face's first 0.5 mm carries 30 % more
    # (wall heating), which the margin must keep out of the plateau
    nodes, conn = ur.box_tets(1, 1, 200, hi=(1e-3, 1e-3, 20e-3))
    zc = nodes[conn, 2].mean(axis=1)
    us_true, p_true = 1.01 * 4684.5, 0.98 * 8930.0 * 4684.5 * 500.0
    times = [0.0, 0.8e-6, 1.6e-6, 2.4e-6, 3.2e-6, 4.0e-6]

    def pressure(t):
        ramp = np.clip((us_true * t + 0.2e-3 - zc) / 0.4e-3, 0.0, 1.0)   # half at the front
        return p_true * ramp * np.where(zc < 0.5e-3, 1.3, 1.0)

    with tempfile.TemporaryDirectory(prefix="udar_shock_test_") as tmp:
        h5 = os.path.join(tmp, "column.h5")
        ur.write_fields(h5, nodes, conn, [{"time": t, "cycle": k, "coordinates": nodes,
                                           "fields": {"pressure": pressure(t)}}
                                          for k, t in enumerate(times)], deck=MG_DECK)
        m = measure_file(h5)
        check(close(m["shock_speed_m_s"], us_true) and close(m["pressure_pa"], p_true)
              and close(m["shock_speed_difference"], 0.01, 1e-6)
              and close(m["pressure_difference"], -0.02, 1e-6),
              "synthetic shock: U %.3f m/s (expected %.3f), plateau %.6g Pa (expected %.6g)"
              % (m["shock_speed_m_s"], us_true, m["pressure_pa"], p_true))
        check([s["time_s"] for s in m["steps"]] == times[2:5] and m["skipped_s"] == [0.8e-6, 4.0e-6]
              and all(close(s["front_m"], us_true * s["time_s"]) for s in m["steps"]),
              "fronts at U t; 0.8 us (front within 2 margins) and 4.0 us (at the far end) left out")
        rc, out, err = test.run_main(main, [h5])
        check(rc == 0 and err == "" and "difference +1.00 %" in out and "difference -2.00 %" in out
              and "shock_speed_m_s=4731.345 hugoniot_shock_speed_m_s=4684.5 " in out,
              "CLI: machine line and measured-vs-Hugoniot lines")
        rc, out, _ = test.run_main(main, [h5, "--impact-speed", "1200", "--json"])
        js = json.loads(out) if rc == 0 else {}
        check(rc == 0 and close(js["particle_velocity_m_s"], 600.0)
              and close(js["hugoniot"]["shock_speed_m_s"], 3940.0 + 1.489 * 600.0),
              "--impact-speed 1200: symmetric impact, u_p = 600 m/s (JSON)")
        # the same column below a wall at x = 0.05 m, moving along +x
        xs = np.column_stack([0.05 - nodes[:, 2], nodes[:, 0], nodes[:, 1]])
        h5x = os.path.join(tmp, "column_x.h5")
        ur.write_fields(h5x, xs, conn, [{"time": t, "cycle": k, "coordinates": xs,
                                         "fields": {"pressure": pressure(t)}}
                                        for k, t in enumerate(times)], deck=MG_DECK)
        test.raises(ShockError, "no velocity along x in the deck: error asking for --impact-speed",
                    measure_file, h5x, axis=0, wall=0.05, contains="--impact-speed")
        mx = measure_file(h5x, axis=0, wall=0.05, deck=MG_DECK.replace("0.0, 0.0, -500.0", "500.0, 0, 0"))
        check(close(mx["shock_speed_m_s"], us_true) and close(mx["pressure_pa"], p_true)
              and close(mx["shock_speed_difference"], 0.01, 1e-6),
              "column along -x below the wall x = 0.05 m, deck given apart: same answers")
        two = MG_DECK + "&part group = 'plate', material = 'cu' /\n"
        ur.write_fields(h5x, nodes, conn, [{"time": 0.0, "cycle": 0, "coordinates": nodes,
                                            "fields": {"pressure": pressure(0.0)}}], deck=two)
        rc, _, err = test.run_main(main, [h5x])
        check(rc == 1 and "2 parts" in err and "--part" in err, "two parts without --part: error")
        rc, _, err = test.run_main(main, [h5x, "--part", "column"])
        check(rc == 1 and "0 step(s)" in err, "no measurable step: error")
        rc, _, err = test.run_main(main, [os.path.join(tmp, "missing.h5")])
        check(rc == 1 and "missing.h5: no such file" in err, "missing file: exit code 1")
    return test.finish()


# --------------------------------------------------------------------------------------
# CLI
# --------------------------------------------------------------------------------------

def build_parser():
    p = ur.cli_parser(
        "shock.py",
        "Measure the shock of a plate impact in a udar field file (<case>.h5): Lagrangian "
        "shock speed and plateau pressure, against the Hugoniot of the deck's material "
        "(the resolved deck stored in the file, or --deck). Prints one line per step, a "
        "machine-readable line 'shock_speed_m_s=... hugoniot_shock_speed_m_s=... "
        "pressure_pa=... hugoniot_pressure_pa=... particle_velocity_m_s=...' and the "
        "measured and Hugoniot values with their relative differences.",
        """examples:
  /usr/bin/python3 postproc/shock.py out/plate_impact.h5
  /usr/bin/python3 postproc/shock.py out/plate_impact.h5 --axis z --wall 0 --margin 2e-3
  /usr/bin/python3 postproc/shock.py out/plate.h5 --part flyer --impact-speed 1000 --json
  /usr/bin/python3 postproc/shock.py --self-test

Lengths in metres, speeds in m/s. u_p is the part's deck velocity along --axis (a body on a
rigid wall), or half of --impact-speed (a symmetric impact at that closing speed).""")
    ur.add_fields_argument(p)
    p.add_argument("--axis", default="z", choices=("x", "y", "z"), help="impact axis (default z)")
    p.add_argument("--wall", type=float, default=0.0, metavar="POS",
                   help="position of the wall (impact plane) along the axis, m (default 0)")
    p.add_argument("--part", metavar="NAME", help="the part to measure (default: the only one)")
    p.add_argument("--margin", type=float, default=2e-3, metavar="DIST",
                   help="plateau: elements more than DIST m from the impact face and from "
                        "the front (default 0.002)")
    p.add_argument("--impact-speed", type=float, metavar="V",
                   help="closing speed of a symmetric impact, m/s: u_p = V/2")
    p.add_argument("--deck", metavar="FILE",
                   help="take the material from this deck instead of the one in the file")
    p.add_argument("--json", action="store_true", help="print the result as JSON")
    return ur.add_self_test(p, "run the built-in checks on a synthetic shock, print PASS/FAIL")


def main(argv=None):
    return ur.cli_main(build_parser(), argv, _self_test, _run, errors=(ShockError, KeyError),
                       require=ur.FIELDS_REQUIRED)


def _run(args, p):
    deck = None
    if args.deck:
        try:
            with open(args.deck) as fh:
                deck = fh.read()
        except OSError as e:
            raise ShockError("%s: %s" % (args.deck, e.strerror)) from None
    m = measure_file(args.fields, AXES.index(args.axis), args.wall, args.part, args.margin,
                     args.impact_speed, deck)
    print(json.dumps(m, indent=2) if args.json else "\n".join(report_lines(m)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
