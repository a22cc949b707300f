#!/usr/bin/env python3
"""sierra-render --out NAME.mp4|.webm|.gif: the videos, read back by Debian's ffprobe and ffmpeg.

- A 24-frame orbit to mp4: ffprobe finds h264, the frame size, 24 frames at 30
  fps; every frame ffmpeg decodes matches the PNG frame of the same run with a
  PSNR of at least 38 dB (sierra_image_compare, render::compareImages).
- The same orbit in two slices (--frames 0:11 and 12:23) writes two segments
  that `ffmpeg -f concat -c copy` joins into the 24 frames, in order.
- webm is VP9 and gif is GIF; --fps sets the rate.
- Bad options fail with one message before any work and leave no file: an
  unknown codec, --fps 0, a codec this libavcodec lacks, an odd frame size,
  a codec the container cannot hold, --crf with --bitrate.
Exit 77 (CTest: skipped) with a note when ffprobe or ffmpeg is missing.

Usage: render_video.py SIERRA_RENDER SIERRA_IMAGE_COMPARE WORK_DIR
"""

import json
import os
import shutil
import subprocess
import sys

SKIP = 77
for tool in ("ffprobe", "ffmpeg"):
    if shutil.which(tool) is None:
        print(f"SKIPPED: {tool} is not installed; apt-get install ffmpeg")
        sys.exit(SKIP)

RENDER, COMPARE, WORK = (os.path.abspath(a) for a in sys.argv[1:4])
shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)
os.chdir(WORK)
failures = []
# 720p: the PSNR of yuv420p at the default quality grows with the frame size
# (its chroma is half the resolution, and x264 spends more bits per detail on
# small frames), and 720p is the smallest size videos are commonly made at.
W, H, FRAMES = 1280, 720, 24
# A small generated terrain and an orbit: seconds on llvmpipe.
SCENE = ["--generate", "129", "--path", "orbit", "--no-debug"]
MAIN = SCENE + ["--size", f"{W}x{H}"]
SMALL = SCENE + ["--size", "320x180"]


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL:", what)


def run(args, expect_ok=True):
    p = subprocess.run(args, capture_output=True, text=True, timeout=600)
    if expect_ok and p.returncode != 0:
        sys.exit(f"{' '.join(args)}: exit {p.returncode}\n{p.stdout}\n{p.stderr}")
    return p


def probe(path):
    """codec, width, height, frames counted by decoding, rate as a fraction string."""
    out = run(["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0",
               "-show_entries", "stream=codec_name,width,height,nb_read_frames,r_frame_rate,"
               "avg_frame_rate", "-of", "json", path]).stdout
    s = json.loads(out)["streams"][0]
    return s["codec_name"], s["width"], s["height"], int(s["nb_read_frames"]), s["avg_frame_rate"]


def psnr(a, b):
    out = run([COMPARE, a, b]).stdout
    return float(dict(line.split() for line in out.splitlines())["psnr"])


def decode(video, folder):
    """Every frame as folder/d_0000.png, ...; the sorted list."""
    os.makedirs(folder)
    run(["ffmpeg", "-v", "error", "-i", video, "-start_number", "0",
         os.path.join(folder, "d_%04d.png")])
    return sorted(os.path.join(folder, f) for f in os.listdir(folder))


# The orbit to mp4 and to PNG frames.
run([RENDER, *MAIN, "--frames", str(FRAMES), "--out", "fly.mp4"])
run([RENDER, *MAIN, "--frames", str(FRAMES), "--out", "png/f.png"])
check(os.path.exists("fly.mp4") and not [f for f in os.listdir(".") if ".tmp-" in f],
      "fly.mp4 written, no temporary file left")
codec, w, h, n, rate = probe("fly.mp4")
check((codec, w, h, n, rate) == ("h264", W, H, FRAMES, "30/1"),
      f"fly.mp4: h264 {W}x{H}, {FRAMES} frames at 30/1 fps; ffprobe: {codec} {w}x{h}, {n} at {rate}")
