#pragma once
// The distance-to-border field for the real-time texturing pass: per texel the
// zone it lies in, the two zones of the nearest borderline and the signed
// distance to it, built from the vectorised borderlines (not the raw pixels).
//
// Upload (one texel per entry, row 0 = map top = texture row 0):
//   zone:           R8UI, nearest filtering: the zone that owns the texel centre
//   lowZone/highZone: R8UI (or one RG8UI), nearest: the zone pair of the nearest borderline
//   signedDistance: R32F (or R16F), linear filtering: texels to the nearest borderline,
//                   < 0 on lowZone's side, > 0 on highZone's side
// Blend in a band of width W zone-map pixels: weight of highZone =
//   smoothstep(-W/2, W/2, signedDistance / texelsPerPixel), lowZone gets 1 - weight;
// away from every band exactly one zone's tile is sampled.

#include <sierra/zones/Borderlines.h>

#include <cstdint>
#include <vector>

namespace sierra::zones {

struct BorderFieldDesc {
    int texelsPerPixel = 1;  // field resolution in texels per zone-map pixel, 1..8
};

struct BorderField {
    int width = 0;   // mapWidth * texelsPerPixel
    int height = 0;  // mapHeight * texelsPerPixel
    int texelsPerPixel = 1;
    // Texel (i, j) has its centre at ((i + 0.5) / texelsPerPixel, (j + 0.5) / texelsPerPixel)
    // in zone-map pixel units; all arrays are row-major, width * height entries.
    std::vector<uint8_t> zone;
    std::vector<uint8_t> lowZone;  // lowZone == highZone == zone where the map has no borderline
    std::vector<uint8_t> highZone;
    std::vector<float>
        signedDistance;  // texels; a very large value (1e9) where there is no borderline
};

// Builds the field from the borderlines between zones (frame edges and band
// copies are ignored: pass the lines before doubling, the band is |d| < W/2).
// Zones come from an exact scanline fill of the edge polygons; distances from a
// two-pass propagation of the nearest segment with exact point-segment distances.
BorderField buildBorderField(const Borderlines& lines, const BorderFieldDesc& desc = {});

}  // namespace sierra::zones
