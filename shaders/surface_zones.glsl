// Surface function: zone tiles with blended transition bands (engine:
// render/ZoneSurface.h). Zone-map coordinates: x right, y down (= world +z),
// the map's pixel centres on the terrain's real samples.
layout(binding = 3) uniform sampler2DArray uTiles;    // layer = zone id; rgb albedo, a height
layout(binding = 4) uniform usampler2D uZoneId;       // the zone owning each field texel
layout(binding = 5) uniform usampler2D uZonePair;     // the zone pair of the nearest borderline
layout(binding = 6) uniform sampler2D uZoneDistance;  // signed texels to it: < 0 on the pair's first zone's side

layout(std140, binding = 2) uniform Zones {
    vec4 uZoneMap;    // xy: zone-map size in pixels; z: field texels per pixel; w: band width in pixels
    vec4 uZoneFlags;  // x: height blend; y: triplanar; z: variation; w: debug view (0 none, 1 zones, 2 bands)
    vec4 uZoneTile[256];    // x: zone-map pixels per tile repetition; y: height blend 0..1
    vec4 uZoneColour[256];  // rgb: the zone's palette colour
};

vec2 zoneMapPosition(vec3 world) {
    return world.xz / uSpacingValid.zw * (uZoneMap.xy - 1.0) + 0.5;
}

// A cheap smooth value in [0, 1] that varies over a few tile repetitions.
float tileVariation(vec2 p) {
    return 0.5 + 0.25 * (sin(p.x * 0.37 + 1.3 * sin(p.y * 0.23)) + sin(p.y * 0.31 + 1.7 * sin(p.x * 0.19)));
}

// One filtered tile sample; `grad` holds d(uv)/dx and d(uv)/dy (taken where
// control flow is uniform, see surfaceAlbedo).
vec4 tileSample(int zone, vec2 uv, vec4 grad) {
#ifdef SIERRA_MANUAL_TILE_FILTER
    // llvmpipe (Mesa 22.3): with anisotropic filtering on, texture() and
    // textureGrad on the array took minutes a frame; without it they cost
    // about as much as this (ZoneSurface turns anisotropy off there), and this
    // filter is what the goldens were made with. The mip level comes from the
    // gradients and four texelFetch calls are blended bilinearly.
    vec2 size0 = vec2(textureSize(uTiles, 0).xy);
    vec2 dx = grad.xy * size0, dy = grad.zw * size0;
    float lod = max(0.5 * log2(max(dot(dx, dx), dot(dy, dy))), 0.0);
    int level = min(int(lod + 0.5), textureQueryLevels(uTiles) - 1);
    ivec2 size = max(ivec2(size0) >> level, ivec2(1));
    vec2 p = uv * vec2(size) - 0.5;
    vec2 f = fract(p);
    ivec2 i0 = ivec2(floor(p));
    // Tiles are square powers of two (ZoneSurface checks): wrap by a mask, as
    // llvmpipe runs an integer % lane by lane.
    ivec2 a = i0 & (size - 1);
    ivec2 b = (i0 + 1) & (size - 1);
    vec4 c00 = texelFetch(uTiles, ivec3(a.x, a.y, zone), level);
    vec4 c10 = texelFetch(uTiles, ivec3(b.x, a.y, zone), level);
    vec4 c01 = texelFetch(uTiles, ivec3(a.x, b.y, zone), level);
    vec4 c11 = texelFetch(uTiles, ivec3(b.x, b.y, zone), level);
    return mix(mix(c00, c10, f.x), mix(c01, c11, f.x), f.y);
#else
    return textureGrad(uTiles, vec3(uv, float(zone)), grad.xy, grad.zw);
#endif
}

// The tiles of a fragment as one loop over sample jobs: zones (1, or 2 in a
// band) x projections (1, or 3 with triplanar on a steep slope) x samples (1,
// or 2 with the variation), each job one tileSample whose weighted colour adds
// to its zone's sum. Why one loop: llvmpipe (Mesa 22.3) runs every branch of a
// shader with the lanes that skip it masked off, so written with ifs every
// fragment paid for all 18 tile samples of the three call sites and the zone frame
// cost about 10x the hypsometric one at 1920x1080; a loop runs only as many
// times as the block's busiest pixel needs (2 away from bands with the
// variation, 4 in a band).
// mapGrad: the zone-map position's screen derivatives; worldGrad: the world
// position's (x and y derivatives of the xyz). Planar mapping is the seed
// document's; triplanar takes the tile along the normal on cliffs too.
void zoneTiles(int zones, int low, int high, vec2 mapXY, vec4 mapGrad, vec3 world, mat2x3 worldGrad, Ground g,
               out vec4 a, out vec4 b) {
    a = vec4(0.0);
    b = vec4(0.0);
    bool sides = uZoneFlags.y > 0.5 && g.slope >= 0.05;
    int projections = sides ? 3 : 1;
    int variations = uZoneFlags.z > 0.5 ? 2 : 1;
    vec3 wp = vec3(0.0, 1.0, 0.0);  // projection weights: x side (zy), top (xz), z side (xy)
    if (sides) {
        wp = pow(abs(g.normal), vec3(4.0));
        wp /= wp.x + wp.y + wp.z;
    }
    // World in zone-map pixels (heights too), before the tile's size.
    float worldScale = (uZoneMap.x - 1.0) / max(uSpacingValid.z, 1e-6);
    int jobs = zones * projections * variations;
    // Job j = (zi * projections + projection) * variations + v, counted up
    // without integer division (which llvmpipe runs lane by lane).
    int v = 0, projection = 0, zi = 0;
    for (int j = 0; j < jobs; ++j) {
        int zone = zi == 0 ? low : high;
        float inverseSize = 1.0 / max(uZoneTile[zone].x, 1e-3);
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
        uv *= inverseSize;
        grad *= inverseSize;
        float variation = variations > 1 ? 0.45 * tileVariation(uv) : 0.0;
        if (v == 1) {
            // A second sample, rotated and at another scale, mixed in by a slow
            // variation: the eye no longer finds the repeat.
            const mat2 turn = mat2(0.8, 0.6, -0.6, 0.8);
            uv = turn * uv * 0.61 + 0.37;
            grad = vec4(turn * grad.xy, turn * grad.zw) * 0.61;
            weight *= variation;
        } else {
            weight *= 1.0 - variation;
        }
        vec4 c = tileSample(zone, uv, grad) * weight;
        if (zi == 0) a += c;
        else b += c;
        if (++v == variations) {
            v = 0;
            if (++projection == projections) {
                projection = 0;
                ++zi;
            }
        }
    }
}

