#pragma once
// Imagery drapes: an image (GeoTIFF, PNG, JPEG, and WebP or JPEG 2000 where
// GDAL has them; RGB or RGBA) resampled onto a heightfield's extent, ready to
// be a texture over the terrain.
//
// The result covers the grid's pixel corners exactly: texel column u of W
// spans sample columns from u W' / W - 0.5 to (u + 1) W' / W - 0.5 for a
// grid W' samples wide (rows likewise), so texture coordinate
// ((i + 0.5) / W', (j + 0.5) / H') is sample (i, j). Where the image does
// not reach, alpha is 0 and the surface beneath shows.
//
// Placement, in order of precedence:
// - bounds given: the image's corners at those bounds, in sample
//   coordinates or in the grid's reference system;
// - the image is georeferenced and so is the grid: warped from its system
//   into the grid's (GDAL's warper), clipped to the grid;
// - otherwise: stretched over the grid's extent (DrapeImage::stretched says
//   so, for the caller's warning).

#include <sierra/terrain/Vector.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace sierra::terrain {

enum class Resampling { Bilinear, Cubic };

struct DrapeBounds {
    enum class Units { Samples, Crs };
    Units units = Units::Samples;
    // The image's left, top, right and bottom edges: sample coordinates (i
    // for left and right, j for top and bottom; the grid's own corners are
    // -0.5 and W - 0.5), or the system's X and Y (top = the larger Y).
    double left = 0.0, top = 0.0, right = 0.0, bottom = 0.0;
};

struct DrapeOptions {
    std::optional<GridPlacement> placement;  // the grid's georeference, when it has one
    int width = 0, height = 0;               // the grid's size in samples (without placement)
    std::optional<DrapeBounds> bounds;
    Resampling resampling = Resampling::Bilinear;
    // The largest texture side (the GPU's GL_MAX_TEXTURE_SIZE): a larger
    // result is reduced to fit, and DrapeImage::reducedFrom says from what.
    int maxTexels = 16384;
};

struct DrapeImage {
    int width = 0, height = 0;
    std::vector<uint8_t> rgba;             // width * height * 4, top row (j = 0 side) first
    bool stretched = false;                // no georeference to go by: stretched over the grid
    bool reprojected = false;              // warped from another reference system
    std::array<int, 2> reducedFrom{0, 0};  // the size before reduction; {0, 0} = not reduced
    double coverage = 0.0;                 // share of texels the image reaches (alpha > 0)
};

// Reads and places `path`. Throws sierra::Error naming the file for one GDAL
// cannot read as an image, a band layout that is not grey, grey + alpha, RGB
// or RGBA, bounds that are empty or not finite, a system with no
// transformation to the grid's, or an image that reaches no texel of the
// grid. Built without GDAL, throws saying so.
DrapeImage readDrape(const std::string& path, const DrapeOptions& options);

// Rows of a drape as they are warped, top first.
struct DrapeStrip {
    int row = 0, rows = 0, width = 0;
    const uint8_t* rgba = nullptr;  // width * rows * 4 bytes, valid during the call
};

// readDrape in strips of at most `stripBytes` bytes (RGBA8; at least one
// row), so a large drape is never held whole: onSize gets the result's size
// and flags (rgba empty) before the first strip, onStrip each strip in turn;
// returns the same header with the coverage. GDAL's block cache is capped at
// 64 MiB while it reads: a strip's source rows, not the image.
DrapeImage readDrapeStrips(const std::string& path, const DrapeOptions& options, size_t stripBytes,
                           const std::function<void(const DrapeImage&)>& onSize,
                           const std::function<void(const DrapeStrip&)>& onStrip);

}  // namespace sierra::terrain
