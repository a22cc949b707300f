#!/usr/bin/env python3
"""The figures of docs/performance.md: what to run, and how its JSON becomes a table.

    perf_tables.py runs                 one line per run: NAME<TAB>OPTIONAL<TAB>COMMAND
                                        (OPTIONAL 1 or 0; COMMAND in shell words, {json}
                                        where the JSON file goes, {out} the output folder)
    perf_tables.py tables DIR [OUT.md]  DIR/NAME.json of every run (and DIR/machine.json)
                                        into Markdown, to OUT.md or stdout

scripts/measure.sh runs the commands and calls `tables`. Adding a figure is one
Figure(...) entry in FIGURES: its runs and a function from their parsed JSON to the
table's rows. A figure marked optional is left out (with a line saying so) when its
benchmarks do not exist in this build.
"""

import json
import os
import re
import shlex
import sys
from dataclasses import dataclass, field
from typing import Callable

# Google Benchmark runs: medians of 3 repetitions, aggregates only, JSON to {json}.
MICRO = ["sierra-microbench", "--benchmark_repetitions=3", "--benchmark_report_aggregates_only=true",
         "--benchmark_out={json}", "--benchmark_out_format=json"]
# The frame loop at 1080p, tau 1 px, no MSAA (sierra-bench frames' defaults) along the orbit.
FRAMES = ["sierra-bench", "frames", "--size", "1920x1080", "--tau", "1", "--path", "orbit"]
ROUGH = ["--generate", "2049", "--hurst", "0.8"]


@dataclass
class Figure:
    name: str
    title: str
    note: str
    runs: dict  # run name -> command (list of words)
    table: Callable  # dict run name -> parsed JSON  =>  (header, rows)
    optional: bool = False
    after: str = ""  # a sentence below the table


# ---------------------------------------------------------------- helpers

def micro_medians(report):
    """run_name -> the median aggregate of a Google Benchmark JSON report (the single
    run where a benchmark has no aggregates)."""
    out = {}
    for b in report.get("benchmarks", []):
        if b.get("run_type") == "aggregate":
            if b.get("aggregate_name") == "median":
                out[b["run_name"]] = b
        else:
            out.setdefault(b["run_name"], b)
    return out


def ms(b):
    """A benchmark's real time in milliseconds."""
    scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b.get("time_unit", "ns")]
    return b["real_time"] * scale


def f(x, digits=3):
    """A number with `digits` significant digits; from 1000 up a whole number, thousands
    spaced."""
    if x is None:
        return "n/a"
    if abs(x) >= 1000 or (isinstance(x, int) and not isinstance(x, bool)):
        return f"{int(round(x)):,}".replace(",", " ")
    if x == 0:
        return "0"
    return f"{x:.{digits}g}"


def threads_label(t):
    return {0: "default", 1: "1", 2: "2"}.get(int(t), str(t))


# ---------------------------------------------------------------- tables

def refinement_table(data):
    cases = [
        (r"BM_RefineFixed/2049/-1/(\d)/", "fixed error, 2049² full grid"),
        (r"BM_RefineFixed/2049/5/(\d)/", "fixed error, 2049², ε 0.05% of the relief"),
        (r"BM_RefineOrbit/8/(\d)/1/", "view-dependent, rough 2049² (H 0.8), orbit view, τ 1, culling"),
        (r"BM_RefineOrbitMoving/8/(\d)/150/", "the same camera, 48 views 15° apart"),
    ]
    rows = []
    for run, b in micro_medians(data["refine"]).items():
        for pattern, label in cases:
            m = re.match(pattern, run)
            if not m:
                continue
            t = b.get("median_ms", ms(b))
            tri = b.get("triangles")
            rate = tri / t / 1e3 if tri and t else None
            rows.append([label, threads_label(m.group(1)), f(tri), f(t), f(rate)])
    order = {label: k for k, (_, label) in enumerate(cases)}
    rows.sort(key=lambda r: (order[r[0]], {"1": 0, "2": 1, "default": 2}.get(r[1], 3)))
    return (["case", "threads", "triangles", "ms per refinement", "M triangles/s"], rows)


