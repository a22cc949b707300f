#pragma once
// OpenEXR images of float data (dataset normals), written and read through
// the OpenEXR library. OpenEXR is confined to render/Exr.cpp.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace sierra::render {

// Bits per stored value: half (16-bit) or full (32-bit) IEEE floats.
enum class ExrPrecision { Half, Float };

struct ExrImage {
    int width = 0;
    int height = 0;
    std::vector<std::string> channels;  // names, in the order of `values`
    std::vector<float> values;  // width * height * channels, top row first, channels interleaved
    ExrPrecision precision = ExrPrecision::Float;  // of the first channel
};

// The bytes of a scanline EXR file (ZIP compression, lossless) of `image`:
// its channels, each stored at `image.precision`. NaN stays NaN. Throws
// sierra::Error for an empty or inconsistent image.
std::vector<uint8_t> encodeExr(const ExrImage& image);

// Reads an EXR file's channels (as floats, in the file's channel order, which
// OpenEXR keeps sorted by name). Throws sierra::Error naming the file when it
// cannot be read.
ExrImage readExr(const std::string& path);

}  // namespace sierra::render
