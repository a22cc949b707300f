"""sierra-render on sequences of any length, stopped by a signal or a failed
write: python3 render_sequence_signals.py SIERRA_RENDER WORK_DIR.

- A billion-frame orbit writes its first frame at once: the path is
  evaluated per frame, not built up front.
- SIGTERM (and SIGINT) stop it after the frames in flight are written: exit
  128 + the signal, one message, every frame file complete, no temporary file.
- A frame that cannot be written stops the run with one message and exit 1;
  the frames written before it are complete.
"""
import os
import signal
import struct
import subprocess
import sys
import time
import zlib

# The first frame of this small scene takes well under a second on an idle
# machine; the limit leaves room for a loaded one (the tests run beside
# builds), and a path built up front (a billion cameras) takes many minutes.
FIRST_FRAME_LIMIT_S = 10.0
SCENE = ["--generate", "129", "--size", "320x180", "--msaa", "0", "--no-debug",
         "--path", "orbit"]


def check_png(path):
    """Fails unless `path` is a whole PNG: signature, chunks with good CRCs up
    to IEND, and image data that inflates to the rows the header promises."""
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", f"{path}: not a PNG"
    pos, idat, width, height, channels, ended = 8, b"", 0, 0, 0, False
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        crc, = struct.unpack(">I", data[pos + 8 + length:pos + 12 + length])
        assert zlib.crc32(kind + body) == crc, f"{path}: bad CRC in {kind}"
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", body[:10])
            channels = {2: 3, 6: 4, 0: 1}[colour]
        elif kind == b"IDAT":
            idat += body
        elif kind == b"IEND":
            ended = True
        pos += 12 + length
    assert ended, f"{path}: no IEND (cut short)"
    raw = zlib.decompress(idat)
    assert len(raw) == height * (width * channels + 1), f"{path}: short image data"


def listing(folder):
    return sorted(os.listdir(folder)) if os.path.isdir(folder) else []


def no_temporaries(folder):
    left = [n for n in listing(folder) if ".tmp-" in n]
    assert not left, f"temporary files left in {folder}: {left}"


def stop_with(render, work, sig):
    folder = os.path.join(work, f"seq_{sig.name}")
    first = os.path.join(folder, "f_0000.png")
    start = time.monotonic()
    proc = subprocess.Popen([render] + SCENE + ["--frames", "1000000000",
                                                "--out", os.path.join(folder, "f.png")],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        while not os.path.exists(first):
            if proc.poll() is not None:
                raise AssertionError(f"exited {proc.returncode} before frame 0:\n"
                                     + proc.stderr.read())
            if time.monotonic() - start > FIRST_FRAME_LIMIT_S:
                raise AssertionError(f"no frame 0 after {FIRST_FRAME_LIMIT_S} s")
            time.sleep(0.005)
        took = time.monotonic() - start
        print(f"{sig.name}: frame 0 of a billion-frame orbit after {took:.3f} s")
        # A few more frames, so frames are in flight when the signal comes.
        while len(listing(folder)) < 4 and time.monotonic() - start < 30:
            time.sleep(0.005)
        proc.send_signal(sig)
        _, err = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    assert proc.returncode == 128 + sig, f"exit {proc.returncode}, expected {128 + sig}:\n{err}"
    assert f"stopped by {sig.name}" in err, err
    assert "error" not in err, err
    no_temporaries(folder)
    frames = [n for n in listing(folder) if n.endswith(".png")]
    assert len(frames) >= 4, frames
    for name in frames:
        check_png(os.path.join(folder, name))
    # Frames 0..N, none missing: the message names the last one written.
    indices = sorted(int(n[2:-4]) for n in frames)
    assert indices == list(range(len(indices))), indices
    assert f"frames 0..{indices[-1]} of 0..999999999 written" in err, err


def failed_write(render, work):
    folder = os.path.join(work, "fails")
    os.makedirs(os.path.join(folder, "f_0003.png"))  # a directory where frame 3 goes
    proc = subprocess.run([render] + SCENE + ["--frames", "8", "--max-queued-frames", "2",
                                              "--out", os.path.join(folder, "f.png")],
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 1, f"exit {proc.returncode}:\n{proc.stderr}"
    errors = [line for line in proc.stderr.splitlines() if "error" in line]
    assert len(errors) == 1, proc.stderr
    assert errors[0].startswith("sierra-render: error: ") and "f_0003.png" in errors[0], errors
    no_temporaries(folder)
    for k in range(3):
        check_png(os.path.join(folder, f"f_{k:04d}.png"))
    print("failed write:", errors[0])


def main():
    render, work = sys.argv[1], sys.argv[-1]  # sierra-render, [sierra_image_compare,] folder
    os.makedirs(work, exist_ok=True)
    for entry in listing(work):
        subprocess.run(["rm", "-rf", os.path.join(work, entry)], check=True)
    stop_with(render, work, signal.SIGTERM)
    stop_with(render, work, signal.SIGINT)
    failed_write(render, work)
    print("ok")


if __name__ == "__main__":
    main()
