#!/usr/bin/env python3
"""sierra-gen map --values against gdaldem on the same Float32 GeoTIFF.

A rough diamond-square terrain (cropped to 129 x 113 samples, 30 m pixels in a
projected system, a flat plateau, and no-data holes inside and on the border)
is written with GDAL's Python bindings; gdaldem computes each field and
sierra-gen map writes the same field with --values. Both runs, with and without
-compute_edges, must agree:
  - the no-data samples exactly (gdaldem's no-data value where sierra-gen has NaN);
  - slope and aspect within 1e-3 degrees (aspect modulo 360);
  - hillshade (each style) within 1 grey level on at least 99.9% of the samples;
  - TRI (Riley, Wilson), TPI and roughness within 1e-4 relative (to the larger
    of the value and 1 m, for values near 0).
Exit 77 (CTest: skipped) with a note when gdaldem, NumPy or GDAL's Python
bindings are missing: apt-get install gdal-bin python3-gdal python3-numpy.

Usage: gen_map_gdaldem.py SIERRA_GEN WORK_DIR
"""

import os
import shutil
import subprocess
import sys

SKIP = 77


def reexec_or_skip(reason):
    # The first python3 on PATH may lack the system's packages; Debian's has them.
    system = "/usr/bin/python3"
    if os.path.exists(system) and os.path.realpath(sys.executable) != os.path.realpath(system) \
            and not os.environ.get("SIERRA_GDALDEM_REEXEC"):
        os.environ["SIERRA_GDALDEM_REEXEC"] = "1"
        os.execv(system, [system] + sys.argv)
    print(f"SKIPPED: {reason}; apt-get install gdal-bin python3-gdal python3-numpy")
    sys.exit(SKIP)


try:
    import numpy as np
    from osgeo import gdal, osr
except ImportError as e:
    reexec_or_skip(f"this python3 ({sys.executable}) cannot import {e.name}")
if shutil.which("gdaldem") is None:
    reexec_or_skip("gdaldem is not installed")

gdal.UseExceptions()
GEN, WORK = os.path.abspath(sys.argv[1]), sys.argv[2]
os.makedirs(WORK, exist_ok=True)
os.chdir(WORK)
NODATA = -9999.0
failures = []


def diamond_square(n, rng, roughness=0.62):
    """(2^k+1)^2 fractal heights: each level's offsets shrink by `roughness`."""
    z = np.zeros((n, n))
    z[0, 0], z[0, -1], z[-1, 0], z[-1, -1] = rng.normal(size=4) * 200
    step, amp = n - 1, 150.0
    while step > 1:
        h = step // 2
        for y in range(h, n, step):  # diamond: centres of the squares
            for x in range(h, n, step):
                z[y, x] = (z[y - h, x - h] + z[y - h, x + h] + z[y + h, x - h] + z[y + h, x + h]) / 4 \
                    + rng.normal() * amp
        for y in range(0, n, h):  # square: edge midpoints
            for x in range((y + h) % step, n, step):
                s = [z[yy, xx] for yy, xx in ((y - h, x), (y + h, x), (y, x - h), (y, x + h))
                     if 0 <= yy < n and 0 <= xx < n]
                z[y, x] = sum(s) / len(s) + rng.normal() * amp
        step, amp = h, amp * roughness
    return z


def make_dem():
    rng = np.random.default_rng(20260101)
    z = diamond_square(129, rng)[:113, :] + 800.0
    z[60:70, 20:32] = 812.5  # a flat plateau: flat aspect, zero slope
    z[30:36, 80:85] = NODATA  # a hole inside
    z[0, 40:44] = NODATA  # no data on the border
    z[90, 0] = NODATA
    # Heights on a 1/32 m grid: gdaldem sums its windows in float32, and sums
    # of such heights (below 2^24 / 32 / 8 = 65536 m) are exact, so the
    # comparison tests the formulas rather than float32 rounding.
    z = (np.round(z * 32.0) / 32.0).astype(np.float32)
    d = gdal.GetDriverByName("GTiff").Create("dem.tif", z.shape[1], z.shape[0], 1, gdal.GDT_Float32)
    d.SetGeoTransform((500000.0, 30.0, 0.0, 4000000.0, 0.0, -30.0))
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(32633)  # UTM 33N: metres both ways
    d.SetProjection(srs.ExportToWkt())
    band = d.GetRasterBand(1)
    band.SetNoDataValue(NODATA)
    band.WriteArray(z)
    d = None


