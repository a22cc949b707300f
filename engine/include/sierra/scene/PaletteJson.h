#pragma once
// The JSON form of a zones::Palette (docs/zones.md), read by the strict layer
// of JsonRead.h: snake_case keys, unknown keys refused, one number rule.
//
//   {"borderline": "#000000",          // colour of borderline pixels (no zone)
//    "band_width": 3,                  // default transition band, zone-map pixels, 0..1e4
//    "zones": [{"name": "grass", "colour": "#4f8f37", "tile": "../tiles/grass.png",
//               "tile_size": 16,       // zone-map pixels per tile repetition, 1e-3..1e6
//               "height_blend": 0.5},  // 0..1
//              ...]}

#include <sierra/scene/JsonRead.h>
#include <sierra/zones/Palette.h>

#include <string>

namespace sierra::scene {

// Parses a palette from JSON text. `baseDir` resolves relative tile paths,
// `source` names the file in messages. checkTiles: every tile file must exist.
// Throws sierra::Error: not JSON, unknown or missing keys, wrong types or
// ranges, duplicate colours or names, a surface using the borderline colour, a
// missing tile file.
zones::Palette parsePalette(const std::string& text, const std::string& baseDir,
                            const std::string& source, bool checkTiles = true);

// Reads and parses a palette file (tile paths relative to the file's folder).
zones::Palette loadPalette(const std::string& path, bool checkTiles = true);

// The palette JSON text (tiles written as given, relative to nothing).
std::string paletteToJson(const zones::Palette& palette);

}  // namespace sierra::scene
