#!/usr/bin/env python3
"""A fractal terrain of any size as a raw little-endian uint16 file (.r16),
written a band of rows at a time in bounded memory: the input of the tiled
terrain's benchmarks (65537^2 samples, 8.6 GB, by default).

Fractional Brownian motion of value noise with smoothstep interpolation,
Hurst exponent 0.8: the octaves of cells of 64 samples and more are summed on
a grid 16 times coarser and interpolated, the finer ones per band. Heights
span 0..65535 (metres with --spacing 1: a mountain range at 1 m).

Usage: make-large-terrain.py OUT.r16 [--size 65537] [--seed 1]
Needs NumPy (apt-get install python3-numpy); run it with /usr/bin/python3.
"""

import argparse
import os
import sys
import time

try:
    import numpy as np
except ImportError:
    sys.exit("make-large-terrain: NumPy is missing: apt-get install python3-numpy")

HURST = 0.8
COARSE = 16        # the coarse grid's step, samples
FINE_CELL = 64     # octaves with smaller cells are computed per band
TABLE = 4096       # side of the periodic lattice of the fine octaves


def smooth(t):
    return t * t * (3.0 - 2.0 * t)


def value_noise(x, y, cell, table):
    """Value noise at sample positions x (columns) and y (rows), cells of `cell` samples."""
    fx, fy = x / cell, y / cell
    ix, iy = np.floor(fx).astype(np.int64), np.floor(fy).astype(np.int64)
    tx, ty = smooth(fx - ix).astype(np.float32), smooth(fy - iy).astype(np.float32)
    n = table.shape[0]
    x0, x1 = ix % n, (ix + 1) % n
    y0, y1 = iy % n, (iy + 1) % n
    a = table[y0[:, None], x0[None, :]]
    b = table[y0[:, None], x1[None, :]]
    c = table[y1[:, None], x0[None, :]]
    d = table[y1[:, None], x1[None, :]]
    top = a + (b - a) * tx[None, :]
    bottom = c + (d - c) * tx[None, :]
    return top + (bottom - top) * ty[:, None]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("out")
    parser.add_argument("--size", type=int, default=65537, help="samples per side (default 65537)")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--band", type=int, default=256, help="rows written at a time")
    args = parser.parse_args()
    size = args.size
    if size < 2 * COARSE:
        sys.exit(f"make-large-terrain: --size must be at least {2 * COARSE}")
    rng = np.random.default_rng(args.seed)
    cells = []
    cell = 1 << max(1, (size - 1).bit_length())
    while cell >= 2:
        cells.append(cell)
        cell //= 2
    coarse_cells = [c for c in cells if c >= FINE_CELL]
    fine_cells = [c for c in cells if c < FINE_CELL]
    amplitude = {c: float(c) ** HURST for c in cells}
    tables = {c: rng.random((TABLE, TABLE), dtype=np.float32) - 0.5 for c in fine_cells}

    # The coarse octaves on every COARSE-th sample (and one beyond the edge).
    coarse_side = (size - 1) // COARSE + 2
    positions = np.arange(coarse_side, dtype=np.float64) * COARSE
    coarse = np.zeros((coarse_side, coarse_side), dtype=np.float32)
    for c in coarse_cells:
        lattice = int(np.ceil(size / c)) + 2
        table = rng.random((lattice, lattice), dtype=np.float32) - 0.5
        coarse += amplitude[c] * value_noise(positions, positions, c, table)
    span_fine = sum(amplitude[c] for c in fine_cells) * 0.5
    low, high = float(coarse.min()) - span_fine, float(coarse.max()) + span_fine
    scale = 65535.0 / (high - low)

    tmp = args.out + ".partial"
    columns = np.arange(size, dtype=np.float64)
    cx = columns / COARSE
    cx0 = np.floor(cx).astype(np.int64)
    cfx = (cx - cx0).astype(np.float32)
    start = time.time()
    with open(tmp, "wb") as out:
        for y0 in range(0, size, args.band):
            rows = np.arange(y0, min(size, y0 + args.band), dtype=np.float64)
            cy = rows / COARSE
            cy0 = np.floor(cy).astype(np.int64)
            cfy = (cy - cy0).astype(np.float32)
            a = coarse[cy0[:, None], cx0[None, :]]
            b = coarse[cy0[:, None], cx0[None, :] + 1]
            c = coarse[cy0[:, None] + 1, cx0[None, :]]
            d = coarse[cy0[:, None] + 1, cx0[None, :] + 1]
            top = a + (b - a) * cfx[None, :]
            h = top + ((c + (d - c) * cfx[None, :]) - top) * cfy[:, None]
            for cell in fine_cells:
                h += amplitude[cell] * value_noise(columns, rows, cell, tables[cell])
            np.clip((h - low) * scale, 0.0, 65535.0).astype("<u2").tofile(out)
            done = min(size, y0 + args.band)
            print(f"\rmake-large-terrain: {done}/{size} rows, {time.time() - start:.0f} s",
                  end="", file=sys.stderr, flush=True)
    print(file=sys.stderr)
    os.replace(tmp, args.out)
    print(f"{args.out}: {size} x {size} uint16 samples ({os.path.getsize(args.out)} bytes)")


if __name__ == "__main__":
    main()
