// Surface function: zone tiles with blended transition bands (engine:
// render/ZoneSurface.h). Zone-map coordinates: x right, y down (= world +z),
// the map's pixel centres on the terrain's real samples.
// The surface's options are compiled in (ZoneSurface's defines), not read from
// uniforms: llvmpipe (Mesa 22.3) runs every branch of a shader with the lanes
// that skip it masked off, so an option that is off still cost its
// instructions in every fragment when it was tested at run time.
//   SIERRA_ZONE_TRIPLANAR     tiles projected along the normal's axes on steep slopes
//   SIERRA_ZONE_VARIATION     the tile warp against visible repetition
//   SIERRA_ZONE_HEIGHT_BLEND  the tiles' heights move the transition in a band
//   SIERRA_ZONE_DEBUG         0 none (default), 1 zone colours, 2 band weights
#ifndef SIERRA_ZONE_DEBUG
#define SIERRA_ZONE_DEBUG 0
#endif
layout(binding = 3) uniform sampler2DArray uTiles;  // layer = zone id; rgb albedo, a height
#include "zone_field.glsl"

// Against visible repetition, from the one sample a zone already takes: a slow
// warp of the tile coordinates by up to kWarp tile repetitions, two nested
// waves of the zone-map position with periods of about 170-420 pixels, so
// repeated features no longer line up on a lattice. The warp's slope is at
// most about 0.05 per zone-map pixel; times kWarp and the largest tile size
// (32 pixels in the default palette) each entry of the mapping's Jacobian
// moves by at most about 0.4, so the warped tile never folds.
const float kWarp = 0.25;  // tile repetitions
// A sine-like wave of period 2 pi, amplitude 1, continuous in value and slope
// (two parabolas a period): llvmpipe's sin is a long polynomial with range
// reduction, and the warp needs no more than a smooth wiggle.
vec2 wave(vec2 x) {
    vec2 t = 2.0 * fract(x * (0.5 / 3.14159265)) - 1.0;  // -1..1 over a period
    return -4.0 * t * (1.0 - abs(t));
}
vec2 tileWarp(vec2 m) {
    vec2 inner = wave(vec2(m.x * 0.015, m.y * 0.019));
    return wave(vec2(m.y * 0.037 + 1.7 * inner.x, m.x * 0.031 + 1.3 * inner.y));
}

// One filtered tile sample; grad: d(uv)/dx in xy, d(uv)/dy in zw, taken where
// control flow is uniform (surfaceAlbedo). On llvmpipe (Mesa 22.3) the array
// has no anisotropy and the nearest mip level (ZoneSurface): with anisotropy 8
// a 1080p frame took minutes, and the one bilinear lookup of the nearest level
// costs fewer instructions than the shader's own four-texel filter did
// (docs/zones.md, "Frame cost").
vec4 tileSample(int zone, vec2 uv, vec4 grad) {
    return textureGrad(uTiles, vec3(uv, float(zone)), grad.xy, grad.zw);
}

