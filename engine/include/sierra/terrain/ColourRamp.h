#pragma once
// Height-to-colour ramps for 2D maps and the renderer's 1D colour texture, after
// the colouring schemes of the seed document ("Some Random Landscapes").

#include <sierra/terrain/Heightfield.h>

#include <cstdint>
#include <string>
#include <vector>

namespace sierra::terrain {

struct Rgb {
    uint8_t r, g, b;
};

enum class RampScheme {
    // Deep to shallow water graded by depth, a thin sand band just above sea
    // level (the lowest 3% of the land relief), grass, rock browns and greys,
    // snow on the top 10%.
    Hypsometric,
    // Monochrome, black at minHeight to white at maxHeight ("plasma cloud");
    // sea level is ignored.
    Plasma,
    // Sober "first atlas" colours: muted blue water, muted green land.
    Atlas,
    // Absolute elevation for metric heights (metres): water graded by depth
    // (shallow at sea level, deep 2000 m below), a 5 m sand band above sea
    // level, grass to half the tree line, scrub and brown rock up to the tree
    // line, grey rock above it, snow above the snow line. The same height gets
    // the same colour on every DEM.
    Elevation,
};

struct ColourRampDesc {
    RampScheme scheme = RampScheme::Hypsometric;
    float minHeight = 0.0f;  // stored height of the first colour; lower heights clamp to it
    float maxHeight = 1.0f;  // stored height of the last colour, > minHeight
    float seaLevel = 0.0f;   // water below, land at or above; outside [min, max] = all land/water
    float treeLine = 2000.0f;  // Elevation: metres above which no vegetation grows
    float snowLine = 3000.0f;  // Elevation: metres above which snow lies, >= treeLine
};

// Piecewise-linear colour stops over stored heights. Cheap to copy.
class ColourRamp {
  public:
    // Throws sierra::Error unless minHeight < maxHeight, all finite.
    explicit ColourRamp(const ColourRampDesc& desc = {});

    // A ramp over field.range() (widened by 1 when the field is flat).
    static ColourRamp forField(const Heightfield& field, RampScheme scheme, float seaLevel);

    const ColourRampDesc& desc() const { return desc_; }

    // Colour of a stored height; heights outside [min, max] clamp, NaN gives the
    // colour of minHeight.
    Rgb colourAt(float height) const;

    // `entries` RGBA8 colours (4 bytes each, alpha 255), entry k at height
    // min + (max - min) * k / (entries - 1): ready for a GL_RGBA8 1D texture.
    // entries must be 2..65536.
    std::vector<uint8_t> table(int entries) const;

  private:
    struct Stop {
        float height;
        Rgb colour;
    };
    ColourRampDesc desc_;
    std::vector<Stop> stops_;  // sorted by height; two stops at one height = a hard edge
};

// Writes `field` as an RGB8 PNG coloured by `ramp` (row j = image row j), with
// no-data samples black. colourBar adds a white gap and a vertical bar on the
// right, maxHeight at the top to minHeight at the bottom, as in the seed
// document's maps. Written to a temporary name, then renamed.
void writeMapPng(const std::string& path, const Heightfield& field, const ColourRamp& ramp,
                 bool colourBar);

}  // namespace sierra::terrain
