#pragma once
// A self-contained 16-bit PNG encoder for the heightfield writer; files are
// read and written through sierra/core/Files.h.

#include <sierra/core/Files.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace sierra::terrain {

// A complete PNG file: 16-bit greyscale (colour type 0, bit depth 16), width x
// height samples row-major (row 0 first), no filtering, zlib "stored" deflate
// blocks (uncompressed: needs no zlib, files are ~2 bytes per sample).
std::vector<uint8_t> encodePngGrey16(int width, int height, std::span<const uint16_t> samples);

}  // namespace sierra::terrain