// Signed distance (zone-map pixels) to the borderline of `pair`, bilinear over
// the four field texels around m, for a fragment of `zone` that the filtered
// field puts inside a band. Each texel holds the distance to its own nearest
// borderline, signed by that line's pair; where two texels' nearest lines are
// of different pairs (a ridge between two borderlines) the hardware-filtered
// value can pass through 0 far from any border when the zone lies on the
// negative side of one pair and the positive side of the other: a line of
// band-blended pixels appeared along such ridges (dotted at the frame's
// resolution). A texel of another pair is taken at its own distance (a lower
// bound of its distance to this pair's line) with the sign of its zone's side
// of this pair, or of this fragment's side when its zone is in neither.
// `texels`: 4 in a band, 0 elsewhere (the result is then unused). A loop and
// not an if, so a block with no band pixel pays one masked iteration instead
// of all four (see zoneTiles).
float pairDistance(vec2 m, uvec2 pair, uint zone, int texels) {
    vec2 p = m * uZoneMap.z - 0.5;
    ivec2 i0 = ivec2(floor(p));
    vec2 f = p - vec2(i0);
    ivec2 last = textureSize(uZoneDistance, 0) - 1;
    float ownSign = zone == pair.x ? -1.0 : 1.0;
    vec4 d = vec4(0.0);
    for (int k = 0; k < texels; ++k) {
        ivec2 t = clamp(i0 + ivec2(k & 1, k >> 1), ivec2(0), last);
        float dk = texelFetch(uZoneDistance, t, 0).r;
        uvec2 pk = texelFetch(uZonePair, t, 0).rg;
        if (pk != pair) {
            // The texel's zone from its own pair and sign (no third fetch).
            uint zk = dk < 0.0 ? pk.x : pk.y;
            dk = abs(dk) * (zk == pair.x ? -1.0 : zk == pair.y ? 1.0 : ownSign);
        }
        d[k] = dk;
    }
    return mix(mix(d.x, d.y, f.x), mix(d.z, d.w, f.x), f.y) / uZoneMap.z;
}

vec3 surfaceAlbedo(vec3 world, Ground g) {
    vec2 m = zoneMapPosition(world);
    // Derivatives here, where control flow is still uniform.
    vec4 mGrad = vec4(dFdx(m), dFdy(m));
    mat2x3 wGrad = mat2x3(dFdx(world), dFdy(world));
    ivec2 size = ivec2(uZoneMap.xy * uZoneMap.z);
    ivec2 texel = clamp(ivec2(floor(m * uZoneMap.z)), ivec2(0), size - 1);
    int zone = int(texelFetch(uZoneId, texel, 0).r);
    uvec2 pair = texelFetch(uZonePair, texel, 0).rg;
    float halfBand = 0.5 * uZoneMap.w;
    float d = texture(uZoneDistance, m / uZoneMap.xy).r / uZoneMap.z;  // zone-map pixels
    bool inBand = halfBand > 0.0 && pair.x != pair.y && abs(d) < halfBand;
    // Only where the filtered field says "band" (a few per cent of the
    // pixels): the exact value, free of the ridge artefact (pairDistance).
    float exact = pairDistance(m, pair, uint(zone), inBand ? 4 : 0);
    if (inBand) {
        d = exact;
        inBand = abs(d) < halfBand;
    }
    float weight = inBand ? smoothstep(-halfBand, halfBand, d) : 0.0;  // of the pair's second zone

    // One tile set away from borders, two in a band, none in the debug views.
    int tiles = uZoneFlags.w > 0.5 ? 0 : inBand ? 2 : 1;
    int low = inBand ? int(pair.x) : zone, high = int(pair.y);
    vec4 a, b;
    zoneTiles(tiles, low, high, m, mGrad, world, wGrad, g, a, b);
    if (tiles == 2 && uZoneFlags.x > 0.5) {
        // Height blending: where one tile stands higher (stones in sand) it
        // shows through earlier; the shift vanishes at the band's edges.
        float strength = 0.5 * (uZoneTile[low].y + uZoneTile[high].y);
        float shift = strength * (b.a - a.a) * 4.0 * weight * (1.0 - weight);
        weight = clamp(weight + shift, 0.0, 1.0);
        weight = smoothstep(0.15, 0.85, weight);
    }

    if (uZoneFlags.w > 1.5) {  // bands: the blend weight, black outside every band
        return inBand ? mix(vec3(0.9, 0.2, 0.1), vec3(0.1, 0.8, 0.2), weight) : vec3(0.05);
    }
    if (uZoneFlags.w > 0.5) return uZoneColour[zone].rgb;  // zones: flat palette colours
    return mix(a.rgb, b.rgb, weight);
}
