#!/usr/bin/env python3
"""The Python module's cost over the C++ facade, side by side in one run.

Renders one 1080p frame of the same scene (the default fractal unless --config
names a scene file) through `sierra.Renderer.render` and through
`sierra-bench facade` (facade::SceneRenderer, the renderer created on a kept
context and frame 0 read back, as the module does), in alternating rounds, and
reports each side's median and their ratio (target: at most 1.05).

    PYTHONPATH=build/python python3 python/bench/render_bench.py \\
        --bench build/apps/sierra-bench [--config scene.json] [--rounds 3] [--repeat 3] \\
        [--json out.json]
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

import sierra


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bench", required=True, help="the sierra-bench program")
    ap.add_argument("--config", help="scene JSON (default: the default scene at 1920x1080)")
    ap.add_argument("--rounds", type=int, default=3, help="alternating rounds (default 3)")
    ap.add_argument("--repeat", type=int, default=3, help="timed renders per side and round")
    ap.add_argument("--json", help="write the figures as JSON")
    a = ap.parse_args()
    if a.rounds < 1 or a.repeat < 1:
        sys.exit("render_bench.py: error: --rounds and --repeat must be at least 1")

    if a.config:
        with open(a.config) as fh:
            scene = sierra.Scene.from_json(fh.read())
    else:
        scene = sierra.Scene(width=1920, height=1080)
    with tempfile.TemporaryDirectory() as tmp:
        config = os.path.join(tmp, "scene.json")
        with open(config, "w") as fh:
            fh.write(scene.to_json())
        renderer = sierra.Renderer()
        renderer.render(scene=scene)  # warm-up, as the facade command does
        py_ms, cpp_ms = [], []
        for r in range(a.rounds):
            report = os.path.join(tmp, f"facade{r}.json")
            subprocess.run([a.bench, "facade", "--config", config, "--repeat", str(a.repeat),
                            "--json", report], check=True, stdout=subprocess.DEVNULL)
            with open(report) as fh:
                cpp_ms += json.load(fh)["render_ms"]
            for _ in range(a.repeat):
                start = time.perf_counter()
                image = renderer.render(scene=scene)
                py_ms.append(1000.0 * (time.perf_counter() - start))
            assert image.shape[:2] == (scene.to_dict()["output"]["height"],
                                       scene.to_dict()["output"]["width"])
    py, cpp = statistics.median(py_ms), statistics.median(cpp_ms)
    print(f"Python render: median {py:.1f} ms over {len(py_ms)}")
    print(f"C++ facade:    median {cpp:.1f} ms over {len(cpp_ms)}")
    print(f"ratio {py / cpp:.3f} (target at most 1.05)")
    if a.json:
        with open(a.json, "w") as fh:
            json.dump({"command": "python-render", "gl_renderer": renderer.gl_renderer,
                       "python_ms": py_ms, "facade_ms": cpp_ms, "python_median_ms": py,
                       "facade_median_ms": cpp, "ratio": py / cpp}, fh, indent=2)
            fh.write("\n")


if __name__ == "__main__":
    main()
