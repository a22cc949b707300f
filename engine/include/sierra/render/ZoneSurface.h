#pragma once
// The zone surface: terrain textured from one tile per surface type, with
// blended transition bands between zones, every frame (the terrain pass's
// shaders/surface_zones.glsl).
//
// Built once per terrain and zone map: the zone map (a PNG through the
// palette, or derived from height and slope), its vectorised borderlines and
// the distance-to-border field built from them (sierra/zones). On the GPU:
//   unit 3  tiles, a 2D texture array (layer = zone id) with mipmaps and, where
//           the driver has it, anisotropic filtering; RGB albedo, A height
//   unit 4  the zone field (R32UI, nearest, read by textureGather): per texel
//           the zone pair of the nearest borderline (bits 0-7, 8-15) and the
//           signed distance to it in texels (a half float, bits 16-31); the
//           texel's zone is the pair's first where the sign is negative
//   block 2 per-zone tile scale, mip level offset, height blend and debug
//           colour; map, field and tile sizes, band width
// The options (triplanar, variation, height blend, debug view) are compiled
// into the shader.
// A fragment away from every band samples one zone's tiles; in a band of width
// W it blends the pair's tiles by smoothstep(-W/2, W/2, distance), moved by
// the tiles' heights when height blending is on.

#include <sierra/render/Surface.h>
#include <sierra/terrain/Heightfield.h>
#include <sierra/zones/Palette.h>
#include <sierra/zones/ZoneMap.h>

#include <memory>
#include <string>

namespace sierra::render {

enum class ZoneDebugView { None, Zones, Bands };

struct ZoneSurfaceDesc {
    std::string map = "auto";  // "auto" or a zone-map PNG
    // The surface types and their tiles (the programs read a palette file
    // with scene::loadPalette), and the name messages give the palette.
    zones::Palette palette;
    std::string paletteName = "the palette";
    float band = -1.0f;       // band width in zone-map pixels; < 0 = the palette's; 0 = none
    float epsilon = 0.5f;     // borderline simplification, zone-map pixels
    bool heightBlend = true;  // tile heights move the transition inside a band
    bool triplanar = false;   // tiles projected along the normal's axes on steep slopes
    bool variation = true;    // a slow warp of the tile coordinates against visible repetition
    ZoneDebugView debugView = ZoneDebugView::None;
    zones::AutoZoneDesc autoZones;  // thresholds for map "auto" (seaLevel in stored units)
    // Grid samples a zone-map pixel spans: 1 for a map of the grid itself,
    // the stride for one of an overview (a tiled terrain's). The palette's
    // tile sizes and band widths are in zone-map pixels at 1; the tiles keep
    // their size in grid samples, the bands their width in map pixels.
    int samplesPerPixel = 1;
};

// What was built, for the log and the debug panel.
struct ZoneSurfaceInfo {
    int mapWidth = 0, mapHeight = 0;
    int zoneCount = 0;  // surface types of the palette
    size_t borderVertices = 0, borderEdges = 0;
    int texelsPerPixel = 1;  // distance field resolution
    float band = 0.0f;       // band width used, zone-map pixels
    double buildMs = 0.0;    // zone map, borderlines and field
};

// `field` is the heightfield the terrain was built from (its real samples are
// zoned for map "auto"). Throws sierra::Error for a bad palette, zone map or tile.
std::unique_ptr<Surface> makeZoneSurface(const TerrainGpu& terrain,
                                         const terrain::Heightfield& field,
                                         const ZoneSurfaceDesc& desc,
                                         ZoneSurfaceInfo* info = nullptr);
// The same over `real`, the terrain's real samples and nothing else (for map
// "auto"; an overview of a tiled terrain, with desc.samplesPerPixel its stride).
std::unique_ptr<Surface> makeZoneSurface(const terrain::Heightfield& real,
                                         const ZoneSurfaceDesc& desc,
                                         ZoneSurfaceInfo* info = nullptr);

}  // namespace sierra::render