def frame_loop_table(data):
    rows = []
    for run, threads in (("loop_1", "1"), ("loop_default", "default")):
        d = data[run]
        rows.append([threads, f(d["triangles_median"]), f(d["ms"]["refine_strip"]["median"]),
                     f(d["refine_triangles_per_second_median"] / 1e6), f(d["ms"]["frame"]["median"]),
                     f(100 * d["cpu_share"], 2) + "%"])
    return (["threads", "triangles", "refine + strip, ms", "M triangles/s", "frame, ms",
             "refine + strip + upload, share of the frame"], rows)


def full_grid_table(data):
    d = data["full"]
    psnr = d.get("psnr") or {}
    rows = [
        ["SBT frame, median", f(d["ms"]["frame"]["median"]) + " ms"],
        ["full-grid frame, median", f(d["full_frame"]["median"]) + " ms"],
        ["frame time ratio SBT / full", f(d["frame_ratio"])],
        ["PSNR of the SBT frames against the full grid, median (min)",
         f"{f(psnr.get('median'))} dB ({f(psnr.get('min'))} dB)"],
        ["pixels differing by more than 8/255, median", f(100 * d["differing_share_median"], 2) + "%"],
        ["triangles per SBT frame", f(d["triangles_median"])],
        ["indices per triangle, bytes uploaded per triangle",
         f"{f(d['indices_per_triangle'], 4)}, {f(d['bytes_per_triangle'])}"],
    ]
    return (["", "value"], rows)


def indices_table(data):
    rows = []
    for run, label in (("static_full", "full 1025² grid"), ("static_fine", "fixed error 0.002 (1025²)"),
                       ("static_coarse", "fixed error 0.01 (1025²)")):
        d = data[run]
        rows.append([label, f(d["triangles"]), f(d["strip_indices"]), f(d["indices_per_triangle"], 4)])
    for run, label in (("loop_1", "view-dependent frames, rough 2049², τ 1"),
                       ("full", "view-dependent frames, 2049², τ 1")):
        d = data[run]
        rows.append([label + " (median frame)", f(d["triangles_median"]), "",
                     f(d["indices_per_triangle"], 4)])
    return (["mesh", "triangles", "strip indices", "indices per triangle"], rows)


def zones_table(data):
    rows = []
    for run, label in (("zones_auto", "`--zones auto`"),
                       ("zones_map", "the sample zone map, 4-pixel bands")):
        c = data[run]["surface_costs"]
        rows.append([label, f(c["plain_frame"]["median"]), f(c["zones_frame"]["median"]),
                     f(c["ratio"]), f(c["ratio_p95"]), f(c["cpu_ratio"])])
    return (["zone map", "plain colouring, frame ms", "zones, frame ms",
             "zones / plain, median over frames", "p95", "the same in process CPU time"], rows)


def overlays_table(data):
    o = data["overlays"]["overlay_costs"]
    rows = [["all four (shaded, lines, hatch, contours)", f(o["all_ratio"])]]
    for name, v in sorted(o.get("alone", {}).items()):
        rows.append([f"{name} alone", f(v["ratio"])])
    return (["overlays", "frame / frame without overlays"], rows)


def tin_table(data):
    rows = []
    for run, label in (("tin", "1025² fractal, max error 0.1% of the relief"),
                       ("tin_zones", "1025² default scene with the sample zone map, 0.5%")):
        d = data[run]
        t = d["time_ms"]
        rows.append([label, f(d["triangles"]), f(d["max_error"]), f(d["rms_error"]),
                     f(t["insert"]), f(t.get("borderlines", 0.0)), f(t["total"])])
    return (["case", "triangles", "max error", "RMS error", "insertion, ms", "borderlines, ms",
             "total, ms"], rows)


