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
    // llvmpipe (Mesa 22.3): filtered texture() on a 2D array texture under
    // magnification runs about a thousand times slower than texelFetch, so a
    // close-up takes minutes. Here the mip level comes from the gradients and
    // four texelFetch calls are blended bilinearly (no anisotropy).
    vec2 size0 = vec2(textureSize(uTiles, 0).xy);
    vec2 dx = grad.xy * size0, dy = grad.zw * size0;
    float lod = max(0.5 * log2(max(dot(dx, dx), dot(dy, dy))), 0.0);
    int level = min(int(lod + 0.5), textureQueryLevels(uTiles) - 1);
    ivec2 size = max(ivec2(size0) >> level, ivec2(1));
    vec2 p = uv * vec2(size) - 0.5;
    vec2 f = fract(p);
    ivec2 i0 = ivec2(floor(p));
    ivec2 a = ((i0 % size) + size) % size;
    ivec2 b = ((i0 + 1) % size + size) % size;
    vec4 c00 = texelFetch(uTiles, ivec3(a.x, a.y, zone), level);
    vec4 c10 = texelFetch(uTiles, ivec3(b.x, a.y, zone), level);
    vec4 c01 = texelFetch(uTiles, ivec3(a.x, b.y, zone), level);
    vec4 c11 = texelFetch(uTiles, ivec3(b.x, b.y, zone), level);
    return mix(mix(c00, c10, f.x), mix(c01, c11, f.x), f.y);
#else
    return textureGrad(uTiles, vec3(uv, float(zone)), grad.xy, grad.zw);
#endif
}

vec4 planarTile(int zone, vec2 uv, vec4 grad) {
    vec4 c = tileSample(zone, uv, grad);
    if (uZoneFlags.z > 0.5) {
        // A second sample, rotated and at another scale, mixed in by a slow
        // variation: the eye no longer finds the repeat.
        const mat2 turn = mat2(0.8, 0.6, -0.6, 0.8);
        vec4 other = tileSample(zone, turn * uv * 0.61 + 0.37, vec4(turn * grad.xy, turn * grad.zw) * 0.61);
        c = mix(c, other, 0.45 * tileVariation(uv));
    }
    return c;
}

// The tile of `zone` at a map position: planar by default (the document's
// mapping); with triplanar on, steep slopes take the tile along their normal
// too, so cliffs do not stretch it.
// mapGrad: the zone-map position's screen derivatives; worldGrad: the
// world position's (x and y derivatives of the xyz).
vec4 zoneTile(int zone, vec2 mapXY, vec4 mapGrad, vec3 world, mat2x3 worldGrad, Ground g) {
    float size = max(uZoneTile[zone].x, 1e-3);
    vec4 top = planarTile(zone, mapXY / size, mapGrad / size);
    if (uZoneFlags.y < 0.5 || g.slope < 0.05) return top;
    // World in zone-map pixels, heights too.
    float scale = (uZoneMap.x - 1.0) / max(uSpacingValid.z, 1e-6) / size;
    vec3 p = world * scale;
    mat2x3 pg = worldGrad * scale;
    vec3 w = pow(abs(g.normal), vec3(4.0));
    w /= w.x + w.y + w.z;
    return top * w.y + planarTile(zone, p.zy, vec4(pg[0].zy, pg[1].zy)) * w.x +
           planarTile(zone, p.xy, vec4(pg[0].xy, pg[1].xy)) * w.z;
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
float pairDistance(vec2 m, uvec2 pair, uint zone) {
    vec2 p = m * uZoneMap.z - 0.5;
    ivec2 i0 = ivec2(floor(p));
    vec2 f = p - vec2(i0);
    ivec2 last = textureSize(uZoneDistance, 0) - 1;
    float ownSign = zone == pair.x ? -1.0 : 1.0;
    vec4 d;
    for (int k = 0; k < 4; ++k) {
        ivec2 t = clamp(i0 + ivec2(k & 1, k >> 1), ivec2(0), last);
        float dk = texelFetch(uZoneDistance, t, 0).r;
        if (texelFetch(uZonePair, t, 0).rg != pair) {
            uint zk = texelFetch(uZoneId, t, 0).r;
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
    if (inBand) {
        d = pairDistance(m, pair, uint(zone));
        inBand = abs(d) < halfBand;
    }
    float weight = inBand ? smoothstep(-halfBand, halfBand, d) : 0.0;  // of the pair's second zone

    if (uZoneFlags.w > 1.5) {  // bands: the blend weight, black outside every band
        return inBand ? mix(vec3(0.9, 0.2, 0.1), vec3(0.1, 0.8, 0.2), weight) : vec3(0.05);
    }
    if (uZoneFlags.w > 0.5) return uZoneColour[zone].rgb;  // zones: flat palette colours

    if (!inBand) return zoneTile(zone, m, mGrad, world, wGrad, g).rgb;  // one tile set away from borders
    int low = int(pair.x), high = int(pair.y);
    vec4 a = zoneTile(low, m, mGrad, world, wGrad, g);
    vec4 b = zoneTile(high, m, mGrad, world, wGrad, g);
    if (uZoneFlags.x > 0.5) {
        // Height blending: where one tile stands higher (stones in sand) it
        // shows through earlier; the shift vanishes at the band's edges.
        float strength = 0.5 * (uZoneTile[low].y + uZoneTile[high].y);
        float shift = strength * (b.a - a.a) * 4.0 * weight * (1.0 - weight);
        weight = clamp(weight + shift, 0.0, 1.0);
        weight = smoothstep(0.15, 0.85, weight);
    }
    return mix(a.rgb, b.rgb, weight);
}