def gdaldem(mode, args):
    subprocess.run(["gdaldem", mode, "dem.tif", "ref.tif", "-q"] + args, check=True)
    ds = gdal.Open("ref.tif")
    band = ds.GetRasterBand(1)
    return band.ReadAsArray().astype(np.float64), band.GetNoDataValue()


def sierra(scheme, args):
    out = f"{scheme}.npy"
    r = subprocess.run([GEN, "map", "--heightmap", "dem.tif", "--scheme", scheme, "--values", out]
                       + args, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"sierra-gen map --scheme {scheme} {' '.join(args)}: exit "
                           f"{r.returncode}\n{r.stderr}")
    return np.load(out).astype(np.float64)


def compare(name, mode, gargs, scheme, sargs, kind):
    ref, nodata = gdaldem(mode, gargs)
    mine = sierra(scheme, sargs)
    if ref.shape != mine.shape:
        failures.append(f"{name}: shape {mine.shape}, gdaldem {ref.shape}")
        return
    mine_nd = np.isnan(mine)
    if nodata is None:
        # aspect -zero_for_flat writes 0 for no data as for flat ground, and
        # declares no no-data value: sierra-gen's NaN must meet a 0 there.
        bad_mask = int((mine_nd & (ref != 0.0)).sum())
        both = ~mine_nd
    else:
        ref_nd = ref == nodata
        bad_mask = int((ref_nd != mine_nd).sum())
        both = ~ref_nd & ~mine_nd
    a, b = mine[both], ref[both]
    if kind == "degrees":
        err = np.abs(a - b)
        ok = err <= 1e-3
    elif kind == "percent":  # as degrees of slope
        err = np.abs(np.degrees(np.arctan(a / 100.0)) - np.degrees(np.arctan(b / 100.0)))
        ok = err <= 1e-3
    elif kind == "aspect":
        err = np.abs((a - b + 180.0) % 360.0 - 180.0)
        ok = err <= 1e-3
    elif kind == "grey":
        err = np.abs(np.round(a) - b)
        ok = err <= 1.0
    else:
        err = np.abs(a - b) / np.maximum(np.abs(b), 1.0)
        ok = err <= 1e-4
    share = ok.mean() if ok.size else 0.0
    need = 0.999 if kind == "grey" else 1.0
    verdict = "ok" if bad_mask == 0 and share >= need and ok.size > 0 else "FAIL"
    print(f"{verdict:4s} {name:44s} no-data mismatches {bad_mask}, max error {err.max():.3g}, "
          f"within tolerance {100 * share:.3f}% of {ok.size}")
    if verdict != "ok":
        failures.append(name)


make_dem()
for edges in (False, True):
    e = ["-compute_edges"] if edges else []
    s = ["--compute-edges"] if edges else []
    tag = " edges" if edges else ""
    for galg, salg in (("Horn", "horn"), ("ZevenbergenThorne", "zevenbergen")):
        a = ["-alg", galg]
        sa = ["--algorithm", salg]
        compare(f"slope {salg}{tag}", "slope", a + e, "slope", sa + s, "degrees")
        compare(f"slope percent {salg}{tag}", "slope", a + ["-p"] + e, "slope",
                sa + ["--slope-units", "percent"] + s, "percent")
        compare(f"aspect {salg}{tag}", "aspect", a + e, "aspect", sa + s, "aspect")
        compare(f"aspect trigonometric zero-for-flat {salg}{tag}", "aspect",
                a + ["-trigonometric", "-zero_for_flat"] + e, "aspect",
                sa + ["--trigonometric", "--zero-for-flat"] + s, "aspect")
        compare(f"hillshade {salg}{tag}", "hillshade", a + e, "hillshade", sa + s, "grey")
    compare(f"hillshade az 100 alt 30 z 2.5{tag}", "hillshade", ["-az", "100", "-alt", "30", "-z", "2.5"] + e,
            "hillshade", ["--azimuth", "100", "--altitude", "30", "--z-factor", "2.5"] + s, "grey")
    for style in ("multidirectional", "combined", "igor"):
        compare(f"hillshade {style}{tag}", "hillshade", [f"-{style}"] + e, "hillshade",
                [f"--{style}"] + s, "grey")
    for formula in ("Riley", "Wilson"):
        compare(f"TRI {formula}{tag}", "TRI", ["-alg", formula] + e, "tri",
                ["--tri", formula.lower()] + s, "relative")
    compare(f"TPI{tag}", "TPI", e, "tpi", s, "relative")
    compare(f"roughness{tag}", "roughness", e, "roughness", s, "relative")

if failures:
    print(f"{len(failures)} comparisons failed: {', '.join(failures)}")
    sys.exit(1)
print("all comparisons with gdaldem hold")