def curvature_table(data):
    methods = ["two-normal", "three-normal", "three-vertex", "edge-angle"]
    cpu1, cpuN, gpu = {}, {}, {}
    for run, b in micro_medians(data["curvature"]).items():
        m = re.match(r"BM_Curvature/2049/(\d)/1/(\d)/0/", run)
        if m:
            (cpu1 if m.group(2) == "1" else cpuN)[int(m.group(1))] = ms(b)
        m = re.match(r"BM_CurvatureGpu/2049/(\d)/0/0/1/", run)
        if m:
            gpu[int(m.group(1))] = ms(b)
    rows = []
    for k, name in enumerate(methods):
        g, c = gpu.get(k), cpuN.get(k)
        rows.append([name, f(cpu1.get(k)), f(c), f(g), f(g / c) if g and c else "n/a"])
    return (["method", "CPU, 1 thread, ms", "CPU, all threads, ms", "GPU, ms", "GPU / CPU all threads"],
            rows)


def python_table(data):
    d = data["python_render"]
    return (["path", "median, ms", "renders"],
            [["`sierra.Renderer.render`", f(d["python_median_ms"]), len(d["python_ms"])],
             ["`sierra-bench facade`", f(d["facade_median_ms"]), len(d["facade_ms"])],
             ["ratio", f(d["ratio"]), ""]])


def capture_table(data):
    d = data["capture"]
    enc = micro_medians(data["encode"])
    rows = [["`sierra-bench frames` (the frame loop, read back, nothing written)",
             f(d["median_s"]["frame_loop"]) + " s", "1", ""]]
    for name, label in (("png", "`sierra-render` to PNG, same frames (`--msaa 0`)"),
                        ("jpeg", "`sierra-render` to JPEG, same frames"),
                        ("png_msaa4", "`sierra-render` to PNG, its defaults (4x MSAA)")):
        rows.append([label, f(d["median_s"][name]) + " s", f(d["ratio_to_frame_loop"][name]),
                     f(d["frame_bytes_median"].get(name, 0) / 1e3)])
    stb = enc.get("BM_EncodePngStb/real_time")
    for run, label in (("BM_EncodePngStb/real_time", "one frame's encode: stb's PNG writer"),
                       ("BM_EncodePng/0/real_time", "one frame's encode: libspng, fast"),
                       ("BM_EncodePng/1/real_time", "one frame's encode: libspng, default"),
                       ("BM_EncodePng/2/real_time", "one frame's encode: libspng, best"),
                       ("BM_EncodeJpeg/90/real_time", "one frame's encode: libjpeg-turbo, quality 90")):
        b = enc.get(run)
        if b:
            rows.append([label, f(b["ms"]) + " ms", f(b["ms"] / stb["ms"]) if stb else "n/a",
                         f(b["bytes"] / 1e3)])
    return (["run", "median", "ratio (runs: to the frame loop; encodes: to stb)", "KB per frame"],
            rows)


def relief_table(data):
    """The relief target's work (BM_ReliefFields) and its parts, 4097² unless the row says."""
    cases = [
        (r"BM_ReliefFields/4097/0/0/", "16 azimuths + the sun, every angle kept (1 GiB)"),
        (r"BM_ReliefFields/4097/0/1/", "16 azimuths + the sun, only the sky light kept"),
        (r"BM_ReliefFields/4097/1/1/", "the same on one thread"),
        (r"BM_Horizons/4097/0/0/", "16 azimuths, every angle kept"),
        (r"BM_SunVisibility/4097/0/", "the sun alone (one sweep)"),
    ]
    rows = []
    benches = micro_medians(data["relief"])
    for pattern, label in cases:
        for run, b in benches.items():
            if re.match(pattern, run):
                t = ms(b)
                rate = b.get("items_per_second")
                rows.append([label, f(b.get("threads")), f(t / 1e3), f(rate / 1e6) if rate else "n/a"])
    return (["4097² fractal", "threads", "median, s", "M samples × azimuths / s"], rows)


