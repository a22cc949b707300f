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
//   unit 4  zone id per field texel (R8UI, nearest)
//   unit 5  the zone pair of the nearest borderline (RG8UI, nearest)
//   unit 6  signed distance to that borderline in texels (R32F, linear)
//   block 2 per-zone tile size, height blend and debug colour; map size, band
//           width, flags
// A fragment away from every band samples one zone's tiles; in a band of width
// W it blends the pair's tiles by smoothstep(-W/2, W/2, distance), moved by
// the tiles' heights when height blending is on.

#include <sierra/render/Surface.h>
#include <sierra/terrain/Heightfield.h>
#include <sierra/zones/ZoneMap.h>

#include <memory>
#include <string>

namespace sierra::render {

enum class ZoneDebugView { None, Zones, Bands };

struct ZoneSurfaceDesc {
    std::string map = "auto";  // "auto" or a zone-map PNG
    std::string palette;       // palette JSON (tile paths relative to it)
    float band = -1.0f;        // band width in zone-map pixels; < 0 = the palette's; 0 = none
    float epsilon = 0.5f;      // borderline simplification, zone-map pixels
    bool heightBlend = true;   // tile heights move the transition inside a band
    bool triplanar = false;    // tiles projected along the normal's axes on steep slopes
    bool variation = true;     // a second, rotated sample against visible repetition
    ZoneDebugView debugView = ZoneDebugView::None;
    zones::AutoZoneDesc autoZones;  // thresholds for map "auto" (seaLevel in stored units)
};

// What was built, for the log and the debug panel.
struct ZoneSurfaceInfo {
    int mapWidth = 0, mapHeight = 0;
    int zoneCount = 0;          // surface types of the palette
    size_t borderVertices = 0, borderEdges = 0;
    int texelsPerPixel = 1;     // distance field resolution
    float band = 0.0f;          // band width used, zone-map pixels
    double buildMs = 0.0;       // zone map, borderlines and field
};

// `field` is the heightfield the terrain was built from (its real samples are
// zoned for map "auto"). Throws sierra::Error for a bad palette, zone map or tile.
std::unique_ptr<Surface> makeZoneSurface(const TerrainGpu& terrain, const terrain::Heightfield& field,
                                         const ZoneSurfaceDesc& desc, ZoneSurfaceInfo* info = nullptr);

}  // namespace sierra::render
