#pragma once
// Building a scene from command-line style settings: load or generate the
// heightfield, pad it to (2^n+1)^2, pick spacing and vertical scale. Shared by
// the apps so every program reads terrain the same way.

#include <sierra/terrain/Heightfield.h>

#include <cstdint>
#include <string>
#include <utility>

namespace sierra::render {

struct TerrainSource {
    std::string heightmap;    // file to load; empty = generate
    int generateSize = 1025;  // samples per side of a generated terrain, 2^n + 1
    uint64_t seed = 1;
    float roughness = 1.0f;
    int rawWidth = 0;         // size of .r16/.r32 files
    int rawHeight = 0;
    float spacing = 0.0f;        // world units between samples; 0 = the loader's
    float verticalScale = 0.0f;  // stored height -> world height; 0 = automatic
};

// Parses "WIDTHxHEIGHT" (each 1..16384); throws sierra::Error naming `option`.
std::pair<int, int> parseFrameSize(const std::string& text, const std::string& option = "--size");

// The terrain ready for the SBT. Automatic spacing is the loader's (1 for image
// and array formats; SRTM: 90 m for 1201 wide tiles, 30 m for 3601; GeoTIFF: the
// pixel size of a projected system); automatic vertical scale makes the relief
// 20% of the horizontal extent (SRTM and GeoTIFF: 1, heights are metres).
terrain::Heightfield loadTerrain(const TerrainSource& source, std::string* description = nullptr);

}  // namespace sierra::render
