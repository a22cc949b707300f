// Shared by the terrain stages: the terrain's data textures and uniform block
// (engine: render/TerrainGpu.h).
#include "morph.glsl"
//
// uData holds one texel per grid sample (i, j) of the drawn surface (water
// flattened to sea level):
//   r: world height, g: geomorph base (the mean of the world heights of the
//   hypotenuse endpoints the vertex bisects), b: saturated object-space error
//   (world units), a: nested bounding radius (world units).
layout(binding = 0) uniform sampler2D uData;
// The true world heights (the ground below the water too), linearly filtered.
layout(binding = 2) uniform sampler2D uHeights;

layout(std140, binding = 1) uniform Terrain {
    ivec4 uGrid;          // x: samples per side, 2^n + 1
    vec4 uSpacingValid;   // xy: world distance between samples along x and z; zw: world x, z of the last real sample
    vec4 uHeightInfo;     // x: world sea level; y: 1 with water; z, w: lowest and highest world height
};

vec2 terrainSpacing() { return uSpacingValid.xy; }

// True for fragments over the padding added to reach (2^n+1)^2 samples.
bool overPadding(vec3 world) {
    return any(greaterThan(world.xz, uSpacingValid.zw + 1e-3 * uSpacingValid.xy));
}

vec3 gridToWorld(ivec2 ij, float height) {
    return vec3(float(ij.x) * uSpacingValid.x, height, float(ij.y) * uSpacingValid.y);
}

// The true height, its normal and the water flag at a ground position, from
// the full-resolution heights: a simplified mesh shades like the full grid.
// A surface whose colour does not follow the height (zone tiles: only the
// water flag reads it) defines SIERRA_GROUND_BILINEAR_HEIGHT: the height is
// then one bilinear fetch instead of smoothHeight's four and its B-spline
// weights (about a tenth of the zone frame's shader instructions on
// llvmpipe), and the water's edge, where the normal turns flat, follows the
// bilinear coast (cell-sized corners) instead of the round one.
struct Ground {
    float height;  // world units
    vec3 normal;   // unit
    float slope;   // 0 flat .. 1 vertical (1 - normal.y)
    bool water;    // below sea level (with water on)
};

// The height at a ground position by a cubic B-spline through the samples
// (four bilinear fetches): contours such as the coast come out round at any
// grid resolution, where bilinear interpolation draws them as cell-sized
// diamonds and squares.
float smoothHeight(vec2 xz) {
    vec2 p = xz / uSpacingValid.xy;  // in samples
    vec2 cell = floor(p);
    vec2 f = p - cell;
    vec2 f2 = f * f, f3 = f2 * f;
    // B-spline weights of the 4 samples along each axis.
    vec2 w0 = (1.0 - 3.0 * f + 3.0 * f2 - f3) / 6.0;
    vec2 w1 = (4.0 - 6.0 * f2 + 3.0 * f3) / 6.0;
    vec2 w2 = (1.0 + 3.0 * f + 3.0 * f2 - 3.0 * f3) / 6.0;
    vec2 w3 = f3 / 6.0;
    vec2 g0 = w0 + w1, g1 = w2 + w3;
    vec2 texel = 1.0 / vec2(uGrid.x);
    // Bilinear fetches between samples -1..0 and 1..2 weigh each pair exactly.
    vec2 t0 = (cell - 1.0 + w1 / g0 + 0.5) * texel;
    vec2 t1 = (cell + 1.0 + w3 / g1 + 0.5) * texel;
    return g0.y * (g0.x * texture(uHeights, vec2(t0.x, t0.y)).r + g1.x * texture(uHeights, vec2(t1.x, t0.y)).r) +
           g1.y * (g0.x * texture(uHeights, vec2(t0.x, t1.y)).r + g1.x * texture(uHeights, vec2(t1.x, t1.y)).r);
}

// The texture coordinate of a ground position in a texture with one texel per
// grid sample (uHeights, and the terrain pass's relief fields): texel centres
// on the samples, so linear filtering interpolates between neighbours.
vec2 groundUv(vec2 xz) {
    return (xz / uSpacingValid.xy + 0.5) / vec2(uGrid.x);
}

Ground groundAt(vec2 xz) {
    vec2 texel = 1.0 / vec2(uGrid.x);
    vec2 uv = groundUv(xz);
    Ground g;
#ifdef SIERRA_GROUND_BILINEAR_HEIGHT
    g.height = texture(uHeights, uv).r;
#else
    g.height = smoothHeight(xz);
#endif
    float dx = texture(uHeights, uv + vec2(texel.x, 0.0)).r - texture(uHeights, uv - vec2(texel.x, 0.0)).r;
    float dz = texture(uHeights, uv + vec2(0.0, texel.y)).r - texture(uHeights, uv - vec2(0.0, texel.y)).r;
    g.normal = normalize(vec3(-dx / (2.0 * uSpacingValid.x), 1.0, -dz / (2.0 * uSpacingValid.y)));
    g.water = uHeightInfo.y > 0.5 && g.height < uHeightInfo.x;
    if (g.water) g.normal = vec3(0.0, 1.0, 0.0);  // water lies flat
    g.slope = 1.0 - g.normal.y;
    return g;
}

// The position of grid vertex `vertexId` (a linear index j * side + i) as the
// SBT draws it: its surface height, geomorphed from its morph base while its
// error bound grows through the last quarter of tau (morph.glsl), so the drawn
// surface stays within tau pixels and nothing pops.
vec3 terrainVertex(int vertexId) {
    ivec2 ij = ivec2(vertexId % uGrid.x, vertexId / uGrid.x);
    vec4 d = texelFetch(uData, ij, 0);
    float height = d.r;
    if (uLodEye.w > 0.0) height = morphedHeight(d, gridToWorld(ij, d.r), uLodEye.xyz, uLodEye.w);
    return gridToWorld(ij, height);
}
