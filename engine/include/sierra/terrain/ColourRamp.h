#pragma once
// Height-to-colour ramps for 2D maps and the renderer's 1D colour texture, after
// the colouring schemes of the seed document ("Some Random Landscapes").

#include <sierra/terrain/Heightfield.h>

#include <cstdint>
#include <optional>
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

// One colour at one stored height, for ramps built from a table (a .cpt file).
struct ColourStop {
    float height;
    Rgb colour;
};

// Colours for heights outside a table's stops and for no-data, as a .cpt file's
// B, F and N lines give them; unset = clamp to the end colours (no-data black).
struct OutOfRangeColours {
    std::optional<Rgb> below;   // B
    std::optional<Rgb> above;   // F
    std::optional<Rgb> noData;  // N
};

struct ColourRampDesc {
    RampScheme scheme = RampScheme::Hypsometric;
    float minHeight = 0.0f;    // stored height of the first colour; lower heights clamp to it
    float maxHeight = 1.0f;    // stored height of the last colour, > minHeight
    float seaLevel = 0.0f;     // water below, land at or above; outside [min, max] = all land/water
    float treeLine = 2000.0f;  // Elevation: metres above which no vegetation grows
    float snowLine = 3000.0f;  // Elevation: metres above which snow lies, >= treeLine
};

// Piecewise-linear colour stops over stored heights. Cheap to copy.
class ColourRamp {
  public:
    // Throws sierra::Error unless minHeight < maxHeight, all finite.
    explicit ColourRamp(const ColourRampDesc& desc = {});

    // A ramp from explicit stops, sorted by height (two stops at one height =
    // a hard edge, as a discrete table has), for heights in [minHeight,
    // maxHeight] (what table() spans). Throws unless there are >= 2 stops in
    // ascending order and minHeight < maxHeight.
    ColourRamp(std::vector<ColourStop> stops, float minHeight, float maxHeight,
               const OutOfRangeColours& outside = {});

    // A ramp over field.range() (widened by 1 when the field is flat).
    static ColourRamp forField(const Heightfield& field, RampScheme scheme, float seaLevel);

    const ColourRampDesc& desc() const { return desc_; }

    // Colour of a stored height; heights outside [min, max] clamp, NaN gives the
    // colour of minHeight.
    Rgb colourAt(float height) const;
    // Colour of no-data samples: the table's N colour, else black.
    Rgb noDataColour() const { return outside_.noData.value_or(Rgb{0, 0, 0}); }

    // `entries` RGBA8 colours (4 bytes each, alpha 255), entry k at height
    // min + (max - min) * k / (entries - 1): ready for a GL_RGBA8 1D texture.
    // entries must be 2..65536.
    std::vector<uint8_t> table(int entries) const;

  private:
    using Stop = ColourStop;
    ColourRampDesc desc_;
    OutOfRangeColours outside_;
    std::vector<Stop> stops_;  // sorted by height; two stops at one height = a hard edge
};

// Writes `field` as an RGB8 PNG coloured by `ramp` (row j = image row j), with
// no-data samples black. colourBar adds a white gap and a vertical bar on the
// right, maxHeight at the top to minHeight at the bottom, as in the seed
// document's maps. Written to a temporary name, then renamed.
void writeMapPng(const std::string& path, const Heightfield& field, const ColourRamp& ramp,
                 bool colourBar);

}  // namespace sierra::terrain
