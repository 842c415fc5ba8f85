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


def finish():
    sys.exit(1 if _failed else 0)
