#!/usr/bin/env python3
"""sierra-tile build on the inputs a GIS user brings, end to end.

- Four SRTM3 .hgt tiles (1201 x 1201 samples each, big-endian int16, -32768
  voids) mosaicked through GDAL into one 2401 x 2401 grid: the extent, the
  metre spacing at their latitude, the no-data mask flag and exact int16
  heights (scale 1) are in the header sierra-tile info reports.
- A non-square float32 .npy (memory-mapped): its extent and the bytes a sample.
- sierra-bench tiled flies over the mosaic under a small cache: the first
  frame comes at once, the cache stays within its budget, tiles are read.
- sierra-render draws the mosaic from its tile file: a PNG of the frame once
  every tile it wanted has arrived, with shadows and sky light from the
  overview; options that need the grid in memory are refused with one message.
- sierra-gen map of a float tile file is the map of the grid it was built from,
  byte for byte (the overview at full resolution): a generated .npy and a real
  DEM (Jacksboro, 403 x 344, an .npz with its georeference), which also draws,
  with an image drape too, and with auto zones of its overview that lie where
  the in-memory renderer's do.
- Bad input: a missing file, a truncated tile file, an unknown option, each one
  message and a non-zero exit, and no output file left behind.
Exit 77 (CTest: skipped) with a note when NumPy is
missing: apt-get install python3-numpy.

Usage: tile_inputs.py SIERRA_TILE SIERRA_BENCH SIERRA_RENDER SIERRA_GEN IMAGE_COMPARE WORK_DIR
"""

import json
import os
import subprocess
import struct
import sys
import zlib

SKIP = 77


def reexec_or_skip(reason):
    # The first python3 on PATH may lack the system's packages; Debian's has them.
    system = "/usr/bin/python3"
    if os.path.exists(system) and os.path.realpath(sys.executable) != os.path.realpath(system) \
            and not os.environ.get("SIERRA_TILE_REEXEC"):
        os.environ["SIERRA_TILE_REEXEC"] = "1"
        os.execv(system, [system] + sys.argv)
    print(f"SKIPPED: {reason}; apt-get install python3-numpy")
    sys.exit(SKIP)


try:
    import numpy as np
except ImportError:
    reexec_or_skip("NumPy is missing")


def write_png(path, width, height, colour):
    """An RGB PNG whose pixel (i, j) is colour(i, j)."""
    rows = b"".join(b"\0" + bytes(c for i in range(width) for c in colour(i, j))
                    for j in range(height))
    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))


def run(*args, ok=True):
    p = subprocess.run(args, capture_output=True, text=True, timeout=600)
    if ok and p.returncode != 0:
        sys.exit(f"{' '.join(args)}: exit {p.returncode}\n{p.stdout}\n{p.stderr}")
    if not ok:
        lines = [l for l in p.stderr.splitlines() if "error" in l]
        if p.returncode == 0 or p.returncode < 0 or len(lines) != 1:
            sys.exit(f"{' '.join(args)}: expected one error and a clean non-zero exit, "
                     f"got {p.returncode}\n{p.stderr}")
    return p


def info(tile, path):
    report = path + ".json"
    run(tile, "info", path, "--json", report)
    with open(report) as f:
        return json.load(f)


