#pragma once
// 2D maps of a heightfield (no GL): height colour schemes, hillshade and slope
// as GIS users know them from the usual DEM tools, and a colour bar legend with
// ticks and numbers in height units.

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

// The sun for hillshade: compass azimuth in degrees clockwise from north (the
// top of the map), altitude in degrees above the horizon. Defaults 315 / 45:
// light from the upper left, as shaded relief maps are usually lit.
struct Sun {
    float azimuth = 315.0f;
    float altitude = 45.0f;
};

// Hillshade 0..255 per sample: 255 * max(0, n . sun), n the surface normal from
// the 3x3 (Sobel-weighted) height gradient in world units: heights times
// field.verticalScale(), distances field.spacingX() / spacingZ(). The map's top
// is north (row 0), its right east. Edges repeat their samples; no-data
// neighbours take the centre's height; no-data samples give 0.
std::vector<float> hillshade(const Heightfield& field, const Sun& sun);

// Slope in degrees (0 = flat, 90 = vertical) per sample, from the same
// gradient; no-data samples give NaN.
std::vector<float> slopeDegrees(const Heightfield& field);

enum class MapScheme { Plasma, Atlas, Hypsometric, Hillshade, Slope, Cpt };

// Parses "plasma", "atlas", "hypsometric", "hillshade", "slope"; throws otherwise.
MapScheme parseMapScheme(const std::string& name);

// The map image of `field`, one pixel per sample. Height schemes colour through
// `ramp`; hillshade and slope are grey (hillshade: 0 = unlit; slope: white
// flat to black vertical). No-data samples take ramp.noDataColour().
RgbImage renderMap(const Heightfield& field, MapScheme scheme, const ColourRamp& ramp,
                   const Sun& sun = {});

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
