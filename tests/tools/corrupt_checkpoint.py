#!/usr/bin/env python3
"""Damage a copy of a udar checkpoint the way a disk, a network file system
or a careless hand does: change bytes in the middle, not only at the end.

  corrupt_checkpoint.py IN OUT CASE

CASE is one of the names in CASES (a byte of one number, chosen by dataset
and row) or 'random:SEED' (8 random bytes anywhere past the superblock).
Prints what it changed.
"""
import random
import shutil
import sys

import h5py
import numpy as np

# (dataset, row, column or None, byte within the float64: 0 = lowest mantissa byte, 7 = sign/exponent)
CASES = {
    'velocity_mantissa': ('nodes/v', 100, 2, 2),
    'velocity_low_bit': ('nodes/v', 7, 0, 0),
    'position_exponent': ('nodes/x', 500, 1, 7),
    'force_mantissa': ('nodes/f', 33, 2, 5),
    'vref_mantissa': ('nodes/vref', 12, None, 3),
    'stress_exponent': ('elems/s', 2000, 3, 7),
    'stress_mantissa': ('elems/s', 10, 0, 1),
    'energy_mantissa': ('elems/e', 4000, None, 4),
    'plastic_strain_exponent': ('elems/eps_p', 1234, None, 6),
    'volume_mantissa': ('elems/vol', 77, None, 2),
    'temperature_mantissa': ('elems/temp', 5000, None, 5),
    'state_flag': ('elems/state', 42, None, 6),
    'altitude_mantissa': ('elems/h', 4321, None, 3),
    'wall_work_limb': ('wall_work', 3, None, 0),
    'model_hash_byte': ('hashes', 0, None, 1),
    'checksum_byte': ('checksum', 0, None, 4),
}
ATTRS = {   # scalars stored as attributes: changed through the library
    'time_attribute': ('t', lambda v: np.nextafter(v, 1.0)),
    'cycle_attribute': ('cycle', lambda v: v + 1),
    'stable_step_attribute': ('dt_stable', lambda v: v*1.5),
}


def flip(path, offset, byte_values):
    with open(path, 'r+b') as f:
        f.seek(offset)
        old = f.read(len(byte_values))
        f.seek(offset)
        f.write(bytes(byte_values))
    return old


def main():
    src, dst, case = sys.argv[1:4]
    shutil.copyfile(src, dst)
    if case in CASES:
        name, row, col, byte = CASES[case]
        with h5py.File(dst, 'r') as h:
            ds = h[name]
            offset = ds.id.get_offset()
            assert offset is not None, f'{name} is not contiguous'
            width = 1 if ds.ndim == 1 else ds.shape[1]
            item = row*width + (col or 0)
            offset += item*ds.dtype.itemsize + byte
        old = flip(dst, offset, [0])
        if old == b'\x00':
            flip(dst, offset, [0x5a])
        print(f'{case}: {name} row {row} col {col} byte {byte} at file offset {offset}')
    elif case in ATTRS:
        name, change = ATTRS[case]
        with h5py.File(dst, 'r+') as h:
            old = h.attrs[name]
            h.attrs.modify(name, change(old))
            print(f'{case}: attribute {name} {old} -> {h.attrs[name]}')
    elif case.startswith('random:'):
        rng = random.Random(int(case.split(':')[1]))
        with open(dst, 'rb') as f:
            size = len(f.read())
        for _ in range(8):
            offset = rng.randrange(512, size)
            flip(dst, offset, [rng.randrange(256)])
        print(f'{case}: 8 random bytes in {size} bytes')
    else:
        sys.exit(f'unknown case {case}; known: {", ".join(list(CASES) + list(ATTRS))}, random:SEED')


if __name__ == '__main__':
    main()
