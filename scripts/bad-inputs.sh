#!/usr/bin/env bash
# The bad-input table: runs Sierra's programs on hostile and broken inputs and
# prints, per row, the exit code, the message, the wall time, the peak memory
# (maximum resident set) and whether an output file was left behind.
#
#   scripts/bad-inputs.sh [BUILD_DIR]        (default build/; markdown on stdout)
#
# Every row must exit non-zero with one message and leave no output, except the
# rows marked "warns", which render and must say why on stderr, and "renders",
# input within the documented limits that must render (its cost is the figure).
set -uo pipefail
cd "$(dirname "$0")/.."
build=$(realpath "${1:-build}")
render=$build/apps/sierra-render bench=$build/apps/sierra-bench gen=$build/apps/sierra-gen
for p in "$render" "$bench" "$gen"; do
  [[ -x $p ]] || { echo "bad-inputs.sh: $p not built (cmake --build $build)" >&2; exit 1; }
done
work=$(mktemp -d /tmp/sierra-bad-inputs.XXXXXX)
trap 'rm -rf "$work"' EXIT
cd "$work"

python3 - <<'PY'
import struct, zlib, os
def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
def png(w, h, depth, colour, raw, crc_flip=False, idat_len=None):
    ihdr = chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, depth, colour, 0, 0, 0))
    idat = chunk(b"IDAT", zlib.compress(raw, 9))
    if crc_flip:
        idat = idat[:-1] + bytes([idat[-1] ^ 0x40])
    if idat_len is not None:
        idat = struct.pack(">I", idat_len) + idat[4:]
    return b"\x89PNG\r\n\x1a\n" + ihdr + idat + chunk(b"IEND", b"")
grey = b"".join(b"\0" + bytes(range(64)) for _ in range(64))
open("photo.png", "wb").write(png(64, 64, 8, 2, b"".join(b"\0" + bytes(64 * 3) for _ in range(64))))
open("one.png", "wb").write(png(1, 1, 8, 0, b"\0\x07"))
open("strip.png", "wb").write(png(1000, 3, 8, 0, b"".join(b"\0" + bytes(1000) for _ in range(3))))
open("crc.png", "wb").write(png(64, 64, 8, 0, grey, crc_flip=True))
open("idat1g.png", "wb").write(png(64, 64, 8, 0, grey, idat_len=1 << 30))
open("zeros16384.png", "wb").write(png(16384, 16384, 8, 0, b"".join(b"\0" + bytes(16384) for _ in range(16384))))
open("text.png", "w").write("this is not a png at all")
open("strip16385.pgm", "wb").write(b"P5 16385 1 255\n" + bytes(16385))
open("strip65537.pgm", "wb").write(b"P5 65537 2 255\n" + bytes(1024))
open("wide.r16", "wb").write(bytes(20000 * 2 * 2))
open("odd.r16", "wb").write(bytes(1001))
hdr = "{'descr': '<f4', 'fortran_order': False, 'shape': (2, 2), }"
hdr += " " * ((64 - (10 + len(hdr) + 1) % 64) % 64) + "\n"
open("nan.npy", "wb").write(b"\x93NUMPY\x01\x00" + struct.pack("<H", len(hdr)) + hdr.encode()
                           + struct.pack("<4f", 1, float("nan"), 2, 3))
open("unknown_key.json", "w").write('{"terrain": {"generate": 65}, "camra": {}}')
open("wrong_type.json", "w").write('{"lod": {"tau": "fine"}}')
open("zonemap_text.png", "w").write("not a zone map")
open("palette_bad.json", "w").write('{"surfaces": 3}')
PY
mkfifo fifo.png
ln -s /dev/zero zero.npy
echo "a file where a directory is needed" > blocker
mkfifo out_fifo.png
echo "kept" > kept.png
ln -s kept.png out_link.png

