#include <sierra/terrain/ColourRamp.h>

#include <sierra/terrain/FileIO.h>

#include <stb/stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <utility>

namespace sierra::terrain {
namespace {

// Hypsometric colours, land positions as fractions of the relief above sea level.
constexpr Rgb kDeepWater{12, 32, 100};
constexpr Rgb kMidWater{40, 100, 180};
constexpr Rgb kShallowWater{110, 175, 225};
constexpr Rgb kSand{225, 208, 150};
constexpr float kSandTop = 0.03f;  // thin band: the lowest 3% of the land relief
constexpr Rgb kLowGrass{105, 170, 75};
constexpr Rgb kHighGrass{55, 125, 50};
constexpr Rgb kScrub{125, 115, 70};
constexpr Rgb kBrownRock{120, 95, 75};
constexpr Rgb kGreyRock{140, 135, 130};
constexpr float kSnowLine = 0.9f;  // snow on the top 10%
constexpr Rgb kSnow{245, 245, 250};
constexpr Rgb kPeak{255, 255, 255};

// Atlas: "slightly more sober colours".
constexpr Rgb kAtlasDeep{70, 115, 180};
constexpr Rgb kAtlasShallow{120, 165, 215};
constexpr Rgb kAtlasLow{150, 195, 120};
constexpr Rgb kAtlasHigh{95, 150, 85};

uint8_t lerp8(uint8_t a, uint8_t b, float t) {
    return uint8_t(std::lround(float(a) + (float(b) - float(a)) * t));
}

// Collects the PNG bytes stb_image_write hands over.
void appendBytes(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<uint8_t>*>(context);
    auto* p = static_cast<const uint8_t*>(data);
    out->insert(out->end(), p, p + size);
}

}  // namespace

ColourRamp::ColourRamp(const ColourRampDesc& desc) : desc_(desc) {
    const float lo = desc.minHeight, hi = desc.maxHeight, sea = desc.seaLevel;
    SIERRA_CHECK(std::isfinite(lo) && std::isfinite(hi) && std::isfinite(sea) && lo < hi,
                 "colour ramp range [", lo, ", ", hi, "] with sea level ", sea,
                 " is invalid; need finite values and minHeight < maxHeight");
    auto add = [&](float h, Rgb c) { stops_.push_back({h, c}); };
    switch (desc.scheme) {
        case RampScheme::Plasma:
            add(lo, {0, 0, 0});
            add(hi, {255, 255, 255});
            break;
        case RampScheme::Atlas:
            if (sea > lo) {
                add(lo, kAtlasDeep);
                add(sea, kAtlasShallow);
            }
            add(sea, kAtlasLow);
            add(std::max(hi, sea), kAtlasHigh);
            break;
        case RampScheme::Elevation: {
            const float tree = desc.treeLine, snow = desc.snowLine;
            SIERRA_CHECK(std::isfinite(tree) && std::isfinite(snow) && tree > 0.0f && snow >= tree,
                         "tree line ", tree, " m and snow line ", snow,
                         " m: need 0 < tree line <= snow line");
            constexpr float kSandMetres = 5.0f;
            float ground = lo;  // where the land colours start
            if (sea > lo) {
                add(sea - 2000.0f, kDeepWater);
                add(sea - 200.0f, kMidWater);
                add(sea, kShallowWater);
                add(sea, kSand);
                add(sea + kSandMetres, kSand);
                ground = sea + kSandMetres;
            }
            // Absolute stops above the ground; those below it are dropped so
            // the land starts with the colour the ground height has.
            const Stop land[] = {{0.0f, kLowGrass},      {0.5f * tree, kHighGrass},
                                 {0.8f * tree, kScrub},  {tree, kBrownRock},
                                 {snow, kGreyRock},      {snow, kSnow},
                                 {snow + 1500.0f, kPeak}};
            size_t first = 0;
            while (first + 1 < std::size(land) && land[first + 1].height <= ground) ++first;
            if (land[first].height < ground) {
                // Interpolate the colour at the ground between the surrounding stops.
                const Stop& a = land[first];
                const Stop& b = land[std::min(first + 1, std::size(land) - 1)];
                float t = b.height > a.height
                              ? std::clamp((ground - a.height) / (b.height - a.height), 0.0f, 1.0f)
                              : 1.0f;
                add(ground, {lerp8(a.colour.r, b.colour.r, t), lerp8(a.colour.g, b.colour.g, t),
                             lerp8(a.colour.b, b.colour.b, t)});
                ++first;
            }
            for (size_t k = first; k < std::size(land); ++k) add(land[k].height, land[k].colour);
            break;
        }
        case RampScheme::Hypsometric: {
            if (sea > lo) {
                add(lo, kDeepWater);
                add(0.5f * (lo + sea), kMidWater);
                add(sea, kShallowWater);
            }
            // Land relief: sea level to the top (a unit relief when all is water).
            const float relief = hi > sea ? hi - sea : 1.0f;
            auto land = [&](float fraction, Rgb c) { add(sea + fraction * relief, c); };
            land(0.0f, kSand);
            land(kSandTop, kSand);
            land(kSandTop, kLowGrass);
            land(0.35f, kHighGrass);
            land(0.5f, kScrub);
            land(0.65f, kBrownRock);
            land(0.8f, kGreyRock);
            land(kSnowLine, kGreyRock);
            land(kSnowLine, kSnow);
            land(1.0f, kPeak);
            break;
        }
    }
}

ColourRamp::ColourRamp(std::vector<ColourStop> stops, float minHeight, float maxHeight,
                       const OutOfRangeColours& outside)
    : desc_{.minHeight = minHeight, .maxHeight = maxHeight},
      outside_(outside),
      stops_(std::move(stops)) {
    SIERRA_CHECK(std::isfinite(minHeight) && std::isfinite(maxHeight) && minHeight < maxHeight,
                 "colour ramp range [", minHeight, ", ", maxHeight,
                 "] is invalid; need minHeight < maxHeight");
    SIERRA_CHECK(stops_.size() >= 2, "a colour table needs at least 2 stops, got ", stops_.size());
    for (size_t k = 0; k < stops_.size(); ++k) {
        SIERRA_CHECK(std::isfinite(stops_[k].height), "colour stop ", k,
                     " has a non-finite height");
        SIERRA_CHECK(k == 0 || stops_[k].height >= stops_[k - 1].height,
                     "colour stops are not ascending: ", stops_[k - 1].height, " then ",
                     stops_[k].height);
    }
}

ColourRamp ColourRamp::forField(const Heightfield& field, RampScheme scheme, float seaLevel) {
    auto [lo, hi] = field.range();
    if (!(hi > lo)) hi = lo + 1.0f;
    return ColourRamp({.scheme = scheme, .minHeight = lo, .maxHeight = hi, .seaLevel = seaLevel});
}

Rgb ColourRamp::colourAt(float height) const {
    if (std::isnan(height)) {
        if (outside_.noData) return *outside_.noData;
        height = desc_.minHeight;
    }
    height = std::clamp(height, desc_.minHeight, desc_.maxHeight);
    if (outside_.below && height < stops_.front().height) return *outside_.below;
    if (outside_.above && height > stops_.back().height) return *outside_.above;
    // First stop strictly above: at a hard edge (two stops at one height) the
    // upper colour wins, so sea level itself is land.
    auto above = std::upper_bound(stops_.begin(), stops_.end(), height,
                                  [](float h, const Stop& s) { return h < s.height; });
    if (above == stops_.begin()) return above->colour;
    if (above == stops_.end()) return stops_.back().colour;
    const Stop& a = *(above - 1);
    const Stop& b = *above;
    const float t = (height - a.height) / (b.height - a.height);
    return {lerp8(a.colour.r, b.colour.r, t), lerp8(a.colour.g, b.colour.g, t),
            lerp8(a.colour.b, b.colour.b, t)};
}

std::vector<uint8_t> ColourRamp::table(int entries) const {
    SIERRA_CHECK(entries >= 2 && entries <= 65536, "colour ramp table of ", entries,
                 " entries; need 2..65536");
    std::vector<uint8_t> rgba(size_t(entries) * 4);
    const double lo = desc_.minHeight, hi = desc_.maxHeight;
    for (int k = 0; k < entries; ++k) {
        const Rgb c = colourAt(float(lo + (hi - lo) * k / (entries - 1)));
        rgba[4 * k + 0] = c.r;
        rgba[4 * k + 1] = c.g;
        rgba[4 * k + 2] = c.b;
        rgba[4 * k + 3] = 255;
    }
    return rgba;
}

void writeMapPng(const std::string& path, const Heightfield& field, const ColourRamp& ramp,
                 bool colourBar) {
    if (field.empty()) throw Error(msg("cannot write ", path, ": the heightfield is empty"));
    const int fieldWidth = field.width(), height = field.height();
    // Bar geometry in pixels: a gap of ~2% and a bar of ~6% of the map width.
    const int gap = colourBar ? std::max(2, fieldWidth / 50) : 0;
    const int bar = colourBar ? std::max(8, fieldWidth / 16) : 0;
    const int width = fieldWidth + gap + bar;
    std::vector<uint8_t> rgb(size_t(width) * height * 3, 255);
    const float lo = ramp.desc().minHeight, hi = ramp.desc().maxHeight;
    for (int j = 0; j < height; ++j) {
        uint8_t* row = rgb.data() + size_t(j) * width * 3;
        for (int i = 0; i < fieldWidth; ++i) {
            const Rgb c = field.valid(i, j) ? ramp.colourAt(field.at(i, j)) : ramp.noDataColour();
            row[3 * i] = c.r, row[3 * i + 1] = c.g, row[3 * i + 2] = c.b;
        }
        if (colourBar) {
            const float t = height > 1 ? float(j) / float(height - 1) : 0.0f;
            const Rgb c = ramp.colourAt(hi - (hi - lo) * t);  // top row = maxHeight
            for (int i = fieldWidth + gap; i < width; ++i)
                row[3 * i] = c.r, row[3 * i + 1] = c.g, row[3 * i + 2] = c.b;
        }
    }
    std::vector<uint8_t> png;
    if (!stbi_write_png_to_func(appendBytes, &png, width, height, 3, rgb.data(), width * 3))
        throw Error(msg("cannot write ", path, ": PNG encoding failed for a ", width, "x", height,
                        " image"));
    writeFileAtomic(path, png);
}

}  // namespace sierra::terrain
