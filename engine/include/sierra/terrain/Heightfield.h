#pragma once
// A regular grid of height samples: the input of every other module.
//
// Sample (i, j): i is the column along +x (east), j the row along +z. Samples
// are stored row-major as float32, index j * width + i. World position of a
// sample: (i * spacingX, height * verticalScale, j * spacingZ).

#include <sierra/core/Error.h>

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace sierra::terrain {

class Heightfield {
  public:
    Heightfield() = default;
    // A width x height grid filled with `fill`; every sample valid.
    Heightfield(int width, int height, float fill = 0.0f);

    int width() const { return width_; }
    int height() const { return height_; }
    int64_t sampleCount() const { return int64_t(width_) * height_; }
    bool empty() const { return samples_.empty(); }

    float at(int i, int j) const { return samples_[size_t(j) * width_ + i]; }
    float& at(int i, int j) { return samples_[size_t(j) * width_ + i]; }
    std::span<const float> samples() const { return samples_; }
    std::span<float> samples() { return samples_; }

    // Ground distance between neighbouring samples along x and z (world units,
    // default 1) and the factor from stored height to world height (default 1).
    float spacingX() const { return spacingX_; }
    float spacingZ() const { return spacingZ_; }
    float verticalScale() const { return verticalScale_; }
    void setSpacing(float x, float z);
    void setVerticalScale(float scale);

    // True when the file's georeferencing says the heights and the ground
    // spacing are metres (SRTM, a GeoTIFF with a reference system, an .npz
    // with geographic bounds); false when their units are unknown.
    bool metres() const { return metres_; }
    void setMetres(bool metres) { metres_ = metres; }

    // The geographic position of the real samples' centre (WGS 84 degrees,
    // latitude north, longitude east), when the file's georeferencing gives
    // it (SRTM's tile name, a GeoTIFF's geotransform and reference system, an
    // .npz's geographic bounds); the sun's position at a time needs it.
    struct GeoPoint {
        double latitude = 0.0;   // degrees, -90..90
        double longitude = 0.0;  // degrees, -180..360
        bool operator==(const GeoPoint&) const = default;
    };
    const std::optional<GeoPoint>& geoCentre() const { return geoCentre_; }
    void setGeoCentre(std::optional<GeoPoint> centre);

    // Where the grid lies in the file's coordinate reference system, when the
    // file says (a GeoTIFF's geotransform and reference system, an .npz's
    // geographic bounds on WGS 84). geoTransform is GDAL's affine map of
    // pixel corners: sample (i, j) covers pixel column i, row j, and its
    // centre is at X = g[0] + (i + 0.5) g[1] + (j + 0.5) g[2],
    // Y = g[3] + (i + 0.5) g[4] + (j + 0.5) g[5], in the system's units
    // (degrees for a geographic one). Heights stay the stored heights.
    struct Georeference {
        std::array<double, 6> geoTransform{0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
        std::string crsWkt;  // the reference system as OGC WKT; "" = unknown
        bool operator==(const Georeference&) const = default;
    };
    const std::optional<Georeference>& georeference() const { return georeference_; }
    void setGeoreference(std::optional<Georeference> georeference);

    // World height of sample (i, j): at(i, j) * verticalScale().
    float worldHeight(int i, int j) const { return at(i, j) * verticalScale_; }

    // No-data mask: empty means every sample is valid; otherwise one byte per
    // sample, 1 = real data, 0 = no data (the stored height is then a fill value).
    bool hasMask() const { return !mask_.empty(); }
    bool valid(int i, int j) const { return mask_.empty() || mask_[size_t(j) * width_ + i]; }
    std::span<const uint8_t> mask() const { return mask_; }
    void setMask(std::vector<uint8_t> mask);

    // Smallest and largest stored height over valid samples (0, 0 when empty).
    std::pair<float, float> range() const;

  private:
    int width_ = 0;
    int height_ = 0;
    float spacingX_ = 1.0f;
    float spacingZ_ = 1.0f;
    float verticalScale_ = 1.0f;
    bool metres_ = false;
    std::optional<GeoPoint> geoCentre_;
    std::optional<Georeference> georeference_;
    std::vector<float> samples_;
    std::vector<uint8_t> mask_;
};

}  // namespace sierra::terrain