def video_table(data):
    d = data["video_mp4"]
    rows = [
        ["sierra-bench frames, whole process", f(d["bench_wall_s"]) + " s"],
        ["its frame loop (the sum of the frame times)", f(d["bench_frame_loop_s"]) + " s"],
        [f"sierra-render to mp4 ({d['encoder']}), whole process", f(d["render_mp4_wall_s"]) + " s"],
        ["ratio to sierra-bench frames (whole processes)", f(d["ratio_to_bench_wall"])],
        ["ratio to its frame loop", f(d["ratio_to_frame_loop"])],
        ["video size", f(d["video_bytes"] / 1e6) + " MB"],
    ]
    return (["median of " + str(d["rounds"]) + " rounds", "value"], rows)


def layers_table(data):
    """BM_DrapeFrame's variants against the plain frame, then the orthophoto's peak memory."""
    benches = micro_medians(data["layers"])
    plain = benches.get("BM_DrapeFrame/0/real_time")
    rows = []
    for run, b in sorted(benches.items()):
        if not run.startswith("BM_DrapeFrame/"):
            continue
        label = b.get("label", run).split(",")[0]
        rows.append([label, f(ms(b)) + " ms", f(ms(b) / ms(plain)) if plain else "n/a"])
    d = data["drape_rss"]
    rows.append([f"peak RSS, one frame with a {d['side']}² RGB orthophoto (whole process)",
                 f(d["drape_peak_rss"] / 2**30) + " GiB",
                 f"{f(d['drape_peak_rss'] / d['target_bytes'])} of the 2 GiB target"])
    rows.append(["peak RSS, the same frame without it",
                 f(d["plain_peak_rss"] / 2**30) + " GiB", ""])
    return (["1920x1080 frame of a 2049² fractal", "median", "vs the plain frame"], rows)


def tiled_table(data):
    """BM_TiledRefine's four ways by their p99 against the in-memory one, then the
    tile file's build, fly-through and first frame (tiled_figures.py)."""
    benches = micro_medians(data["tiled_refine"])
    base = benches.get("BM_TiledRefine/0/real_time")
    rows = []
    for run, b in sorted(benches.items()):
        if not run.startswith("BM_TiledRefine/"):
            continue
        rows.append([b.get("label", run), f(ms(b)) + " ms", f(b["p99_ms"]) + " ms",
                     f(b["p99_ms"] / base["p99_ms"]) if base else "n/a"])
    t = data["tiled_flight"]
    side, fl = t["side"], t["flight"]
    rows.append([f"`sierra-tile build` of a {side}² .r16 (whole process)",
                 f(t["build_seconds"]) + " s",
                 f"{f(t['build']['bytes_per_sample'])} bytes a sample",
                 f"peak RSS {f(t['build_peak_rss'] / 2**20)} MiB"])
    rows.append([f"`sierra-bench tiled`, {f(fl['frames'])} frames at {f(fl['fps'])} fps, "
                 f"{t['budget_mib']} MiB budget: refine + strip",
                 f(fl["refine_ms"]["median"]) + " ms", f(fl["refine_ms"]["p99"]) + " ms",
                 f"first frame {f(fl['first_frame_ms'])} ms after start"])
    rows.append(["the same flight: tiles read, longest `beginFrame`",
                 f(fl["tiles_read"]), f(fl["begin_frame_ms_max"]) + " ms",
                 f"peak RSS {f(t['flight_peak_rss'] / 2**20)} MiB (whole process)"])
    rows.append(["`sierra-render --heightmap T.sierra` 1920x1080, one frame, nothing waited for",
                 f(t["frame_seconds"]) + " s", "",
                 f"peak RSS {f(t['frame_peak_rss'] / 2**20)} MiB (whole process)"])
    rows.append(["the same with `--shadows off --sky-light off`",
                 f(t["plain_frame_seconds"]) + " s", "",
                 f"peak RSS {f(t['plain_frame_peak_rss'] / 2**20)} MiB (whole process)"])
    return (["tiled terrain", "median", "p99", "vs in-memory p99 / other"], rows)


