#pragma once
// The GIF palette of a video (internal to render/Video.cpp): one global
// palette by median cut (Heckbert, "Color image quantization for frame buffer
// display", 1982) over the first frame's colours, and frames mapped to it
// with ordered (Bayer) dithering through a 32x32x32 lookup table.

#include <cstdint>
#include <vector>

namespace sierra::render::detail {

class GifPalette {
  public:
    // The palette of an RGBA8 frame (alpha ignored), at most `colours` entries (2..256).
    GifPalette(const uint8_t* rgba, int width, int height, int colours = 255);

    // Entries as 0xAARRGGBB (alpha 255), 256 of them (unused ones black): an
    // AV_PIX_FMT_PAL8 palette.
    const std::vector<uint32_t>& argb() const { return argb_; }
    int size() const { return size_; }

    // Palette indices of an RGBA8 frame into `out` (rows `stride` bytes apart).
    void map(const uint8_t* rgba, int width, int height, uint8_t* out, int stride) const;

  private:
    std::vector<uint32_t> argb_;
    std::vector<uint8_t> lut_;  // 15-bit colour (5 bits each, r high) -> palette index
    int size_ = 0;
};

}  // namespace sierra::render::detail
