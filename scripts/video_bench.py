#!/usr/bin/env python3
"""The 1080p orbit to mp4 beside the frame loop that renders the same frames.

    video_bench.py APPS_DIR OUT_DIR JSON [ROUNDS]

Each round runs, one after the other so both see the same machine,
  sierra-bench frames --size 1920x1080 --frames 48 --json ...
  sierra-render --size 1920x1080 --msaa 0 --frames 48 --path orbit --no-debug --out OUT_DIR/orbit.mp4
(the same 48 frames: sierra-bench frames' defaults are that orbit without MSAA)
and times each process from start to exit. JSON gets the medians over the
rounds (default 3): both wall times, the benchmark's own frame-loop time (the
sum of its frame times), their ratios, and the video's size and encoder.
"""

import json
import os
import re
import statistics
import subprocess
import sys
import time

SIZE, FRAMES = "1920x1080", "48"


def timed(command):
    start = time.monotonic()
    p = subprocess.run(command, capture_output=True, text=True)
    seconds = time.monotonic() - start
    if p.returncode != 0:
        sys.exit(f"video_bench: {' '.join(command)}: exit {p.returncode}\n{p.stderr[-2000:]}")
    return seconds, p.stdout + p.stderr


def main(argv):
    if len(argv) not in (4, 5):
        sys.stderr.write(__doc__)
        return 2
    apps, out, report = argv[1], argv[2], argv[3]
    rounds = int(argv[4]) if len(argv) == 5 else 3
    os.makedirs(out, exist_ok=True)
    bench_json = os.path.join(out, "video_bench_frames.json")
    video = os.path.join(out, "orbit.mp4")
    bench = [os.path.join(apps, "sierra-bench"), "frames", "--size", SIZE, "--frames", FRAMES,
             "--json", bench_json]
    render = [os.path.join(apps, "sierra-render"), "--size", SIZE, "--msaa", "0", "--frames", FRAMES,
              "--path", "orbit", "--no-debug", "--out", video]
    bench_wall, loop, render_wall = [], [], []
    encoder = ""
    for _ in range(rounds):
        seconds, _ = timed(bench)
        bench_wall.append(seconds)
        with open(bench_json) as fh:
            frames = json.load(fh)["per_frame"]
        loop.append(sum(f["frame"] for f in frames) / 1000.0)
        seconds, log = timed(render)
        render_wall.append(seconds)
        m = re.search(r"at \d+ fps, (\S+)", log)
        encoder = m.group(1) if m else "unknown"
    result = {
        "rounds": rounds,
        "bench_wall_s": statistics.median(bench_wall),
        "bench_frame_loop_s": statistics.median(loop),
        "render_mp4_wall_s": statistics.median(render_wall),
        "encoder": encoder,
        "video_bytes": os.path.getsize(video),
        "all": {"bench_wall_s": bench_wall, "bench_frame_loop_s": loop, "render_mp4_wall_s": render_wall},
    }
    result["ratio_to_bench_wall"] = result["render_mp4_wall_s"] / result["bench_wall_s"]
    result["ratio_to_frame_loop"] = result["render_mp4_wall_s"] / result["bench_frame_loop_s"]
    with open(report, "w") as fh:
        json.dump(result, fh, indent=2)
    print(json.dumps(result, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