decoded = decode("fly.mp4", "decoded")
check(len(decoded) == FRAMES, f"ffmpeg decodes {FRAMES} frames, got {len(decoded)}")
worst = min((psnr(d, f"png/f_{k:04d}.png"), k) for k, d in enumerate(decoded))
print(f"mp4 against PNG: lowest PSNR {worst[0]:.2f} dB (frame {worst[1]})")
check(worst[0] >= 38.0, f"every decoded frame within 38 dB of its PNG, frame {worst[1]}: {worst[0]:.2f}")

# Two slices, joined.
os.makedirs("seg")
for a, b in ((0, 11), (12, 23)):
    run([RENDER, *MAIN, "--frame-count", str(FRAMES), "--frames", f"{a}:{b}",
         "--out", "seg/fly.mp4"])
segments = sorted(os.listdir("seg"))
check(segments == ["fly_0000.mp4", "fly_0012.mp4"], f"segments named by first frame: {segments}")
with open("list.txt", "w") as f:
    f.writelines(f"file 'seg/{s}'\n" for s in segments)
run(["ffmpeg", "-v", "error", "-f", "concat", "-safe", "0", "-i", "list.txt", "-c", "copy",
     "joined.mp4"])
codec, w, h, n, rate = probe("joined.mp4")
check((codec, n) == ("h264", FRAMES), f"joined.mp4: {FRAMES} h264 frames, got {n} {codec}")
joined = decode("joined.mp4", "joined")
if len(joined) == FRAMES:
    for k in (0, 11, 12, 23):
        value = psnr(joined[k], f"png/f_{k:04d}.png")
        check(value >= 38.0, f"joined frame {k} is frame {k} of the run ({value:.2f} dB)")

# Other containers and rates.
run([RENDER, *SMALL, "--frames", "6", "--fps", "24", "--out", "fly.webm"])
codec, w, h, n, rate = probe("fly.webm")
check((codec, w, h, n, rate) == ("vp9", 320, 180, 6, "24/1"),
      f"fly.webm: vp9 320x180, 6 frames at 24/1; got {codec} {w}x{h}, {n} at {rate}")
run([RENDER, *SCENE, "--frames", "6", "--size", "161x91", "--out", "fly.gif"])
codec, w, h, n, rate = probe("fly.gif")
check((codec, w, h, n) == ("gif", 161, 91, 6),
      f"fly.gif: gif 161x91 (odd sizes are fine), 6 frames; got {codec} {w}x{h}, {n}")

# Bad options: exit 2, one message, no file.
missing = next((e for e in ("libkvazaar", "libopenh264", "av1_nvenc")
                if f" {e} " not in run(["ffmpeg", "-hide_banner", "-encoders"]).stdout), None)
bad = [
    (["--video-codec", "h263"], "unknown video codec 'h263'"),
    (["--fps", "0"], "output.fps (--fps) must be 1..1000 frames per second, got 0"),
    (["--fps", "-3"], "got -3"),
    (["--size", "321x181"], "needs an even frame size, got 321x181; use --size 320x180"),
    (["--crf", "20", "--bitrate", "4M"], "excludes output.bitrate (--bitrate)"),
    (["--out", "bad.webm", "--video-codec", "h264"], "WebM holds vp9 or av1 video, not h264"),
]
if missing:
    bad.append((["--out", "bad.mkv", "--video-codec", missing],
                f"libavcodec here has no encoder {missing}"))
for args, message in bad:
    out = args + ([] if "--out" in args else ["--out", "bad.mp4"])
    p = run([RENDER, *SMALL, "--frames", "3", *out], expect_ok=False)
    lines = [line for line in p.stderr.splitlines() if "error:" in line]
    check(p.returncode == 2, f"{args}: exit {p.returncode}, expected 2\n{p.stderr}")
    check(len(lines) == 1 and message in lines[0], f"{args}: one error naming '{message}':\n{p.stderr}")
leftovers = [f for f in os.listdir(".") if f.startswith("bad")]
check(not leftovers, f"no file from a refused run: {leftovers}")

if failures:
    sys.exit(f"{len(failures)} check(s) failed")
print("videos: h264/vp9/gif read back right; PNG match and segment join hold")
