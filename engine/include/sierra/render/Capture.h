#pragma once
// Frame capture to image files and image comparison. The encoders are plain
// functions of an image in memory, safe to call from any thread (FrameQueue's
// encoder threads call them).

#include <sierra/gpu/ReadBack.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace sierra::render {

// zlib's effort for a PNG: Fast is level 1 with the Sub filter (for frame
// sequences), Default level 6 and Best level 9, both with the filter chosen
// per row.
enum class PngCompression { Fast, Default, Best };

// How an image file is written; the format follows the file name (.jpg and
// .jpeg: JPEG, anything else: PNG).
struct ImageEncoding {
    PngCompression png = PngCompression::Fast;
    int jpegQuality = 90;  // 1..100
    bool alpha = false;    // PNG: RGBA instead of RGB; JPEG refuses it
};

// An RGBA8 image as an 8-bit RGB PNG (RGBA with `alpha`), through libspng.
// Throws sierra::Error for an empty or inconsistent image.
std::vector<uint8_t> encodePng(const gpu::Image& image, bool alpha = false,
                               PngCompression compression = PngCompression::Fast);
// A 16-bit grey PNG of `width` x `height` samples, rows top first.
std::vector<uint8_t> encodePngGrey16(int width, int height, std::span<const uint16_t> samples,
                                     PngCompression compression);
// An 8-bit grey PNG (masks, zone ids), rows top first.
std::vector<uint8_t> encodePngGrey8(int width, int height, std::span<const uint8_t> samples,
                                    PngCompression compression);
// An RGBA8 image as a baseline JPEG (alpha dropped), through libjpeg-turbo;
// `quality` 1..100.
std::vector<uint8_t> encodeJpeg(const gpu::Image& image, int quality = 90);

// The file's bytes for `path` (PNG or JPEG by its extension; JPEG with
// encoding.alpha is a sierra::Error).
std::vector<uint8_t> encodeImage(const std::string& path, const gpu::Image& image,
                                 const ImageEncoding& encoding);

// Writes the image to `path` in the format its name says. Written to a
// temporary name in the same directory, then renamed: a failed write never
// leaves a half file. Creates the parent directory if needed.
void writeImage(const std::string& path, const gpu::Image& image, const ImageEncoding& encoding);

// writeImage as an RGB PNG (RGBA with `alpha`), fast compression.
void writePng(const std::string& path, const gpu::Image& image, bool alpha = false);

// Reads a PNG as RGBA8; throws sierra::Error if it cannot.
gpu::Image readPng(const std::string& path);

// "frame_0007.png" style names for sequences: base "out/frame.png", index 7
// -> "out/frame_0007.png" (at least four digits; more for indices past 9999).
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
