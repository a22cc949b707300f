#!/usr/bin/env python3
"""Frames to files against the frame loop alone, side by side in one run.

    capture_timing.py --apps BUILD/apps --json OUT.json [--frames 48] [--size 1920x1080]
                      [--repeat 5] [--work DIR]

Runs, in turn and --repeat times each (interleaved, so both see the same load):
  - sierra-bench frames --size S --frames N --path orbit (the frame loop, read-back included);
  - sierra-render with the same frames (--msaa 0, the frame loop's default) to a PNG sequence;
  - sierra-render to a JPEG sequence;
  - sierra-render with its own defaults (4x MSAA) to PNG, the command a user types first.
Each time is the program's whole run (start-up included) by the wall clock. Writes the
medians, the ratios of each capture to the frame loop and the bytes of a frame as JSON.
"""
import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--apps", required=True, help="the folder of sierra-render and sierra-bench")
    p.add_argument("--json", required=True)
    p.add_argument("--frames", type=int, default=48)
    p.add_argument("--size", default="1920x1080")
    p.add_argument("--repeat", type=int, default=5)
    p.add_argument("--work", help="where the frames go (default: a temporary folder)")
    a = p.parse_args(argv)
    render = os.path.join(a.apps, "sierra-render")
    bench = os.path.join(a.apps, "sierra-bench")
    work = a.work or tempfile.mkdtemp(prefix="sierra_capture_")
    scene = ["--size", a.size, "--frames", str(a.frames), "--path", "orbit"]
    cases = {
        "frame_loop": [bench, "frames"] + scene,
        "png": [render] + scene + ["--msaa", "0", "--no-debug", "--out", "{dir}/f.png"],
        "jpeg": [render] + scene + ["--msaa", "0", "--no-debug", "--out", "{dir}/f.jpg"],
        "png_msaa4": [render] + scene + ["--no-debug", "--out", "{dir}/f.png"],
    }
    times = {name: [] for name in cases}
    frame_bytes = {}
    for _ in range(a.repeat):
        for name, command in cases.items():
            folder = os.path.join(work, name)
            shutil.rmtree(folder, ignore_errors=True)
            words = [w.replace("{dir}", folder) for w in command]
            start = time.monotonic()
            done = subprocess.run(words, capture_output=True, text=True)
            took = time.monotonic() - start
            if done.returncode != 0:
                sys.stderr.write(f"capture_timing: {name} failed ({done.returncode}):\n{done.stderr}")
                return 1
            times[name].append(took)
            if os.path.isdir(folder):
                files = sorted(os.listdir(folder))
                if len(files) != a.frames:
                    sys.stderr.write(f"capture_timing: {name} wrote {len(files)} files, not {a.frames}\n")
                    return 1
                frame_bytes[name] = statistics.median(
                    os.path.getsize(os.path.join(folder, f)) for f in files)
            print(f"{name}: {took:.2f} s", file=sys.stderr)
    if not a.work:
        shutil.rmtree(work, ignore_errors=True)
    medians = {name: statistics.median(t) for name, t in times.items()}
    report = {
        "frames": a.frames, "size": a.size, "repeat": a.repeat,
        "commands": {name: " ".join(os.path.basename(w) if i == 0 else w
                                     for i, w in enumerate(c)) for name, c in cases.items()},
        "seconds": times,
        "median_s": medians,
        "ratio_to_frame_loop": {name: medians[name] / medians["frame_loop"]
                                for name in cases if name != "frame_loop"},
        "frame_bytes_median": frame_bytes,
    }
    tmp = a.json + ".tmp"
    with open(tmp, "w") as fh:
        json.dump(report, fh, indent=1)
    os.replace(tmp, a.json)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
