#pragma once
// 2D maps of a heightfield (no GL): height colour schemes, scalar fields
// (DemMaps.h) through colour ramps, the shaded relief composite, and a colour
// bar legend with ticks and numbers in the field's units.

#include <sierra/terrain/ColourRamp.h>
#include <sierra/terrain/Heightfield.h>
#include <sierra/terrain/HeightfieldIO.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace sierra::terrain {

// An RGB8 image, row-major, row 0 at the top.
struct RgbImage {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> rgb;  // width * height * 3
    Rgb at(int x, int y) const {
        const uint8_t* p = rgb.data() + (size_t(y) * width + x) * 3;
        return {p[0], p[1], p[2]};
    }
    void set(int x, int y, Rgb c) {
        uint8_t* p = rgb.data() + (size_t(y) * width + x) * 3;
        p[0] = c.r, p[1] = c.g, p[2] = c.b;
    }
};

// An RGB image (zone maps, tile images) decoded from PNG bytes with the
// heightmap PNG decoder's checks (HeightfieldIO.cpp): every CRC, the chunk
// limits, and the field size limits (checkFieldSize with maxPaddedSide) before
// the pixels are allocated. `what` names the data in messages.
RgbImage decodePngRgb8(const std::string& what, std::span<const uint8_t> bytes,
                       int maxPaddedSide = kDefaultMaxPaddedSide);

enum class MapScheme { Plasma, Atlas, Hypsometric, Cpt };

// Parses "plasma", "atlas", "hypsometric"; false for any other name.
bool parseMapScheme(const std::string& name, MapScheme* out);

// The map image of `field`'s heights, one pixel per sample, coloured through
// `ramp`. No-data samples take ramp.noDataColour().
RgbImage renderMap(const Heightfield& field, const ColourRamp& ramp);

// A scalar field (row-major, width x height) coloured through `ramp`; NaN
// takes ramp.noDataColour().
RgbImage colourField(int width, int height, std::span<const float> values, const ColourRamp& ramp);

// The value below which `share` (0..1) of the finite values lie; 0 when there
// are none.
float finiteQuantile(std::span<const float> values, double share);

// The shaded relief of Swiss topographic maps (after Imhof, "Cartographic
// Relief Presentation", 1982): height tints multiplied by an oblique
// hillshade normalised to flat ground (brighter than the tint on slopes facing
// the light, darker and bluer facing away) and by the sky-view factor (dark in
// deep valleys and gullies), stretched from skyFloor (darkest) to 1 (open).
// hillshade: 1..255 per sample as DemField::Hillshade gives it, NaN where it
// has none (taken as flat: flatShade); skyView 0..1, NaN taken as 1. No-data
// samples take tints.noDataColour().
struct ReliefDesc {
    float flatShade = 181.0f;  // the hillshade of flat ground: 1 + 254 sin(altitude)
    float shadeWeight = 0.6f;  // 0 = tints only, 1 = the full hillshade
    float skyWeight = 0.5f;    // 0 = no sky-view darkening, 1 = black where the sky is least
    float skyFloor = 0.0f;     // the sky-view factor drawn darkest (0..1): below it clamps
};
RgbImage shadedRelief(const Heightfield& field, const ColourRamp& tints,
                      std::span<const float> hillshade, std::span<const float> skyView,
                      const ReliefDesc& desc = {});

// A legend tick: the height it labels (height units = stored height times
// unitScale) and the image row of the bar where that height's colour is.
struct LegendTick {
    double value;
    int row;
    std::string label;
};

// Appends a vertical colour bar right of `image`: a white gap, the bar
// (ramp.maxHeight at the top row, minHeight at the bottom), ticks and numbers
// at "nice" steps (1, 2 or 5 times a power of ten, about 5 ticks) in height
// units = stored height * unitScale, followed by `units` on the top label.
// Returns the ticks with the bar's first column in *barX.
std::vector<LegendTick> addColourBar(RgbImage& image, const ColourRamp& ramp, float unitScale,
                                     const std::string& units, int* barX = nullptr);

// Draws `text` with its top-left corner at (x, y), each font pixel scale x
// scale image pixels; returns the width drawn in image pixels.
int drawText(RgbImage& image, int x, int y, const std::string& text, Rgb colour, int scale);

// Encodes `image` as PNG and writes it atomically.
void writeRgbPng(const std::string& path, const RgbImage& image);
// The same for an 8-bit grey image, row-major, width * height bytes (a third
// of the data of the RGB form, for intensity images).
void writeGreyPng(const std::string& path, int width, int height, std::span<const uint8_t> grey);

}  // namespace sierra::terrain
