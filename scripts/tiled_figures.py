#!/usr/bin/env python3
"""The tiled terrain's whole-process figures on a terrain made for them.

    tiled_figures.py APPS_DIR OUT_DIR JSON [SIDE]

Writes OUT_DIR/t.r16, a SIDE^2 fractal (default 8193, scripts/make-large-terrain.py),
then runs, each process's peak resident set size taken from the kernel (wait4):
  sierra-tile build t.r16 --vertical-scale 0.05 --out t.sierra --json build.json
  sierra-bench tiled t.sierra --seconds 20 --memory-budget 64 --json flight.json
  sierra-render --heightmap t.sierra --size 1920x1080 --no-debug --tile-wait 0 --out far.png
  the same with --shadows off --sky-light off
JSON gets the build's seconds, bytes a sample and peak RSS, the flight's report
and peak RSS, and each frame's whole run and peak RSS. The 65537^2 figures of the
issue's targets come from the same commands on make-large-terrain.py's default
size (8.6 GB, 26 minutes to write): too large for a routine measurement.
"""

import json
import os
import subprocess
import sys
import time


def run(command):
    """Seconds the process took and its peak resident set size in bytes."""
    start = time.monotonic()
    p = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    err = p.stderr.read()
    _, status, usage = os.wait4(p.pid, 0)
    code = os.waitstatus_to_exitcode(status)
    if code != 0:
        sys.exit(f"tiled_figures: {' '.join(command)}: exit {code}\n{err.decode()[-2000:]}")
    return time.monotonic() - start, usage.ru_maxrss * 1024  # Linux reports KiB


def main(argv):
    if len(argv) not in (4, 5):
        sys.stderr.write(__doc__)
        return 2
    apps, out, report = argv[1], argv[2], argv[3]
    side = int(argv[4]) if len(argv) == 5 else 8193
    os.makedirs(out, exist_ok=True)
    here = os.path.dirname(os.path.abspath(__file__))
    raw, tiles = os.path.join(out, "t.r16"), os.path.join(out, "t.sierra")
    run([sys.executable, os.path.join(here, "make-large-terrain.py"), raw, "--size", str(side)])
    build_json, flight_json = os.path.join(out, "build.json"), os.path.join(out, "flight.json")
    build_s, build_rss = run([os.path.join(apps, "sierra-tile"), "build", raw, "--vertical-scale",
                              "0.05", "--out", tiles, "--json", build_json])
    os.remove(raw)
    budget_mib = 64
    _, flight_rss = run([os.path.join(apps, "sierra-bench"), "tiled", tiles, "--seconds", "20",
                         "--memory-budget", str(budget_mib), "--json", flight_json])
    render = [os.path.join(apps, "sierra-render"), "--heightmap", tiles, "--size", "1920x1080",
              "--no-debug", "--tile-wait", "0", "--out", os.path.join(out, "far.png")]
    frame_s, frame_rss = run(render)
    plain_s, plain_rss = run(render + ["--shadows", "off", "--sky-light", "off"])
    with open(build_json) as fh:
        build = json.load(fh)
    with open(flight_json) as fh:
        flight = json.load(fh)
    result = {"side": side, "samples": side * side, "file_bytes": os.path.getsize(tiles),
              "build_seconds": build_s, "build_peak_rss": build_rss, "build": build,
              "flight": flight, "flight_peak_rss": flight_rss, "budget_mib": budget_mib,
              "frame_seconds": frame_s, "frame_peak_rss": frame_rss,
              "plain_frame_seconds": plain_s, "plain_frame_peak_rss": plain_rss}
    os.remove(tiles)
    with open(report, "w") as fh:
        json.dump(result, fh, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