FIGURES = [
    Figure("refinement", "Refinement and strip emission",
           "Milliseconds per refinement (the median of single refinements) and the triangles it "
           "emits per second, by thread count; `default` measures one thread against all and keeps "
           "the faster.",
           {"refine": MICRO + ["--benchmark_filter=^BM_Refine(Fixed/2049/(-1|5)/[012]|Orbit/8/[012]/1"
                               "|OrbitMoving/8/1/150)/real_time$"]},
           refinement_table),
    Figure("frame-loop", "The frame loop",
           "Refinement inside the frame loop, where the driver's threads compete for the cores: "
           "24 frames of the orbit over a rough 2049² fractal at 1920x1080, medians over the frames.",
           {"loop_1": FRAMES + ROUGH + ["--frames", "24", "--threads", "1", "--json", "{json}"],
            "loop_default": FRAMES + ROUGH + ["--frames", "24", "--json", "{json}"]},
           frame_loop_table),
    Figure("full-grid", "View-dependent SBT against the full grid",
           "Each camera of the orbit drawn as the SBT at τ = 1 px and as the full 2049² grid "
           "(8 388 608 triangles).",
           {"full": FRAMES + ["--generate", "2049", "--frames", "6", "--compare-full", "--json", "{json}"]},
           full_grid_table,
           after="On llvmpipe the frame is fill-bound: the 1080p fragment work dominates whatever "
                 "the mesh."),
    Figure("indices", "Indices per triangle",
           "Generalized strips in Sierpinski order: exactly 5/3 on a full grid, less on adaptive "
           "meshes (a triangle list needs 3).",
           {"static_full": ["sierra-bench", "static", "--max-error", "-1", "--repeat", "3", "--json", "{json}"],
            "static_fine": ["sierra-bench", "static", "--max-error", "0.002", "--repeat", "3", "--json", "{json}"],
            "static_coarse": ["sierra-bench", "static", "--max-error", "0.01", "--repeat", "3", "--json", "{json}"]},
           indices_table,
           after="The view-dependent rows come from the runs of the two figures above."),
    Figure("zones", "Frame cost of the zone surface",
           "The default scene at 1920x1080, τ = 1 px, 24 frames of the orbit: each camera drawn in "
           "turn with the zone surface and with the plain colouring (the hypsometric ramp), the "
           "ratio taken frame by frame in one run, its median and 95th percentile over the frames; "
           "the last column is the median ratio of the CPU time the process spent on each frame (every "
           "thread), which the machine's other load moves less.",
           {"zones_auto": FRAMES + ["--frames", "24", "--zones", "auto", "--surface-costs",
                                    "--json", "{json}"],
            "zones_map": FRAMES + ["--frames", "24", "--zones", "assets/zones/default_zones.png",
                                   "--band", "4", "--surface-costs", "--json", "{json}"]},
           zones_table,
           after="Target: `--zones auto` at most 1.3x the plain frame on llvmpipe."),
    Figure("overlays", "Frame cost of the overlays",
           "Each camera drawn with all overlay passes, without them and with each alone, in turn "
           "(ratios of medians taken in one run), on the 257² terrain of the preset images with "
           "the line settings of fig3a; 6 frames.",
           {"overlays": FRAMES + ["--generate", "257", "--seed", "4", "--vertical-scale", "150",
                                  "--sea-level", "none", "--frames", "6",
                                  "--style", "shaded,lines,hatch,contours", "--curvature-distance", "2",
                                  "--curvature-scale", "6", "--min-length", "6", "--overlay-costs",
                                  "--json", "{json}"]},
           overlays_table),
    Figure("tin", "TIN build",
           "Greedy insertion until the largest vertical error falls below the target (relative to "
           "the height range), Delaunay flips, zone borderlines as constrained edges in the second row.",
           {"tin": ["sierra-tin", "--generate", "1025", "--max-error-rel", "0.001", "--out", "{out}/tin.obj",
                    "--json", "{json}"],
            "tin_zones": ["sierra-tin", "--zones", "assets/zones/default_zones.png", "--max-error-rel", "0.005",
                          "--out", "{out}/tin_zones.obj", "--json", "{json}"]},
           tin_table),
    Figure("curvature", "Curvature field: GPU against CPU",
           "The field along 4 directions of a 2049² grid, reinforcement distance 1, by method; the GPU "
           "path is the one the driver gets by default (fragment runs on llvmpipe, a compute shader "
           "elsewhere).",
           {"curvature": MICRO + ["--benchmark_filter=^BM_Curvature/2049/[0-3]/1/[01]/0/real_time$"
                                  "|^BM_CurvatureGpu/2049/[0-3]/0/0/1/real_time$"]},
           curvature_table),
    Figure("relief", "Relief fields",
           "Horizons of the 4097² diamond-square grid (relief a tenth of the extent) in 16 azimuths "
           "plus the sun's visibility in its own (300°, altitude 20°), on the CPU; the target is "
           "2 s on the 2-core machine. Medians of 3 runs.",
           {"relief": MICRO + ["--benchmark_filter=^BM_(ReliefFields/4097/|Horizons/4097/0/0"
                               "|SunVisibility/4097/0/)"]},
           relief_table, optional=True,
           after="Keeping every angle costs the mapping of 1 GiB of fresh pages on top; the terrain "
                 "pass needs only the sky light, made from one azimuth's angles at a time "
                 "(docs/relief.md)."),
    Figure("python", "Python render against the C++ facade",
           "One 1080p frame of the default scene, the renderer created for the scene on a kept "
           "context and the frame read back, through `sierra.Renderer.render` and through "
           "`sierra-bench facade` (facade::SceneRenderer) in alternating rounds; medians "
           "(PYTHONPATH=build/python).",
           {"python_render": ["python3", "python/bench/render_bench.py", "--bench",
                              "{apps}/sierra-bench", "--json", "{json}"]},
           python_table, optional=True),
    Figure("video", "The 1080p orbit to mp4",
           "48 frames of the default orbit at 1920x1080 without MSAA, encoded to H.264 at the "
           "default quality (libx264, crf 23, preset veryfast) as they are rendered, against "
           "`sierra-bench frames` drawing the same frames; the two programs take turns, 3 rounds.",
           {"video_mp4": ["python3", "scripts/video_bench.py", "{apps}", "{out}", "{json}"]},
           video_table,
           after="Encoding runs on the render thread; libx264's own frame threads overlap it with "
                 "the next frame's rendering."),
    Figure("layers", "Drapes, vector layers and map furniture",
           "One 1920x1080 frame of a 2049² fractal (SBT, τ = 1 px, no MSAA, the default view), "
           "plain and with each layer, side by side in one run, medians of 7 (a frame's spread on "
           "this machine is about 2%); then the peak resident "
           "set size of `sierra-render` drawing one frame with a 16384² RGB orthophoto (streamed "
           "into its texture, which llvmpipe keeps in the process: 1.33 GiB with its mips) and "
           "without it.",
           {"layers": [MICRO[0], "--benchmark_repetitions=7"] + MICRO[2:] +
                      ["--benchmark_filter=^BM_DrapeFrame/"],
            "drape_rss": ["python3", "scripts/drape_rss.py", "{apps}", "{out}", "{json}"]},
           layers_table,
           after="Targets: a drape at most 1.15x the plain frame; one million vector vertices at "
                 "most 1.5x; the 16384² orthophoto within 2 GiB of peak RSS."),
    Figure("tiled", "Tiled terrain",
           "Refinement over tiles against the in-memory path: 48 views of the moving orbit over "
           "the rough 2049² fractal, one thread, every tile resident, the 99th percentile of single "
           "refinements. Then a fractal made by `scripts/make-large-terrain.py`, built into a tile "
           "file, flown over for 20 s without GL and drawn once (`scripts/tiled_figures.py`).",
           {"tiled_refine": MICRO + ["--benchmark_filter=^BM_TiledRefine/"],
            "tiled_flight": ["python3", "scripts/tiled_figures.py", "{apps}", "{out}", "{json}"]},
           tiled_table,
           after="Target: tiled p99 at most 1.5x the in-memory p99. The tiled walk has no view "
                 "keys, from which the in-memory walk decides most splits. A 65537² terrain is "
                 "the script's default size (8.6 GB, 26 minutes to write): too large for this "
                 "page's routine run."),
    Figure("capture", "Capture",
           "The orbit's frames at 1920x1080 written to files against the frame loop that renders "
           "and reads them back, each program's whole run by the wall clock, interleaved, medians of "
           "5; encoders run on the cores the render leaves (hardware threads less one). Below, one "
           "1080p frame's encode on one thread (`BM_Encode*`, a synthetic shaded fractal frame).",
           {"capture": ["python3", "scripts/capture_timing.py", "--apps", "{apps}", "--frames", "48", "--size", "1920x1080",
                        "--repeat", "5", "--json", "{json}"],
            "encode": MICRO + ["--benchmark_filter=^BM_Encode"]},
           capture_table),
]


