#include <sierra/scene/Terrain.h>

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/sbt/TileFile.h>
#include <sierra/terrain/DiamondSquare.h>
#include <sierra/terrain/HeightfieldIO.h>
#include <sierra/terrain/Padding.h>

#include "scene/Names.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <vector>

namespace sierra::scene {
namespace {

// "WxH" with both sides in 1..maxSide; nothing may follow.
std::pair<int, int> parseSize(const std::string& text, const std::string& option, int maxSide,
                              const char* example) {
    int w = 0, h = 0;
    char x = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') ||
        w <= 0 || h <= 0 || w > maxSide || h > maxSide)
        throw Error(msg(option, " '", text, "': expected WIDTHxHEIGHT, each 1..", maxSide,
                        ", e.g. ", example));
    return {w, h};
}

}  // namespace

const char* toString(SeaLevel::Mode mode) {
    switch (mode) {
        case SeaLevel::Mode::None:
            return "none";
        case SeaLevel::Mode::Value:
            return "value";
        case SeaLevel::Mode::Auto:
            break;
    }
    return "auto";
}

const char* toString(HeightUnits units) {
    switch (units) {
        case HeightUnits::Metres:
            return "m";
        case HeightUnits::None:
            return "none";
        case HeightUnits::Auto:
            break;
    }
    return "auto";
}

const char* toString(Channel channel) {
    switch (channel) {
        case Channel::Luminance:
            return "luminance";
        case Channel::Red:
            return "r";
        case Channel::Green:
            return "g";
        case Channel::Blue:
            return "b";
        case Channel::Grey:
            break;
    }
    return "grey";
}

HeightUnits parseHeightUnits(const std::string& text, const std::string& what) {
    static const std::pair<const char*, HeightUnits> kNames[] = {{"auto", HeightUnits::Auto},
                                                                 {"m", HeightUnits::Metres},
                                                                 {"metres", HeightUnits::Metres},
                                                                 {"none", HeightUnits::None}};
    return detail::parseName(text, what, kNames);
}

Channel parseChannel(const std::string& text, const std::string& what) {
    static const std::pair<const char*, Channel> kNames[] = {{"grey", Channel::Grey},
                                                             {"luminance", Channel::Luminance},
                                                             {"r", Channel::Red},
                                                             {"g", Channel::Green},
                                                             {"b", Channel::Blue}};
    return detail::parseName(text, what, kNames);
}

std::pair<int, int> parseFrameSize(const std::string& text, const std::string& option) {
    return parseSize(text, option, 16384, "1920x1080");
}

std::pair<int, int> parseRawSize(const std::string& text, const std::string& option) {
    return parseSize(text, option, 65537, "4097x4097");
}

namespace {

// What loadTerrain does after reading (or generating) the samples: padding,
// spacing and vertical scale, and the description's rest.
terrain::Heightfield finishTerrain(terrain::Heightfield field, const TerrainSource& source,
                                   std::string what, std::string* description, Padding padding) {
    const bool metric = metricHeights(source, field);
    int originalWidth = field.width(), originalHeight = field.height();
    if (padding == Padding::PowerOfTwoPlusOne) field = terrain::padToPowerOfTwoPlusOne(field);
    if (field.width() != originalWidth || field.height() != originalHeight)
        what += msg(", padded to ", field.width(), "x", field.height());

    if (source.spacing > 0.0f) field.setSpacing(source.spacing, source.spacing);
    float spacing = std::max(field.spacingX(), field.spacingZ());
    float scale = source.verticalScale;
    if (scale <= 0.0f) {
        if (metric) {
            scale = 1.0f;
        } else {
            auto [lo, hi] = field.range();
            float extent = float(std::max(originalWidth, originalHeight) - 1) * spacing;
            scale = hi > lo ? 0.2f * extent / (hi - lo) : 1.0f;
        }
    }
    field.setVerticalScale(scale);
    what += msg(", spacing ", field.spacingX(), "x", field.spacingZ(), field.metres() ? " m" : "",
                ", vertical scale ", scale);
    // Metres drawn at scale 1 over a grid of unknown ground spacing: one
    // metre a sample is a guess that can exaggerate the relief a thousandfold.
    if (metric && !field.metres() && source.spacing <= 0.0f && source.verticalScale <= 0.0f)
        what +=
            " [warning: the heights are metres but the ground spacing is unknown, so 1 m a "
            "sample is assumed; --spacing gives it]";
    if (description) *description = what;
    return field;
}

}  // namespace

