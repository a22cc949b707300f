#pragma once
// Heights of a grid too large to hold in memory, read a window at a time: the
// input of the tile builder (sierra-tile build). Raw .r16 / .r32 files and
// .npy arrays are memory-mapped and read where asked, never loaded whole;
// anything GDAL opens (a GeoTIFF, a COG, a VRT, .hgt tiles) is read through
// RasterIO, several files at once as one mosaic (a VRT built in memory).
// Formats small by nature (.npz, .png, .pgm) are loaded whole by
// loadHeightfield and read from memory.

#include <sierra/terrain/Heightfield.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>

namespace sierra::terrain {

// What a reader knows of its grid besides the heights.
struct GridInfo {
    int64_t width = 0, height = 0;  // samples
    float spacingX = 1.0f, spacingZ = 1.0f;
    bool metres = false;
    bool hasNoData = false;  // some samples may be invalid
    // Set when every height is an integer v with v - int16Offset in the int16
    // range (bytes, int16, uint16 inputs): int16 storage keeps them exactly.
    std::optional<double> int16Offset;
    std::optional<Heightfield::GeoPoint> geoCentre;
    std::optional<Heightfield::Georeference> georeference;
};

class GridReader {
  public:
    virtual ~GridReader() = default;
    const GridInfo& info() const { return info_; }
    // Samples [x0, x0 + w) x [y0, y0 + h), inside the grid, into `heights`
    // (row-major, w a row) and, when `valid` is not null, 1 for a real sample
    // and 0 for no data into `valid` (the height is then unspecified). Safe to
    // call from several threads at once. Throws sierra::Error on a read error
    // or a height that is not finite.
    virtual void read(int64_t x0, int64_t y0, int w, int h, float* heights,
                      uint8_t* valid) const = 0;
    // The caller reads no row before `row` again: a mapped file drops those
    // pages from the process (a build streaming through a file many times its
    // memory stays bounded). A hint; the default does nothing.
    virtual void releaseRowsBefore(int64_t row) const { (void)row; }

  protected:
    GridInfo info_;
};

struct GridReaderOptions {
    // Size of a raw .r16/.r32 file in samples; 0, 0 = a square from the file size.
    int64_t rawWidth = 0, rawHeight = 0;
};

// A reader for `paths`: one .r16, .r32, .npy, .npz, .png or .pgm file, or one
// or more files GDAL opens (mosaicked when more than one). Throws sierra::Error naming the
// file for a missing, unreadable or malformed input.
std::unique_ptr<GridReader> openGridReader(std::span<const std::string> paths,
                                           const GridReaderOptions& options = {});

// A reader over a heightfield in memory (kept by reference): tests and small grids.
std::unique_ptr<GridReader> memoryGridReader(const Heightfield& field);

}  // namespace sierra::terrain