# ---------------------------------------------------------------- output

def shown(command, folder):
    """The command as a reader would type it: program names without the build folder,
    the JSON path relative to the output folder."""
    words = [w.replace("{json}", "FILE.json").replace("{out}/", "").replace("{apps}", "build/apps")
             .replace("{out}", ".") for w in command]
    return shlex.join(words)


def markdown_table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(lines)


def present(figure, data):
    """Whether every run of the figure produced data (benchmarks included)."""
    for run in figure.runs:
        d = data.get(run)
        if d is None or ("benchmarks" in d and not d["benchmarks"]):
            return False
    return True


def tables(folder):
    data = {}
    for figure in FIGURES:
        for run in figure.runs:
            path = os.path.join(folder, run + ".json")
            if os.path.exists(path) and os.path.getsize(path) > 0:
                with open(path) as fh:
                    data[run] = json.load(fh)
    machine = {}
    path = os.path.join(folder, "machine.json")
    if os.path.exists(path):
        with open(path) as fh:
            machine = json.load(fh)
    renderer = next((d["renderer"] for d in data.values() if isinstance(d, dict) and "renderer" in d), "unknown")

    out = ["# Performance", "",
           "<!-- Generated by scripts/measure.sh (scripts/perf_tables.py): edit those, not this file. -->",
           "",
           "Measured by `scripts/measure.sh`, which builds the programs, runs each command below and "
           "writes its JSON report to `build/perf/`; `scripts/perf_tables.py` turns the reports into "
           "this page. Programs are in `build/apps/`; `FILE.json` is the run's report.",
           "",
           f"**Machine:** {machine.get('cpu', 'unknown CPU')}, {machine.get('cores', '?')} cores, "
           f"GL renderer {renderer}.",
           "",
           "Figures from a shared machine scatter from run to run by several percent, both ways: compare "
           "ratios taken in one run, and medians.", ""]
    missing = []
    for figure in FIGURES:
        if not present(figure, data):
            if figure.optional:
                missing.append(figure.title)
                continue
            raise SystemExit(f"perf_tables: no data for figure '{figure.name}' "
                             f"(runs: {', '.join(figure.runs)}) in {folder}")
        header, rows = figure.table(data)
        out += [f"## {figure.title}", "", figure.note, "", "```"]
        out += [shown(command, folder) for command in figure.runs.values()]
        out += ["```", "", markdown_table(header, rows), ""]
        if figure.after:
            out += [figure.after, ""]
    if missing:
        out += ["Not measured in this build (its benchmarks are missing): " + ", ".join(missing) + ".", ""]
    return "\n".join(out)


def main(argv):
    if len(argv) >= 2 and argv[1] == "runs":
        for figure in FIGURES:
            for run, command in figure.runs.items():
                print(f"{run}\t{'1' if figure.optional else '0'}\t{shlex.join(command)}")
        return 0
    if len(argv) in (3, 4) and argv[1] == "tables":
        text = tables(argv[2])
        if len(argv) == 4:
            tmp = argv[3] + ".tmp"
            with open(tmp, "w") as fh:
                fh.write(text)
            os.replace(tmp, argv[3])
        else:
            sys.stdout.write(text)
        return 0
    sys.stderr.write(__doc__)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
