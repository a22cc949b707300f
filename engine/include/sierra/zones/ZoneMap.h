#pragma once
// Zone maps: one surface type per pixel, read from an image through a palette,
// or derived from a heightfield by height and slope bands.

#include <sierra/terrain/Heightfield.h>
#include <sierra/zones/Palette.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace sierra::zones {

// Zone id of a Figure 1 borderline pixel (it belongs to no zone).
constexpr int16_t kBorderlinePixel = -1;

enum class ZoneLayout {
    Touching,     // zones meet along pixel edges; the borderlines run on pixel edges
    Borderlines,  // the seed document's Figure 1: 1-pixel borderlines (palette.borderline)
                  // between zones; their pixel centres become the vertices
};

struct ZoneMap {
    int width = 0;
    int height = 0;
    ZoneLayout layout = ZoneLayout::Touching;
    std::vector<int16_t> ids;  // row-major, row 0 at the top: zone id or kBorderlinePixel

    int16_t at(int x, int y) const { return ids[size_t(y) * size_t(width) + size_t(x)]; }
};

// Classifies RGB8 pixels (3 bytes each, row-major) through the palette. The
// layout is Borderlines when any pixel has the borderline colour. Throws
// sierra::Error naming `source`: an unknown colour (its hex and first pixel
// (x, y)), or, in Figure 1 layout, two zones touching with no borderline.
ZoneMap classifyZoneMap(int width, int height, std::span<const uint8_t> rgb, const Palette& palette,
                        const std::string& source);

// Reads a zone map image (PNG, or any format stb reads) and classifies it.
// Throws sierra::Error when the file is missing or not an image, or as above.
ZoneMap loadZoneMap(const std::string& path, const Palette& palette);

// Thresholds of auto-zoning (after the colouring of 001_83c02e222691e7d2.txt).
// Heights are stored heights; fractions are of the depth range below sea level
// or of the land relief above it.
struct AutoZoneDesc {
    float seaLevel = 0.0f;    // water below, land at or above (stored height)
    float deepWater = 0.35f;  // water deeper than this fraction of the deepest depth is deep
    float sandTop = 0.04f;    // sand up to this fraction of the land relief above sea level
    float snowLine = 0.75f;   // snow above this fraction of the land relief
    float rockSlope = 25.0f;  // land steeper than this (degrees, world units: spacing and
                              // vertical scale of the field) is rock; sand and snow included
    int smoothPasses = 2;     // 3x3 majority passes removing single-pixel specks, >= 0
    // Surface names looked up in the palette (each must be there).
    std::string deepName = "deep-water";
    std::string shallowName = "shallow-water";
    std::string sandName = "sand";
    std::string grassName = "grass";
    std::string rockName = "rock";
    std::string snowName = "snow";
};

// A Touching zone map of the field's size, one zone per sample. Throws
// sierra::Error when a name is missing from the palette or a fraction is
// outside [0, 1].
ZoneMap autoZones(const terrain::Heightfield& field, const Palette& palette,
                  const AutoZoneDesc& desc = {});

// The Figure 1 form of a Touching map: a pixel becomes a borderline pixel when
// its right or lower neighbour is another zone, which draws 1-pixel,
// 4-connected borderlines between all zones.
ZoneMap drawBorderlines(const ZoneMap& map);

// RGB8 pixels of a map: palette colours, borderline pixels in palette.borderline.
std::vector<uint8_t> zoneMapRgb(const ZoneMap& map, const Palette& palette);

// A PNG file of zoneMapRgb (lossless, so loadZoneMap reads the same map back).
std::vector<uint8_t> encodeZoneMapPng(const ZoneMap& map, const Palette& palette);

}  // namespace sierra::zones
