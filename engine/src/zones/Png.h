#pragma once
// PNG encoding shared by the zone maps and the tiles (stb, in memory).

#include <cstdint>
#include <vector>

namespace sierra::zones::detail {

// A PNG of 8-bit pixels with `channels` (3 = RGB, 4 = RGBA) per pixel.
std::vector<uint8_t> encodePng8(int width, int height, int channels, const uint8_t* pixels);

}  // namespace sierra::zones::detail