terrain::Heightfield loadTerrain(const TerrainSource& source, std::string* description,
                                 Padding padding, int maxPaddedSide) {
    terrain::Heightfield field;
    std::string what;
    if (source.heightmap.empty()) {
        SIERRA_CHECK(source.generateSize <= maxPaddedSide, "--generate ", source.generateSize,
                     " is larger than the largest grid this renderer takes, ", maxPaddedSide, "x",
                     maxPaddedSide, " (its texture size limit)");
        field = terrain::generateDiamondSquare({.size = source.generateSize,
                                                .seed = source.seed,
                                                .roughness = source.roughness,
                                                .hurst = source.hurst});
        what = msg("diamond-square ", source.generateSize, "x", source.generateSize, ", seed ",
                   source.seed, ", roughness ", source.roughness,
                   source.hurst ? msg(", Hurst ", *source.hurst) : std::string());
    } else if (lowerExtension(source.heightmap) == ".sierra") {
        // A tiled terrain: its overview, every stride-th sample, within the
        // caller's grid (sbt::readOverview). World heights: vertical scale 1.
        const sbt::TileFile file(source.heightmap);
        int stride = 1;
        const int side = std::min(maxPaddedSide, terrain::kDefaultMaxPaddedSide);
        field = sbt::readOverview(file, side - 1, 0, &stride);
        what = msg(source.heightmap, " (a tiled terrain of ", file.info().width, "x",
                   file.info().height, " samples, read at every ", stride, ": ", field.width(), "x",
                   field.height(), ")");
        // Its world heights as built: the automatic vertical scale is 1.
        TerrainSource tiled = source;
        if (tiled.verticalScale <= 0.0f) tiled.verticalScale = 1.0f;
        return finishTerrain(std::move(field), tiled, std::move(what), description, padding);
    } else {
        // The loaders take the channel's name ("" = grey images only).
        field = terrain::loadHeightfield(
            source.heightmap,
            {.rawWidth = source.rawWidth,
             .rawHeight = source.rawHeight,
             .channel = source.channel == Channel::Grey ? std::string() : toString(source.channel),
             .maxPaddedSide = maxPaddedSide});
        what = msg(source.heightmap, " (", field.width(), "x", field.height(), ")");
        if (std::string warning = padding == Padding::None
                                      ? std::string()
                                      : terrain::paddingWarning(field.width(), field.height());
            !warning.empty())
            what += msg(" [warning: ", warning, "]");
    }
    return finishTerrain(std::move(field), source, std::move(what), description, padding);
}

terrain::Heightfield prepareTerrain(terrain::Heightfield field, const TerrainSource& source,
                                    std::string* description, Padding padding, int maxPaddedSide) {
    SIERRA_CHECK(!source.heightmap.empty(), "prepareTerrain needs a name for the grid");
    SIERRA_CHECK(field.width() >= 2 && field.height() >= 2, source.heightmap, ": a ", field.width(),
                 "x", field.height(), " grid has no cell; give at least 2x2 samples");
    if (padding == Padding::PowerOfTwoPlusOne)
        terrain::checkFieldSize(source.heightmap, field.width(), field.height(), maxPaddedSide);
    std::string what = msg(source.heightmap, " (", field.width(), "x", field.height(), ")");
    return finishTerrain(std::move(field), source, std::move(what), description, padding);
}

bool metricHeights(const TerrainSource& source, const terrain::Heightfield& field) {
    if (source.heightUnits != HeightUnits::Auto) return source.heightUnits == HeightUnits::Metres;
    if (source.heightmap.empty()) return false;
    if (field.metres()) return true;
    const std::string ext = lowerExtension(source.heightmap);
    // SRTM and GeoTIFF carry metres: their loaders set the ground spacing, and
    // heights need no exaggeration.
    return ext == ".hgt" || ext == ".tif" || ext == ".tiff";
}

float heightQuantile(const terrain::Heightfield& field, double share) {
    SIERRA_CHECK(share >= 0.0 && share <= 1.0, "a height quantile needs a share in [0, 1], got ",
                 share);
    std::vector<float> heights;
    heights.reserve(size_t(field.sampleCount()));
    for (int j = 0; j < field.height(); ++j)
        for (int i = 0; i < field.width(); ++i)
            if (field.valid(i, j)) heights.push_back(field.at(i, j));
    if (heights.empty()) return 0.0f;
    auto nth = heights.begin() +
               std::ptrdiff_t(std::min(heights.size() - 1, size_t(double(heights.size()) * share)));
    std::nth_element(heights.begin(), nth, heights.end());
    return *nth;
}

float resolveSeaLevel(const TerrainSource& source, const terrain::Heightfield& field) {
    constexpr float kNone = std::numeric_limits<float>::quiet_NaN();
    switch (source.seaLevel.mode) {
        case SeaLevel::Mode::Value:
            return source.seaLevel.value;
        case SeaLevel::Mode::None:
            return kNone;
        case SeaLevel::Mode::Auto:
            break;
    }
    if (source.heightmap.empty()) return heightQuantile(field, 0.3);
    if (metricHeights(source, field) && field.range().first < 0.0f) return 0.0f;
    return kNone;
}

}  // namespace sierra::scene
