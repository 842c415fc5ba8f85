"""Shared helpers of the regression checks: compare a measured number with
its reference and print one PASS/FAIL line; the exit status is the verdict."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..', 'postproc'))

_failed = []


def compare(name, measured, reference, rel_tol, unit=''):
    """PASS when |measured/reference - 1| <= rel_tol."""
    err = measured / reference - 1.0
    ok = abs(err) <= rel_tol
    print(f"{'PASS' if ok else 'FAIL'} {name}: {measured:.6g} {unit} vs {reference:.6g} {unit} "
          f"({100 * err:+.2f}%, tolerance {100 * rel_tol:.1f}%)")
    if not ok:
        _failed.append(name)
    return ok


def below(name, measured, limit, unit=''):
    """PASS when |measured| <= limit."""
    ok = abs(measured) <= limit
    print(f"{'PASS' if ok else 'FAIL'} {name}: |{measured:.4g}| {unit} <= {limit:.4g} {unit}")
    if not ok:
        _failed.append(name)
    return ok


def above(name, measured, limit, unit=''):
    """PASS when measured >= limit."""
    ok = measured >= limit
    print(f"{'PASS' if ok else 'FAIL'} {name}: {measured:.4g} {unit} >= {limit:.4g} {unit}")
    if not ok:
        _failed.append(name)
    return ok


def initial_overlaps(run_dir, interface):
    """How many slave nodes of a contact interface the run's log (run.log,
    written by run_tests.sh) reports as starting behind the master surface."""
    prefix = f'contact {interface}: '
    with open(os.path.join(run_dir, 'run.log')) as f:
        for line in f:
            if not line.startswith(prefix):
                continue
            rest = line[len(prefix):]
            if rest.startswith('no initial overlap'):
                return 0
            if 'start behind the master surface' in rest:
                return int(rest.split()[0])
    raise ValueError(f'{run_dir}/run.log has no initial-overlap line for {interface}')


def unconverged_passes(run_dir, interface):
    """How many contact passes of an interface ended at &contact iterations
    unconverged, from the run's log (run.log, written by run_tests.sh)."""
    prefix = f'contact {interface}: velocity matching '
    with open(os.path.join(run_dir, 'run.log')) as f:
        for line in f:
            line = line.strip()
            if line.startswith(prefix) and 'unconverged' in line:
                return int(line.split(';')[1].split()[0])
    raise ValueError(f'{run_dir}/run.log has no velocity-matching line for {interface}')


def wilkins_guinan(path, axis, radius_name, radius_reference):
    """The Wilkins-Guinan bar's checks on field file ``path`` (rod axis ``axis``): the
    final length within 0.5 % of the converged reference range 21.42-21.48 mm, the final
    footprint radius within 1 % of ``radius_reference`` (check ``radius_name``), and the
    output consistent: with the deck's linear EOS (E 117 GPa, nu 0.35, rho0 8930 kg/m3)
    every element's pressure is K (rho/rho0 - 1) of its output density. Returns the
    measurement (postproc/taylor.py)."""
    import h5py
    import numpy as np
    import taylor
    m = taylor.measure_file(path, axis=axis, wall=0.0)[0]
    print('MEASURED ' + taylor.human_line(m))
    length = m['length_m']
    nearest_end = min(max(length, 21.42e-3), 21.48e-3)
    compare('final_length_to_the_reference_range', length, nearest_end, 0.005, 'm')
    radius = 0.5 * m['footprint_diameter_m']
    print('MEASURED footprint radius %.4f mm, %+.2f %% from the reference 7.22 mm'
          % (radius * 1e3, 100 * (radius / 7.22e-3 - 1)))
    compare(radius_name, radius, radius_reference, 0.01, 'm')
    bulk = 117.0e9 / (3.0 * (1.0 - 2.0 * 0.35))   # the deck's E and nu
    rho0 = 8930.0
    with h5py.File(path, 'r') as f:
        worst = 0.0
        for k in f['steps']:
            st = f['steps'][k]
            p_eos = bulk * (st['density'][:] / rho0 - 1.0)
            worst = max(worst, float(np.max(np.abs(st['pressure'][:] - p_eos))))
    below('pressure_minus_eos_of_output_density_Pa_over_1GPa', worst / 1.0e9, 1.0e-6, '')
    return m


def finish():
    sys.exit(1 if _failed else 0)
