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


def finish():
    sys.exit(1 if _failed else 0)