// The tiles of a fragment: a the first zone's (the fragment's own away from
// bands), b the band's second zone's (weight 0 away from bands).
// Planar (the seed document's mapping): two tileSamples, straight.
// Triplanar (on cliffs too): one loop over sample jobs, zones (1, or 2 in a
// band) x projections (1, or 3 on a steep slope), each job one tileSample
// whose weighted colour adds to its zone's sum. llvmpipe (Mesa 22.3) runs
// every branch of a shader with the lanes that skip it masked off, so written
// with ifs every fragment paid for every tile sample of every call site; a
// loop runs only as many times as the block's busiest pixel needs. For the
// planar pair that bookkeeping costs more than the second sample.
// scales: the two zones' tile repetitions per zone-map pixel (a, b).
// mapGrad: the zone-map position's screen derivatives; worldGrad: the world
// position's (x and y derivatives of the xyz); warp: tileWarp at the fragment
// in tile repetitions, or 0.
void zoneTiles(int zones, int low, int high, vec2 scales, vec2 mapXY, vec4 mapGrad, vec2 warp, vec3 world,
               mat2x3 worldGrad, Ground g, out vec4 a, out vec4 b) {
#ifdef SIERRA_ZONE_TRIPLANAR
    a = vec4(0.0);
    b = vec4(0.0);
    bool sides = g.slope >= 0.05;
    int projections = sides ? 3 : 1;
    vec3 wp = vec3(0.0, 1.0, 0.0);  // projection weights: x side (zy), top (xz), z side (xy)
    if (sides) {
        wp = pow(abs(g.normal), vec3(4.0));
        wp /= wp.x + wp.y + wp.z;
    }
    // World in zone-map pixels (heights too), before the tile's size.
    float worldScale = (uZoneMap.x - 1.0) / max(uSpacingValid.z, 1e-6);
    int jobs = zones * projections;
    // Job j = zi * projections + projection, counted up without integer
    // division (which llvmpipe runs lane by lane).
    int projection = 0, zi = 0;
    for (int j = 0; j < jobs; ++j) {
        int zone = zi == 0 ? low : high;
        float scale = zi == 0 ? scales.x : scales.y;
        vec2 uv = mapXY;
        vec4 grad = mapGrad;
        float weight = wp.y;
        if (projection > 0) {
            vec3 p = world * worldScale;
            mat2x3 pg = worldGrad * worldScale;
            uv = projection == 1 ? p.zy : p.xy;
            grad = projection == 1 ? vec4(pg[0].zy, pg[1].zy) : vec4(pg[0].xy, pg[1].xy);
            weight = projection == 1 ? wp.x : wp.z;
        }
        vec4 c = tileSample(zone, uv * scale + warp, grad * scale) * weight;
        if (zi == 0) a += c;
        else b += c;
        if (++projection == projections) {
            projection = 0;
            ++zi;
        }
    }
#else
    // Planar: both zones' tiles, straight (b is unused away from bands,
    // where its weight is 0). A loop of one pass away from bands and two in a
    // band cost more: llvmpipe's loop bookkeeping (masked stores of a and b,
    // the per-pass selects) took more instructions than the second sample
    // (docs/zones.md, "Frame cost").
    a = tileSample(low, mapXY * scales.x + warp, mapGrad * scales.x);
    b = tileSample(high, mapXY * scales.y + warp, mapGrad * scales.y);
#endif
}

vec3 surfaceAlbedo(vec3 world, Ground g) {
    vec2 m = zoneMapPosition(world);
    // Derivatives here, where control flow is still uniform.
    vec4 mGrad = vec4(dFdx(m), dFdy(m));
    mat2x3 wGrad = mat2x3(dFdx(world), dFdy(world));
    int zone;
    uvec2 pair;
    float d;
    zoneField(m, zone, pair, d);
    float halfBand = 0.5 * uZoneMap.w;
    bool inBand = halfBand > 0.0 && pair.x != pair.y && abs(d) < halfBand;
    float weight = inBand ? smoothstep(-halfBand, halfBand, d) : 0.0;  // of the pair's second zone
#if SIERRA_ZONE_DEBUG == 1  // zones: flat palette colours
    return uZoneColour[zone].rgb;
#elif SIERRA_ZONE_DEBUG == 2  // bands: the blend weight, black outside every band
    return inBand ? mix(vec3(0.9, 0.2, 0.1), vec3(0.1, 0.8, 0.2), weight) : vec3(0.05);
#else
    // One tile set away from borders, two in a band.
    int low = inBand ? int(pair.x) : zone, high = int(pair.y);
#ifdef SIERRA_ZONE_VARIATION
    vec2 warp = kWarp * tileWarp(m);
#else
    vec2 warp = vec2(0.0);
#endif
    vec4 a, b;
    // The two zones' tile settings (scale, height blend), read once each.
    vec2 lowTile = uZoneTile[low].xy, highTile = uZoneTile[high].xy;
    zoneTiles(inBand ? 2 : 1, low, high, vec2(lowTile.x, highTile.x), m, mGrad, warp, world, wGrad, g, a, b);
#ifdef SIERRA_ZONE_HEIGHT_BLEND
    {
        // Height blending: where one tile stands higher (stones in sand) it
        // shows through earlier; the shift vanishes at the band's edges.
        // No `if (inBand)`: llvmpipe runs it masked for every fragment anyway,
        // and outside bands the weight 0 stays 0 through both steps.
        float strength = 0.5 * (lowTile.y + highTile.y);
        float shift = strength * (b.a - a.a) * 4.0 * weight * (1.0 - weight);
        weight = clamp(weight + shift, 0.0, 1.0);
        weight = smoothstep(0.15, 0.85, weight);
    }
#endif
    return mix(a.rgb, b.rgb, weight);
#endif
}
