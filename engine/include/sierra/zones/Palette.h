#pragma once
// Palettes: which colour of a zone map is which surface type, its tile image
// and its blend settings. Its JSON form (docs/zones.md) is read and written
// by the programs' layer, scene/PaletteJson.h.

#include <cstdint>
#include <string>
#include <vector>

namespace sierra::zones {

// A colour as 0xRRGGBB.
using Colour = uint32_t;

// "#rrggbb" (lower case) of a colour.
std::string colourHex(Colour colour);

struct SurfaceType {
    std::string name;          // e.g. "grass"; unique within a palette
    Colour colour = 0;         // its colour in zone maps, 0xRRGGBB
    std::string tile;          // tile image, absolute or relative to the working directory
                               // (the JSON names it relative to the palette file)
    float tileSize = 16.0f;    // zone-map pixels covered by one repetition of the tile, > 0
    float heightBlend = 0.5f;  // 0..1: how much the tile's height channel (alpha) moves the
                               // transition inside a band (0 = plain linear blend)
};

struct Palette {
    std::vector<SurfaceType> surfaces;  // zone id = index; at most 255 surfaces
    Colour borderline = 0x000000;       // colour of Figure 1 borderline pixels (no zone)
    float bandWidth = 0.0f;             // default transition band width, zone-map pixels (0 = none)

    // Zone id of a colour, -1 when the palette does not name it.
    int find(Colour colour) const;
    // Zone id of a surface name, -1 when absent.
    int findName(const std::string& name) const;
};

}  // namespace sierra::zones