# row LABEL EXPECT OUTPUT COMMAND...: EXPECT is "fails" or "warns".
row() {
  local label=$1 expect=$2 output=$3
  shift 3
  # Only a regular file this script's own rows wrote is removed; a FIFO or a
  # link placed as a target stays, and must still be one afterwards.
  [[ -f $output && ! -L $output ]] && rm -f "$output"
  local start end rc
  start=$(date +%s.%N)
  timeout 120 /usr/bin/time -o time.txt -f "%M" "$@" >stdout.txt 2>stderr.txt
  rc=$?
  end=$(date +%s.%N)
  local kib message left=no verdict=ok
  kib=$(tail -1 time.txt 2>/dev/null)
  message=$(grep -v '^Command exited' stderr.txt | grep -m1 -E 'error|warning' || head -1 stderr.txt)
  if [[ -p $output || -L $output ]]; then
    [[ -p out_fifo.png && -L out_link.png ]] || left="target replaced"
  elif [[ -e $output ]]; then
    left=yes
  fi
  if [[ $expect == fails ]]; then
    [[ $rc -ne 0 && $rc -lt 124 && $left == no && -n $message ]] || verdict=WRONG
  elif [[ $expect == warns ]]; then
    [[ $rc -eq 0 && $message == *warning* ]] || verdict=WRONG
  else
    [[ $rc -eq 0 ]] || verdict=WRONG
  fi
  printf '| %s | %s | %.2f s | %s MiB | %s | %s | `%s` |\n' "$label" "$rc" "$(echo "$end - $start" | bc)" \
         "$(( (kib + 1023) / 1024 ))" "$left" "$verdict" "${message//|/\\|}"
}

echo '| input | exit | time | peak RSS | output left | verdict | message |'
echo '|---|---|---|---|---|---|---|'
R=("$render" --no-debug)
row "RGB photo as --heightmap" fails f.png "${R[@]}" --heightmap photo.png --out f.png
row "1x1 PNG" fails f.png "${R[@]}" --heightmap one.png --out f.png
row "1000x3 strip (padded 350x)" warns f.png "${R[@]}" --heightmap strip.png --out f.png --size 64x36
row "missing file" fails f.png "${R[@]}" --heightmap nope.png --out f.png
row "text file named .png" fails f.png "${R[@]}" --heightmap text.png --out f.png
row "unknown option" fails f.png "${R[@]}" --bogus --out f.png
row "PNG with a corrupt IDAT CRC" fails f.png "${R[@]}" --heightmap crc.png --out f.png
row "PNG IDAT length claiming 1 GiB" fails f.png "${R[@]}" --heightmap idat1g.png --out f.png
row "16384² all-zero PNG ($(( $(stat -c %s zeros16384.png) / 1024 )) KiB)" fails f.png "${R[@]}" --heightmap zeros16384.png --out f.png --size 64x36
row "16385x1 PGM header (16 KiB)" fails f.png "${R[@]}" --heightmap strip16385.pgm --out f.png
row "65537x2 PGM header" fails f.png "${R[@]}" --heightmap strip65537.pgm --out f.png
row "FIFO as --heightmap" fails f.png "${R[@]}" --heightmap fifo.png --out f.png
row "symlink to /dev/zero as .npy" fails f.png "${R[@]}" --heightmap zero.npy --out f.png
row "NaN height in .npy" fails f.png "${R[@]}" --heightmap nan.npy --out f.png
row ".r16 of 1001 bytes, no size" fails f.png "${R[@]}" --heightmap odd.r16 --out f.png
row ".r16 20000x2 (pads past the limit)" fails f.png "${R[@]}" --heightmap wide.r16 --raw-size 20000x2 --out f.png --size 64x36
row "--out a FIFO" fails out_fifo.png "${R[@]}" --generate 65 --out out_fifo.png
row "--out a symlink" fails out_link.png "${R[@]}" --generate 65 --out out_link.png
row "--out under a file" fails blocker/f.png "${R[@]}" --generate 65 --out blocker/f.png
row "--debug-out under a file" fails f.png "$render" --generate 65 --out f.png --debug-out blocker/d.png
row "bench --json in a missing place" fails blocker/x.json "$bench" frames --generate 65 --size 64x36 --frames 2 --json blocker/x.json
row "SIERRA_THREADS=1000000000" warns f.png env SIERRA_THREADS=1000000000 "${R[@]}" --generate 65 --out f.png
row "--roughness 1e38" fails f.png "${R[@]}" --generate 65 --roughness 1e38 --out f.png
row "--tau -1" fails f.png "${R[@]}" --generate 65 --tau -1 --out f.png
row "--size 12by5" fails f.png "${R[@]}" --generate 65 --size 12by5 --out f.png
row "config with an unknown key" fails f.png "${R[@]}" --config unknown_key.json --out f.png
row "config with a wrong type" fails f.png "${R[@]}" --config wrong_type.json --out f.png
row "missing config" fails f.png "${R[@]}" --config none.json --out f.png
row "zone map that is not a PNG" fails f.png "${R[@]}" --generate 65 --zones zonemap_text.png --out f.png
row "palette with a wrong type" fails f.png "${R[@]}" --generate 65 --zones auto --palette palette_bad.json --out f.png
row "no EGL driver" fails f.png env __EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json "${R[@]}" --generate 65 --out f.png
row "sierra-gen map, missing file" fails m.png "$gen" map --heightmap nope.png --out m.png
