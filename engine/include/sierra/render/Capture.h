#pragma once
// Frame capture to image files and image comparison.

#include <sierra/gpu/ReadBack.h>

#include <string>

namespace sierra::render {

// Writes an RGBA8 image as an RGB PNG (or RGBA with `alpha`). Written to a
// temporary name in the same directory, then renamed: a failed write never
// leaves a half file. Creates the parent directory if needed.
void writePng(const std::string& path, const gpu::Image& image, bool alpha = false);

// Reads a PNG as RGBA8; throws sierra::Error if it cannot.
gpu::Image readPng(const std::string& path);

// "frame_0007.png" style names for sequences: base "out/frame.png", index 7,
// count 100 -> "out/frame_0007.png".
std::string sequencePath(const std::string& base, int index);

struct ImageDifference {
    double psnr = 0.0;            // dB over RGB; infinity for identical images
    double differingShare = 0.0;  // share of pixels whose RGB differs by more than the threshold
    double meanAbsolute = 0.0;    // mean absolute channel difference, 0..255
};

// Compares two images of equal size; `threshold` is the largest per-channel
// difference (0..255) that still counts as equal for differingShare.
ImageDifference compareImages(const gpu::Image& a, const gpu::Image& b, int threshold = 8);

}  // namespace sierra::render
