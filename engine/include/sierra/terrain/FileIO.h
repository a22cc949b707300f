#pragma once
// Whole-file reads, all-or-nothing writes and a self-contained 16-bit PNG
// encoder, shared by the heightfield and colour-map writers.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace sierra::terrain {

// The bytes of `path`. Throws sierra::Error "cannot open PATH: <reason>" (the
// system's reason, e.g. "No such file or directory") or "cannot read PATH: ...".
std::vector<uint8_t> readFileBytes(const std::string& path);

// Writes `bytes` to "PATH.tmp-XXXXXXXX" in the same directory, then renames it
// to `path`, so readers see either the old file or the complete new one. On any
// failure the temporary file is removed and sierra::Error names the path.
void writeFileAtomic(const std::string& path, std::span<const uint8_t> bytes);

// A complete PNG file: 16-bit greyscale (colour type 0, bit depth 16), width x
// height samples row-major (row 0 first), no filtering, zlib "stored" deflate
// blocks (uncompressed: needs no zlib, files are ~2 bytes per sample).
std::vector<uint8_t> encodePngGrey16(int width, int height, std::span<const uint16_t> samples);

}  // namespace sierra::terrain
