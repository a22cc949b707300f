#include <sierra/terrain/Heightfield.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sierra::terrain {

// Largest side accepted anywhere: 65537 samples (2^16 + 1), so grid positions
// fit in 16 bits and a grid never exceeds 2^32 samples.
constexpr int kMaxSide = 65537;

Heightfield::Heightfield(int width, int height, float fill) : width_(width), height_(height) {
    SIERRA_CHECK(width > 0 && height > 0 && width <= kMaxSide && height <= kMaxSide,
                 "heightfield size ", width, "x", height, " is outside 1..", kMaxSide);
    samples_.assign(size_t(width) * height, fill);
}

void Heightfield::setSpacing(float x, float z) {
    SIERRA_CHECK(std::isfinite(x) && std::isfinite(z) && x > 0 && z > 0,
                 "sample spacing must be finite and positive, got ", x, ", ", z);
    spacingX_ = x;
    spacingZ_ = z;
}

void Heightfield::setVerticalScale(float scale) {
    SIERRA_CHECK(std::isfinite(scale) && scale > 0,
                 "vertical scale must be finite and positive, got ", scale);
    verticalScale_ = scale;
}

void Heightfield::setGeoCentre(std::optional<GeoPoint> centre) {
    SIERRA_CHECK(
        !centre || (std::isfinite(centre->latitude) && std::abs(centre->latitude) <= 90.0 &&
                    std::isfinite(centre->longitude) && centre->longitude >= -180.0 &&
                    centre->longitude <= 360.0),
        "a geographic centre needs latitude -90..90 and longitude -180..360 degrees, got ",
        centre ? centre->latitude : 0.0, ", ", centre ? centre->longitude : 0.0);
    geoCentre_ = centre;
}

void Heightfield::setGeoreference(std::optional<Georeference> georeference) {
    if (georeference) {
        const auto& g = georeference->geoTransform;
        bool finite = true;
        for (double v : g) finite = finite && std::isfinite(v);
        SIERRA_CHECK(finite && g[1] * g[5] - g[2] * g[4] != 0.0,
                     "a georeference needs a finite, invertible geotransform, got ", g[0], ", ",
                     g[1], ", ", g[2], ", ", g[3], ", ", g[4], ", ", g[5]);
    }
    georeference_ = std::move(georeference);
}

void Heightfield::setMask(std::vector<uint8_t> mask) {
    SIERRA_CHECK(mask.empty() || mask.size() == samples_.size(), "mask has ", mask.size(),
                 " entries for ", samples_.size(), " samples");
    mask_ = std::move(mask);
}

std::pair<float, float> Heightfield::range() const {
    float lo = std::numeric_limits<float>::max();
    float hi = std::numeric_limits<float>::lowest();
    for (size_t k = 0; k < samples_.size(); ++k) {
        if (!mask_.empty() && !mask_[k]) continue;
        lo = std::min(lo, samples_[k]);
        hi = std::max(hi, samples_[k]);
    }
    if (lo > hi) return {0.0f, 0.0f};
    return {lo, hi};
}

}  // namespace sierra::terrain
