// Shared by the tiled terrain's stages (engine: render/TiledTerrain.h): the
// GPU tile cache, one array texture a tile resolution, and the page table.
// The names a surface reads (render/Surface.h: the Terrain block's
// uSpacingValid and uHeightInfo, Ground) are those of terrain_common.glsl, so
// one surface function shades both terrains; the tile cache takes texture
// units 16 and up, above the surfaces' own.
//
// Tile (tx, ty) covers samples [tx T, tx T + T]^2, T = 2^k. Page texel
// (tx, ty): x = resolution class c (its slot holds (2^c + 1)^2 world
// heights, sample (a, b) at tile-local (a, b) * T / 2^c), y = layer, zw =
// the texel of the slot's sample (0, 0) in the layer (a layer is an atlas of
// slots, each in a one-texel gutter); x < 0: not on the GPU. At most 9 classes (c = 0..8, k <= 8).
layout(binding = 16) uniform isampler2D uPages;
layout(binding = 17) uniform sampler2DArray uClass[9];  // units 17..25
// The tile corners' world heights ((tiles + 1)^2, the file's coarse
// section): always there, for the coarse mesh and where no tile is resident.
layout(binding = 26) uniform sampler2D uCorners;

layout(std140, binding = 1) uniform Terrain {
    ivec4 uGrid;          // x: samples per side, 2^n + 1
    vec4 uSpacingValid;   // xy: world distance between samples along x and z; zw: world x, z of the last real sample
    vec4 uHeightInfo;     // x: world sea level; y: 0 (no water); z, w: lowest and highest world height
    ivec4 uTileInfo;      // x: k, y: tiles per side, z: T = 2^k
};

// True for fragments over the padding to (2^n+1)^2 samples.
bool overPadding(vec3 world) {
    return any(greaterThan(world.xz, uSpacingValid.zw + 1e-3 * uSpacingValid.xy));
}

// The height in the slot of `page` at grid position g (texels of the slot,
// 0..2^c, may be fractional), bilinear: g is clamped to the slot, whose
// one-texel gutter repeats its edge, so the slot's neighbours in the atlas
// never bleed in.
float classHeight(ivec4 page, vec2 g) {
    vec2 p = vec2(page.zw) + clamp(g, vec2(0.0), vec2(float(1 << page.x))) + 0.5;
    float layer = float(page.y);
    switch (page.x) {
    case 0: return textureLod(uClass[0], vec3(p / vec2(textureSize(uClass[0], 0).xy), layer), 0.0).r;
    case 1: return textureLod(uClass[1], vec3(p / vec2(textureSize(uClass[1], 0).xy), layer), 0.0).r;
    case 2: return textureLod(uClass[2], vec3(p / vec2(textureSize(uClass[2], 0).xy), layer), 0.0).r;
    case 3: return textureLod(uClass[3], vec3(p / vec2(textureSize(uClass[3], 0).xy), layer), 0.0).r;
    case 4: return textureLod(uClass[4], vec3(p / vec2(textureSize(uClass[4], 0).xy), layer), 0.0).r;
    case 5: return textureLod(uClass[5], vec3(p / vec2(textureSize(uClass[5], 0).xy), layer), 0.0).r;
    case 6: return textureLod(uClass[6], vec3(p / vec2(textureSize(uClass[6], 0).xy), layer), 0.0).r;
    case 7: return textureLod(uClass[7], vec3(p / vec2(textureSize(uClass[7], 0).xy), layer), 0.0).r;
    default: return textureLod(uClass[8], vec3(p / vec2(textureSize(uClass[8], 0).xy), layer), 0.0).r;
    }
}

// The tile holding sample (i, j) whose page is on the GPU (a border sample
// lies in up to four), or ivec2(-1).
ivec2 residentTile(ivec2 ij) {
    int k = uTileInfo.x, P = uTileInfo.y, T = uTileInfo.z;
    ivec2 t = min(ij >> k, ivec2(P - 1));
    for (int dy = 0; dy <= 1; ++dy)
        for (int dx = 0; dx <= 1; ++dx) {
            ivec2 u = t - ivec2(dx, dy);
            if (u.x < 0 || u.y < 0) continue;
            if ((dx == 1 && ij.x != t.x * T) || (dy == 1 && ij.y != t.y * T)) continue;
            if (texelFetch(uPages, u, 0).x >= 0) return u;
        }
    return ivec2(-1);
}

// World height of sample (i, j) from the tile holding it; a no-data sample
// (NaN in the tile cache) at the lowest height.
float tiledSampleHeight(ivec2 ij) {
    int T = uTileInfo.z;
    if ((ij.x & (T - 1)) == 0 && (ij.y & (T - 1)) == 0) return texelFetch(uCorners, ij >> uTileInfo.x, 0).r;
    ivec2 t = residentTile(ij);
    if (t.x < 0) return uHeightInfo.z;
    ivec4 page = texelFetch(uPages, t, 0);
    int step = uTileInfo.z >> page.x;
    float h = classHeight(page, vec2(ij - t * uTileInfo.z) / float(step));
    return isnan(h) ? uHeightInfo.z : h;
}

// World height at grid position s (samples, may be fractional) from the tile
// holding it: bilinear in its slot, or the tile corners' surface where the
// tile has no slot on the GPU.
float heightAtGrid(vec2 s) {
    int k = uTileInfo.x, P = uTileInfo.y, T = uTileInfo.z;
    ivec2 t = clamp(ivec2(floor(s)) >> k, ivec2(0), ivec2(P - 1));
    ivec4 page = texelFetch(uPages, t, 0);
    if (page.x < 0) return textureLod(uCorners, (s / float(T) + 0.5) / vec2(P + 1), 0.0).r;
    return classHeight(page, (s - vec2(t * T)) / float(T >> page.x));
}

// World height and normal at a ground position from the finest heights on
// the GPU there, as terrain_common.glsl's Ground (a tiled terrain has no
// water); the height is NaN next to a no-data sample.
struct Ground {
    float height;  // world units
    vec3 normal;   // unit
    float slope;   // 0 flat .. 1 vertical (1 - normal.y)
    bool water;    // always false
};

// The normal is a central difference one texel of the tile's slot either
// side (half a tile on the corners' surface), taken from whichever tile
// holds each end, so it is continuous across tile borders; one-sided only at
// the grid's edges.
Ground groundAt(vec2 xz) {
    int k = uTileInfo.x, P = uTileInfo.y, T = uTileInfo.z;
    vec2 s = xz / uSpacingValid.xy;  // samples
    ivec2 t = clamp(ivec2(floor(s)) >> k, ivec2(0), ivec2(P - 1));
    int c = texelFetch(uPages, t, 0).x;
    float step = c < 0 ? 0.5 * float(T) : float(T >> c);
    float last = float(uGrid.x - 1);
    Ground g;
    g.water = false;
    g.height = heightAtGrid(s);
    float x0 = max(s.x - step, 0.0), x1 = min(s.x + step, last);
    float z0 = max(s.y - step, 0.0), z1 = min(s.y + step, last);
    float dhdx = (heightAtGrid(vec2(x1, s.y)) - heightAtGrid(vec2(x0, s.y))) /
                 max((x1 - x0) * uSpacingValid.x, 1e-6);
    float dhdz = (heightAtGrid(vec2(s.x, z1)) - heightAtGrid(vec2(s.x, z0))) /
                 max((z1 - z0) * uSpacingValid.y, 1e-6);
    g.normal = normalize(vec3(-dhdx, 1.0, -dhdz));
    g.slope = 1.0 - g.normal.y;
    return g;
}
