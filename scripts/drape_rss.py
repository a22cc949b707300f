#!/usr/bin/env python3
"""Peak memory of a large orthophoto drape, beside the same frame without it.

    drape_rss.py APPS_DIR OUT_DIR JSON [SIDE]

Writes OUT_DIR/ortho.tif, a SIDE x SIDE RGB GeoTIFF (default 16384, tiled and
deflated, written in bands of 1024 rows so this script stays small), then runs
  sierra-render --generate 2049 --size 1920x1080 --no-debug --out OUT_DIR/plain.png
  sierra-render ... --drape OUT_DIR/ortho.tif --out OUT_DIR/ortho.png
and takes each process's peak resident set size from the kernel (wait4's
rusage). JSON gets both peaks in bytes, their difference, the texture's size
with its mip chain, and the target (2 GiB).
"""

import json
import os
import subprocess
import sys

import numpy as np
from osgeo import gdal

GIB = 1 << 30


def write_ortho(path, side):
    ds = gdal.GetDriverByName("GTiff").Create(
        path, side, side, 3, gdal.GDT_Byte, ["TILED=YES", "COMPRESS=DEFLATE", "PREDICTOR=2"])
    x = np.arange(side, dtype=np.uint32)[None, :]
    for y0 in range(0, side, 1024):
        y = np.arange(y0, min(side, y0 + 1024), dtype=np.uint32)[:, None]
        checker = ((x // 64 + y // 64) % 2 * 200 + 30).astype(np.uint8)
        east = np.broadcast_to((x * 255 // side).astype(np.uint8), checker.shape)
        south = np.broadcast_to((y * 255 // side).astype(np.uint8), checker.shape)
        for band, values in enumerate((checker, east, south)):
            ds.GetRasterBand(band + 1).WriteArray(np.ascontiguousarray(values), 0, y0)
    ds = None


def peak_rss(command):
    """The process's exit status and its peak resident set size in bytes."""
    p = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    err = p.stderr.read()
    _, status, usage = os.wait4(p.pid, 0)
    p.returncode = os.waitstatus_to_exitcode(status)
    if p.returncode != 0:
        sys.exit(f"drape_rss: {' '.join(command)}: exit {p.returncode}\n{err.decode()[-2000:]}")
    return usage.ru_maxrss * 1024  # Linux reports KiB


def main(argv):
    if len(argv) not in (4, 5):
        sys.stderr.write(__doc__)
        return 2
    apps, out, report = argv[1], argv[2], argv[3]
    side = int(argv[4]) if len(argv) == 5 else 16384
    os.makedirs(out, exist_ok=True)
    ortho = os.path.join(out, "ortho.tif")
    write_ortho(ortho, side)
    render = [os.path.join(apps, "sierra-render"), "--generate", "2049", "--size", "1920x1080",
              "--no-debug"]
    plain = peak_rss(render + ["--out", os.path.join(out, "plain.png")])
    draped = peak_rss(render + ["--drape", ortho, "--out", os.path.join(out, "ortho.png")])
    texels = sum(max(1, side >> k) ** 2 for k in range(side.bit_length()))
    result = {"side": side, "plain_peak_rss": plain, "drape_peak_rss": draped,
              "difference": draped - plain, "texture_bytes_with_mips": texels * 4,
              "target_bytes": 2 * GIB}
    with open(report, "w") as fh:
        json.dump(result, fh, indent=1)
    print(f"drape_rss: {side}^2 drape peak {draped / GIB:.3f} GiB, plain {plain / GIB:.3f} GiB")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
