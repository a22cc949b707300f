#!/usr/bin/env bash
# Fuzzes every Sierra loader with libFuzzer under ASan + UBSan and prints, per
# target, the executions, the time and the findings (crash-*, leak-*, oom-*,
# timeout-* files libFuzzer leaves in build-fuzz/findings/TARGET).
#
#   scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]     (default 120 s, every target)
#
# Exits 1 when any target has a finding (a new file in its findings folder or
# libFuzzer stopping with an error), after printing each reproducer's path and
# the command that replays it; .ci/run's fuzz stage relies on that status.
#
# Needs clang, libclang-rt-14-dev (libFuzzer's runtime) and python3 (the
# seeds) on Debian 12: run as root it installs them when missing, as scripts/setup.sh does for its
# packages; otherwise it prints the apt-get line and exits 1. Builds into
# build-fuzz/; seeds come from small valid files made here, the corpus grows in
# build-fuzz/corpus/TARGET.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-120}
shift || true
targets=("$@")
[[ ${#targets[@]} -gt 0 ]] || targets=(png pgm npy npz r16 r32 hgt cpt palette scene zonemap obj vector drape camera tilefile)

packages=(clang libclang-rt-14-dev python3)
missing=()
if command -v dpkg-query >/dev/null; then
  for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
elif ! command -v clang++ >/dev/null; then
  missing=("${packages[@]}")
fi
if ((${#missing[@]})); then
  if [ "$(id -u)" -eq 0 ] && command -v apt-get >/dev/null; then
    echo "fuzz.sh: installing ${missing[*]}"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  else
    echo "fuzz.sh: missing packages. Install them with:" >&2
    echo "  sudo apt-get install -y ${missing[*]}" >&2
    exit 1
  fi
fi
built=$SECONDS
mkdir -p build-fuzz
if ! { cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
         -DSIERRA_FUZZ=ON -DSIERRA_BUILD_TESTS=OFF -DSIERRA_WITH_GDAL=ON &&
       cmake --build build-fuzz -j"$(nproc)" --target $(printf 'fuzz_%s ' "${targets[@]}"); } \
     >build-fuzz/build.log 2>&1; then
  tail -n 30 build-fuzz/build.log >&2
  echo "fuzz.sh: the build failed (build-fuzz/build.log)" >&2
  exit 1
fi
echo "fuzz.sh: built ${#targets[@]} targets in $((SECONDS - built)) s"

# Seeds: one or two small valid inputs per target.
seeds=build-fuzz/seeds
rm -rf "$seeds"
python3 - "$seeds" <<'PY'
import json, os, struct, sys, zlib, io, zipfile
root = sys.argv[1]
def put(target, name, data):
    os.makedirs(os.path.join(root, target), exist_ok=True)
    with open(os.path.join(root, target, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())
def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
def png(w, h, depth, colour, rows, interlace=0):
    ihdr = struct.pack(">IIBBBBB", w, h, depth, colour, 0, 0, interlace)
    raw = b"".join(b"\0" + r for r in rows)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b"")
put("png", "grey8.png", png(4, 3, 8, 0, [bytes([10 * i + j for i in range(4)]) for j in range(3)]))
put("png", "grey16.png", png(3, 3, 16, 0, [struct.pack(">3H", 1, 300, 65535)] * 3))
put("png", "rgb8.png", png(2, 2, 8, 2, [bytes([1, 2, 3, 4, 5, 6])] * 2))
put("zonemap", "rgb8.png", png(3, 2, 8, 2, [bytes([255, 0, 0, 0, 0, 0, 0, 255, 0])] * 2))
put("zonemap", "palette.png", png(2, 2, 8, 2, [bytes([0, 0, 255, 9, 9, 9])] * 2))
put("pgm", "p2.pgm", "P2\n# comment\n3 2\n255\n0 1 2\n3 4 255\n")
put("pgm", "p5.pgm", b"P5 2 2 65535\n" + struct.pack(">4H", 0, 1, 2, 65535))
def npy(descr, shape, payload):
    header = "{'descr': '%s', 'fortran_order': False, 'shape': (%d, %d), }" % (descr, *shape)
    header += " " * ((64 - (10 + len(header) + 1) % 64) % 64) + "\n"
    return b"\x93NUMPY\x01\x00" + struct.pack("<H", len(header)) + header.encode() + payload
f4 = npy("<f4", (2, 3), struct.pack("<6f", 0, 1, 2, 3, 4, 5))
put("npy", "f4.npy", f4)
put("npy", "u2.npy", npy("<u2", (2, 2), struct.pack("<4H", 0, 1, 2, 3)))
for method, name in ((zipfile.ZIP_STORED, "stored.npz"), (zipfile.ZIP_DEFLATED, "deflated.npz")):
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", method) as z:
        z.writestr("elevation.npy", f4)
    put("npz", name, buf.getvalue())
# Georeferenced archives: scalars dx, dy and bounds, or latitude and longitude lists.
def scalar(value):
    header = "{'descr': '<f8', 'fortran_order': False, 'shape': (), }"
    header += " " * ((64 - (10 + len(header) + 1) % 64) % 64) + "\n"
    return b"\x93NUMPY\x01\x00" + struct.pack("<H", len(header)) + header.encode() + struct.pack("<d", value)
def vector(values):
    header = "{'descr': '<f4', 'fortran_order': False, 'shape': (%d,), }" % len(values)
    header += " " * ((64 - (10 + len(header) + 1) % 64) % 64) + "\n"
    return b"\x93NUMPY\x01\x00" + struct.pack("<H", len(header)) + header.encode() + struct.pack("<%df" % len(values), *values)
buf = io.BytesIO()
with zipfile.ZipFile(buf, "w") as z:
    z.writestr("elevation.npy", f4)
    for k, v in {"dx": 0.01, "dy": 0.01, "xmin": 10.0, "xmax": 10.03, "ymin": 45.02, "ymax": 45.0}.items():
        z.writestr(k + ".npy", scalar(v))
put("npz", "degrees.npz", buf.getvalue())
buf = io.BytesIO()
with zipfile.ZipFile(buf, "w") as z:
    z.writestr("topo.npy", f4)
    z.writestr("latitude.npy", vector([48.0, 48.5]))
    z.writestr("longitude.npy", vector([234.0, 234.2, 234.4]))
put("npz", "latlon.npz", buf.getvalue())
put("r16", "4x4.r16", struct.pack("<16H", *range(16)))
put("r32", "3x3.r32", struct.pack("<9f", *range(9)))
put("hgt", "srtm3.hgt", struct.pack(">h", -32768) + b"\0\x10" * (1201 * 1201 - 1))
put("cpt", "ramp.cpt", "# elevation\n0 0/0/255 100 0/255/0\n100 0/255/0 1000 255 255 255\nB 0/0/0\nF 255/255/255\nN 128/128/128\n")
put("palette", "palette.json", json.dumps({"borderline": "#000000", "surfaces": [
    {"name": "water", "colour": "#0000ff", "tile": "water.png"},
    {"name": "grass", "colour": "#00ff00", "tile": "grass.png", "band": 8}]}))
put("scene", "scene.json", json.dumps({"terrain": {"generate": 257, "seed": 3, "sea_level": "auto"},
    "camera": {"azimuth": 30.0, "elevation": 40.0, "fov": 45.0, "projection": "perspective"},
    "path": {"type": "orbit", "frames": 3, "keyframes": []},
    "lighting": {"sun_azimuth": 232.0, "fog": None, "sky": [0.6, 0.7, 0.8]},
    "lod": {"mode": "sbt", "tau": 2.0, "geomorph": True}, "output": {"width": 64, "height": 48, "msaa": 4}}))
# The OBJ reader: what sierra-tin writes (mtllib, usemtl, v, vt, f i/t), the
# other corner forms, negative indices and comments; an MTL beside it.
put("obj", "tin.obj", "# sierra-tin\nmtllib tin.mtl\nv 0 1.5 0\nv 1 2 0\nv 0 0.5 1\nv 1 1 1\n"
    "vt 0 0\nvt 0.5 0\nvt 0 0.5\nvt 0.5 0.5\nusemtl zone_1\nf 1/1 3/3 2/2\n"
    "usemtl band_1_2\nf 2/2 3/3 4/4\n")
put("obj", "corners.obj", "v 0 0 0\nv 1 0 0\nv 0 0 1\nvn 0 1 0\nvt 0 0\n"
    "f 1//1 3//1 2//1\nf -3/-1/1 -1/-1/1 -2/-1/1\ng ground\no mesh\ns off\n")
put("obj", "tin.mtl", "newmtl zone_1\nKd 0.2 0.6 0.1\nmap_Kd tiles/grass.png\n"
    "newmtl band_1_2\nKd 0.4 0.4 0.2\n")
# Vector layers: GeoJSON of every geometry kind on the fuzz grid (10-11 E,
# 46.5-47 N), GPX and KML where GDAL reads them.
put("vector", "mixed.geojson", json.dumps({"type": "FeatureCollection", "features": [
    {"type": "Feature", "properties": {"name": "Hut"}, "geometry": {"type": "Point", "coordinates": [10.2, 46.9]}},
    {"type": "Feature", "properties": {"name": "River"}, "geometry": {"type": "MultiLineString",
        "coordinates": [[[10.0, 47.0], [10.5, 46.7]], [[10.6, 46.6], [12.0, 46.6]]]}},
    {"type": "Feature", "properties": {}, "geometry": {"type": "Polygon", "coordinates": [
        [[10.1, 46.9], [10.3, 46.9], [10.3, 46.8], [10.1, 46.9]], [[10.2, 46.88], [10.25, 46.88], [10.22, 46.85], [10.2, 46.88]]]}},
    {"type": "Feature", "properties": {}, "geometry": {"type": "GeometryCollection", "geometries": [
        {"type": "Point", "coordinates": [10.4, 46.7]}, {"type": "LineString", "coordinates": [[10.4, 46.7], [10.45, 46.72]]}]}}]}))
put("vector", "track.gpx", '<?xml version="1.0"?><gpx version="1.1" creator="sierra"><wpt lat="46.9" lon="10.2"><name>Hut</name></wpt>'
    '<trk><name>Track</name><trkseg><trkpt lat="46.9" lon="10.1"/><trkpt lat="46.8" lon="10.3"/></trkseg></trk></gpx>')
put("vector", "places.kml", '<?xml version="1.0"?><kml xmlns="http://www.opengis.net/kml/2.2"><Document>'
    '<Placemark><name>Peak</name><Point><coordinates>10.3,46.8,0</coordinates></Point></Placemark>'
    '<Placemark><LineString><coordinates>10.1,46.9 10.2,46.85</coordinates></LineString></Placemark></Document></kml>')
# Drapes: grey, grey + alpha, RGB and RGBA PNGs (stretched over the grid,
# having no georeference), 16 x 8 pixels.
for name, colour, channels in (("grey.png", 0, 1), ("grey_alpha.png", 4, 2), ("rgb.png", 2, 3), ("rgba.png", 6, 4)):
    put("drape", name, png(16, 8, 8, colour, [bytes((x * 16 + y * 32 + c * 80) % 256 for x in range(16) for c in range(channels)) for y in range(8)]))
# Cameras: one scene per path type and projection (fuzz_camera follows each to
# its matrices); the scene seed above as well.
cameras = {
    "still.json": {"camera": {"position": [300.0, 120.0, -40.0], "target": [128.0, 10.0, 128.0],
                              "fov": 30.0}},
    "angles.json": {"camera": {"azimuth": 90.0, "elevation": 89.9, "distance": 400.0},
                    "output": {"width": 640, "height": 360}},
    "ortho.json": {"camera": {"elevation": 90.0, "projection": "orthographic"}},
    "orbit.json": {"camera": {"target": [100.0, 0.0, 90.0], "distance": 250.0, "elevation": 10.0},
                   "path": {"type": "orbit", "frames": 12, "range": [3, 7]}},
    "flyover.json": {"camera": {"fov": 70.0}, "path": {"type": "flyover", "frames": 8}},
    "keys.json": {"path": {"type": "keyframes", "frames": 9, "keyframes": [
        {"time": 0.0, "position": [0.0, 80.0, 300.0], "target": [128.0, 0.0, 128.0]},
        {"time": 1.5, "position": [300.0, 60.0, 300.0], "target": [128.0, 20.0, 128.0]},
        {"time": 4.0, "position": [128.0, 200.0, -20.0], "target": [130.0, 0.0, 120.0]}]}},
}
for name, scene in cameras.items():
    put("camera", name, json.dumps(scene))
    put("scene", name, json.dumps(scene))
with open(os.path.join(root, "scene", "scene.json"), "rb") as f:
    put("camera", "scene.json", f.read())
PY

# Tile files: small ones of both height encodings, written by the main
# build's sierra-tile when there is one (.ci/run builds it first).
tile_app="${BUILD_DIR:-build}/apps/sierra-tile"
mkdir -p "$seeds/tilefile"
if [[ -x "$tile_app" ]]; then
  python3 - "$seeds/tilefile/grid.npy" <<'PY'
import struct, sys
w, h = 40, 33
header = "{'descr': '<f4', 'fortran_order': False, 'shape': (%d, %d), }" % (h, w)
header += " " * (63 - (10 + len(header)) % 64) + "\n"
body = b"".join(struct.pack("<f", ((i * 7 + j * 13) % 29) * 0.5) for j in range(h) for i in range(w))
with open(sys.argv[1], "wb") as f:
    f.write(b"\x93NUMPY\x01\x00" + struct.pack("<H", len(header)) + header.encode() + body)
PY
  "$tile_app" build "$seeds/tilefile/grid.npy" --tile-levels 3 --out "$seeds/tilefile/int16.sierra" >/dev/null 2>&1 || true
  "$tile_app" build "$seeds/tilefile/grid.npy" --tile-levels 2 --heights float --out "$seeds/tilefile/float.sierra" >/dev/null 2>&1 || true
  rm -f "$seeds/tilefile/grid.npy"
fi

# A finding: a new file in the target's findings folder (left there by this
# run; older ones are kept but not counted again) or libFuzzer stopping with
# an error status.
printf '%-9s %14s %8s %9s  %s\n' target executions seconds exec/s findings
failed=()
for t in "${targets[@]}"; do
  corpus=build-fuzz/corpus/$t findings=build-fuzz/findings/$t
  mkdir -p "$corpus" "$findings"
  log=build-fuzz/fuzz_$t.log
  stamp=build-fuzz/findings/.$t.start
  touch "$stamp"
  # -rss_limit_mb: the 2049^2 budget at 8 bytes a sample is 32 MiB; 2 GiB flags
  # any input that costs far more memory than its grid.
  status=0
  build-fuzz/fuzz/fuzz_$t "$corpus" "$seeds/$t" -max_total_time="$seconds" -rss_limit_mb=2048 \
      -max_len=65536 -timeout=10 -artifact_prefix="$findings/" -print_final_stats=1 >"$log" 2>&1 ||
    status=$?
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo 0)
  took=$(grep -o 'Done [0-9]* runs in [0-9]* second' "$log" | grep -o 'in [0-9]*' | grep -o '[0-9]*' || echo "$seconds")
  new=$(find "$findings" -type f -newer "$stamp")
  found=$(printf '%s' "$new" | grep -c . || true)
  printf '%-9s %14s %8s %9s  %s\n' "$t" "$runs" "$took" "$(( runs / (took > 0 ? took : 1) ))" "$found"
  if [[ $status -ne 0 || $found -gt 0 ]]; then
    failed+=("$t")
    for f in $new; do
      echo "fuzz.sh: $t: finding $f; replay: build-fuzz/fuzz/fuzz_$t $f" >&2
    done
    [[ $found -gt 0 ]] || echo "fuzz.sh: $t: libFuzzer exited with status $status; see $log" >&2
  fi
done
echo "logs: build-fuzz/fuzz_TARGET.log; findings: build-fuzz/findings/TARGET"
if ((${#failed[@]})); then
  echo "fuzz.sh: findings in ${failed[*]}" >&2
  exit 1
fi
