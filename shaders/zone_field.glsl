// The zone field of the zone surface (engine: render/ZoneSurface.h) and the
// zone of a ground position, shared by the surface function
// (surface_zones.glsl) and the dataset labels (labels.frag). Zone-map
// coordinates: x right, y down (= world +z), the map's pixel centres on the
// terrain's real samples.

// The zone field, one 32-bit texel each (ZoneSurface packs it): bits 0-7 the
// first (lower) zone of the nearest borderline's pair, 8-15 the second, 16-31
// the signed distance to that borderline in texels as a half float, < 0 on the
// first zone's side. The texel's own zone follows: the pair's first zone where
// the sign bit is set, else its second (the two are equal away from borderlines).
layout(binding = 4) uniform usampler2D uZoneField;

layout(std140, binding = 2) uniform Zones {
    vec4 uZoneMap;    // xy: zone-map size in pixels; z: field texels per pixel; w: band width in pixels
    vec4 uZoneFieldStep;  // xy: 1 / the field's size in texels
    vec4 uZoneTile[256];    // x: 1 / (zone-map pixels per tile repetition); y: height blend 0..1
    vec4 uZoneColour[256];  // rgb: the zone's palette colour
};

vec2 zoneMapPosition(vec3 world) {
    return world.xz / uSpacingValid.zw * (uZoneMap.xy - 1.0) + 0.5;
}

// The zone field around zone-map position m, from one textureGather of the
// four texels around it (no branch, no loop): the zone of the nearest texel,
// the pair of its nearest borderline, and the signed distance to that line in
// zone-map pixels, bilinear over the four texels. Each texel holds the
// distance to its own nearest borderline, signed by that line's pair; where
// two texels' nearest lines are of different pairs (a ridge between two
// borderlines) the plain bilinear value can pass through 0 far from any
// border when the zone lies on the negative side of one pair and the positive
// side of the other: a line of band-blended pixels appeared along such ridges
// (dotted at the frame's resolution). So a texel of another pair is taken at
// its own distance (a lower bound of its distance to this pair's line) with the
// sign of its zone's side of this pair, or of this fragment's side when its
// zone is in neither. A texel of this pair is that too (its zone is the side
// its sign gives), so every texel is |distance| times its side, with no test
// of which pair it holds; where the fragment's pair is one zone twice (no
// borderline near) the distance is not used.
void zoneField(vec2 m, out int zone, out uvec2 pair, out float distance) {
    vec2 p = m * uZoneMap.z - 0.5;
    vec2 i0 = floor(p);
    vec2 f = p - i0;
    // The footprint's centre, so the gather's texels are exactly i0 .. i0 + 1
    // (clamped at the field's edges, as the texture clamps).
    uvec4 t = textureGather(uZoneField, (i0 + 1.0) * uZoneFieldStep.xy);  // (0,1), (1,1), (1,0), (0,0)
    uvec4 lo = t & 255u, hi = (t >> 8u) & 255u;
    bvec4 negative = notEqual(t & 0x80000000u, uvec4(0u));
    // The four halves, two to a conversion.
    vec4 d = vec4(unpackHalf2x16((t.x >> 16u) | (t.y & 0xffff0000u)),
                  unpackHalf2x16((t.z >> 16u) | (t.w & 0xffff0000u)));
    uvec4 zk = mix(hi, lo, negative);
    // The nearest texel, (0, 0) + (f >= 0.5), selected as one texel: its pair
    // and sign are then read once, not from four vectors by a per-pixel index.
    bool right = f.x >= 0.5, down = f.y >= 0.5;
    uint tk = down ? (right ? t.y : t.x) : (right ? t.z : t.w);
    pair = uvec2(tk & 255u, (tk >> 8u) & 255u);
    bool ownNegative = (tk & 0x80000000u) != 0u;
    zone = int(ownNegative ? pair.x : pair.y);
    float ownSign = ownNegative ? -1.0 : 1.0;
    vec4 side = mix(mix(vec4(ownSign), vec4(1.0), equal(zk, uvec4(pair.y))), vec4(-1.0), equal(zk, uvec4(pair.x)));
    d = abs(d) * side;
    distance = mix(mix(d.w, d.z, f.x), mix(d.x, d.y, f.x), f.y) / uZoneMap.z;
}
