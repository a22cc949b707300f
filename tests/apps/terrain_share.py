"""Mean distance from the sky colour of a frame's terrain pixels, for the app
tests: python3 terrain_share.py FRAME.png DEPTH.npy R G B (sky in 0..255).
The terrain is where the depth (float32 .npy, NaN = none) is a number; the
distance is the sum of the RGB differences. Prints the mean and the count."""
import math
import struct
import sys
import zlib


def read_png(path):
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat, width, height, channels = 8, b"", 0, 0, 0
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", body[:10])
            assert depth == 8, "8-bit PNGs only"
            channels = {2: 3, 6: 4, 0: 1}[colour]
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, prev = [], bytearray(stride)
    for y in range(height):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):
            a = line[x - channels] if x >= channels else 0
            b = prev[x]
            c = prev[x - channels] if x >= channels else 0
            if f == 1:
                line[x] = (line[x] + a) & 255
            elif f == 2:
                line[x] = (line[x] + b) & 255
            elif f == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    return width, height, channels, rows


def read_npy(path):
    data = open(path, "rb").read()
    header_len = struct.unpack("<H", data[8:10])[0]
    start = 10 + header_len
    count = (len(data) - start) // 4
    return struct.unpack("<%df" % count, data[start:start + 4 * count])


width, height, channels, rows = read_png(sys.argv[1])
depth = read_npy(sys.argv[2])
sky = [float(v) for v in sys.argv[3:6]]
total, count = 0.0, 0
for y in range(height):
    for x in range(width):
        if math.isnan(depth[y * width + x]):
            continue
        p = rows[y][x * channels:x * channels + 3]
        total += sum(abs(p[c] - sky[c]) for c in range(3))
        count += 1
print("%.2f %d" % (total / max(count, 1), count))