def main():
    tile, bench, render, gen, compare, work = sys.argv[1:7]
    os.makedirs(work, exist_ok=True)

    # Four SRTM3 tiles at 46-48 N, 7-9 E; each tile's value encodes its position.
    names = []
    for lat in (46, 47):
        for lon in (7, 8):
            j, i = np.mgrid[0:1201, 0:1201]
            h = (1000 + (lat - 46) * 500 + (lon - 7) * 200 + (i + j) % 97).astype(">i2")
            if (lat, lon) == (47, 8):
                h[100:110, 200:230] = -32768  # a void
            name = os.path.join(work, f"N{lat:02d}E{lon:03d}.hgt")
            h.tofile(name)
            names.append(name)
    out = os.path.join(work, "alps.sierra")
    run(tile, "build", *names, "--out", out, "--tile-levels", "7")
    head = info(tile, out)
    assert head["width"] == 2401 and head["height"] == 2401, head
    assert head["grid_side"] == 4097 and head["tile_levels"] == 7, head
    assert head["no_data"] is True, "the void is masked"
    assert head["metres"] is True, head
    assert head["heights"] == "int16" and head["height_scale"] == 1.0, "int16 input kept exactly"
    # 3 arc seconds: 92.6 m north-south, about 63 m east-west at 47 N.
    sx, sz = head["spacing"]
    assert abs(sz - 92.6) < 0.5 and abs(sx - 63.2) < 1.0, head["spacing"]
    lat, lon = head["geo_centre"]
    assert abs(lat - 47.0) < 0.01 and abs(lon - 8.0) < 0.01, head["geo_centre"]
    print("hgt mosaic: ok", head["spacing"])

    # A short flight over the mosaic under a 16 MiB cache.
    report = os.path.join(work, "fly.json")
    run(bench, "tiled", out, "--seconds", "2", "--fps", "15", "--size", "640x360",
        "--memory-budget", "16", "--json", report)
    with open(report) as f:
        fly = json.load(f)
    assert fly["frames"] == 30, fly
    assert fly["first_frame_ms"] < 1000.0, fly["first_frame_ms"]
    assert fly["cache_peak_bytes"] <= fly["budget_bytes"], fly
    assert fly["tiles_read"] > 0 and fly["triangles_median"] > 0, fly
    print("tiled flight: ok", fly["tiles_read"], "tiles read")

    # A frame of the mosaic from its tile file, and an option it cannot take.
    frame = os.path.join(work, "alps.png")
    p = run(render, "--heightmap", out, "--size", "480x270", "--out", frame, "--no-debug",
            "--memory-budget", "64")
    assert os.path.getsize(frame) > 1000, "a frame was written"
    assert "0 tiles drawn coarse" in p.stderr, p.stderr
    # Shadows and sky light (on by default) from the overview: every 2nd sample
    # keeps a side within 2049.
    assert "shadows and sky light on an overview of 1201x1201 samples (stride 2" in p.stderr, \
        p.stderr
    with open(frame, "rb") as f:
        assert f.read(8) == b"\x89PNG\r\n\x1a\n"
    p = run(render, "--heightmap", out, "--zones", os.path.join(work, "zones.png"), "--out",
            os.path.join(work, "z.png"), "--no-debug", ok=False)
    assert "--zones with a zone map needs a heightmap in memory" in p.stderr, p.stderr
    print("tiled render: ok")

    # A non-square float32 .npy, memory-mapped.
    grid = (np.random.default_rng(1).random((300, 700)) * 500).astype("<f4")
    npy = os.path.join(work, "wide.npy")
    np.save(npy, grid)
    wide = os.path.join(work, "wide.sierra")
    run(tile, "build", npy, "--out", wide, "--heights", "float", "--tile-levels", "6")
    head = info(tile, wide)
    assert head["width"] == 700 and head["height"] == 300 and head["grid_side"] == 1025, head
    per_sample = os.path.getsize(wide) / (700 * 300)
    assert per_sample < 7.0, per_sample  # the partly padded edge tiles are stored whole
    print(f"npy: ok, {per_sample:.2f} bytes a sample")

    # The same map from the grid and from its tile file.
    maps = [os.path.join(work, name) for name in ("wide_npy.png", "wide_tiled.png")]
    run(gen, "map", "--heightmap", npy, "--out", maps[0])
    run(gen, "map", "--heightmap", wide, "--out", maps[1])
    with open(maps[0], "rb") as f, open(maps[1], "rb") as g:
        assert f.read() == g.read(), "the tiled terrain's map differs from the grid's"
    print("map: ok")

    # A real DEM (non-square, georeferenced, metres; Debian's python-matplotlib-data):
    # its tile file gives the map of the .npz, byte for byte, and draws.
    dem = "/usr/share/matplotlib/mpl-data/sample_data/jacksboro_fault_dem.npz"
    if os.path.exists(dem):
        jack = os.path.join(work, "jacksboro.sierra")
        run(tile, "build", dem, "--out", jack, "--heights", "float", "--tile-levels", "5")
        head = info(tile, jack)
        assert head["width"] == 403 and head["height"] == 344 and head["metres"], head
        maps = [os.path.join(work, name) for name in ("jack_npz.png", "jack_tiled.png")]
        run(gen, "map", "--heightmap", dem, "--out", maps[0])
        run(gen, "map", "--heightmap", jack, "--out", maps[1])
        with open(maps[0], "rb") as f, open(maps[1], "rb") as g:
            assert f.read() == g.read(), "the DEM's tile file maps differently"
        p = run(render, "--heightmap", jack, "--size", "320x180", "--no-debug",
                "--out", os.path.join(work, "jack.png"))
        assert "0 tiles drawn coarse" in p.stderr, p.stderr
        run(render, "--heightmap", jack, "--vertical-scale", "2", "--no-debug",
            "--out", os.path.join(work, "jack2.png"), ok=False)
        # An image drape (a PNG with no georeference: stretched over the
        # terrain), and a missing one.
        drape = os.path.join(work, "drape.png")
        write_png(drape, 64, 32, lambda i, j: (200, 40, 40) if i < 32 else (40, 40, 200))
        p = run(render, "--heightmap", jack, "--size", "320x180", "--no-debug",
                "--drape", drape, "--out", os.path.join(work, "jack_drape.png"))
        # (resampled to the terrain's aspect, as the in-memory renderer does)
        assert "drape: " + drape + ", 64x55 texels, 100% of the terrain" in p.stderr, p.stderr
        assert "0 tiles drawn coarse" in p.stderr, p.stderr
        run(render, "--heightmap", jack, "--drape", os.path.join(work, "none.png"), "--no-debug",
            "--out", os.path.join(work, "jack_none.png"), ok=False)
        assert not os.path.exists(os.path.join(work, "jack_none.png"))
        # Auto zones (flat zone colours): the tiled frame is nearer the in-memory
        # renderer's zones than either frame is to its own without zones (the
        # two renderers' meshes and light differ a little everywhere).
        flat = ["--size", "640x400", "--no-debug", "--shadows", "off", "--sky-light", "off"]
        frames, logs = {}, {}
        for name, heightmap in (("mem", dem), ("tiled", jack)):
            for zones in (True, False):
                out_png = os.path.join(work, f"jack_{name}_{'zones' if zones else 'ramp'}.png")
                extra = ["--zones", "auto", "--debug-view", "zones"] if zones else []
                p = run(render, "--heightmap", heightmap, *flat, *extra, "--out", out_png)
                frames[name, zones], logs[name, zones] = out_png, p.stderr
        assert "zones: auto on an overview of 403x344 samples (stride 1), 7 surface types" \
            in logs["tiled", True], logs["tiled", True]
        def psnr(a, b):
            out = run(compare, frames[a], frames[b]).stdout
            return float(out.split()[1])
        same_zones = psnr(("mem", True), ("tiled", True))
        print(f"zones: tiled vs in-memory {same_zones:.1f} dB; against the ramps "
              f"{psnr(('mem', True), ('tiled', False)):.1f} and "
              f"{psnr(('tiled', True), ('mem', False)):.1f} dB")
        assert same_zones > psnr(("mem", True), ("tiled", False)) + 2.0
        assert same_zones > psnr(("tiled", True), ("mem", False)) + 2.0
        # Curvature lines and contour edges: the overlays' window near the
        # camera is the whole of this small DEM; they darken the frame.
        lines = os.path.join(work, "jack_tiled_lines.png")
        p = run(render, "--heightmap", jack, *flat, "--style", "shaded,lines,contours",
                "--curvature-scale", "auto", "--out", lines)
        assert "overlays: near the camera, samples 0..402 x 0..343 of the tiled terrain" \
            in p.stderr, p.stderr
        differing = float(run(compare, lines, frames["tiled", False]).stdout.split()[3])
        assert differing > 0.01, f"the overlays change {differing:.3f} of the frame"
        run(render, "--heightmap", jack, "--wireframe", "--no-debug",
            "--out", os.path.join(work, "jack_wire.png"), ok=False)
        print("real DEM: ok")

    # Bad input: one message, a non-zero exit, no output.
    missing = os.path.join(work, "missing.sierra")
    run(tile, "build", os.path.join(work, "nothing.tif"), "--out", missing, ok=False)
    run(tile, "build", npy, "--out", missing, "--tile-levels", "0", ok=False)
    run(tile, "build", npy, "--out", missing, "--no-such-option", ok=False)
    assert not os.path.exists(missing), "a failed build left a file"
    cut = os.path.join(work, "cut.sierra")
    with open(wide, "rb") as f, open(cut, "wb") as g:
        g.write(f.read(os.path.getsize(wide) // 2))
    run(tile, "info", cut, ok=False)
    leftovers = [f for f in os.listdir(work) if ".tmp-" in f]
    assert not leftovers, leftovers
    print("bad input: ok")


if __name__ == "__main__":
    main()
