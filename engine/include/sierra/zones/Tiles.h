#pragma once
// Procedural, deterministic, seamless surface tiles (256x256 in the seed
// document): RGBA8, RGB the albedo, A a height for height-based blending
// (0 = low, 255 = high; stones stand above the sand between them).

#include <cstdint>
#include <string>
#include <vector>

namespace sierra::zones {

struct TileImage {
    int size = 0;
    std::vector<uint8_t> rgba;  // size * size * 4, row-major
};

// The surface names the generator knows: grass, sand, rock, snow,
// shallow-water, deep-water, earth.
const std::vector<std::string>& tileNames();

// One tile; the same (name, size, seed) gives the same bytes everywhere.
// size: a power of two, 16..2048. Throws sierra::Error for an unknown name.
TileImage generateTile(const std::string& name, int size = 256, uint64_t seed = 1);

// Reads a square tile image (PNG, or any format stb reads) as RGBA8; an image
// with no alpha gets height 255 everywhere. Throws sierra::Error when the file
// is missing, not an image, not square, or larger than 4096 per side.
TileImage loadTile(const std::string& path);

// Two tiles of one size blended as the middle of a transition band shows them
// in the terrain shader: weight 0.5 of each, moved towards the tile that stands
// higher (alpha) by heightBlend (0..1; 0 = the plain mean), then the shader's
// smoothstep(0.15, 0.85). The result's height is the mean height. Throws
// sierra::Error when the sizes differ.
TileImage blendTiles(const TileImage& first, const TileImage& second, float heightBlend);

// A PNG file (RGBA8) of a tile.
std::vector<uint8_t> encodeTilePng(const TileImage& tile);

// A PNG contact sheet (RGB) of tiles of one size: one column per tile, the top
// row its albedo repeated 2x2 at half resolution (a seam would show as a cross),
// the bottom row its height channel in grey.
std::vector<uint8_t> encodeTileSheetPng(const std::vector<TileImage>& tiles);

}  // namespace sierra::zones
