// Surface function: imagery drapes over a base surface (render/DrapeSurface.h).
// The base surface's albedo (surface_base.glsl stands for its file) goes
// through the layers composed into one affine map per channel,
//   albedo = base * multiplier + added,
// exact for any stack of replace and multiply layers with their alpha and
// opacity: a replace layer of colour L and alpha a maps c to c (1 - a) + a L,
// a multiply layer to c (1 - a + a L), and maps of this form compose into
// one. The terrain pass then lights, shadows and fogs the result like any
// albedo. The textures span the real grid's pixel corners.
#define surfaceAlbedo baseSurfaceAlbedo
#include "surface_base.glsl"
#undef surfaceAlbedo

layout(binding = 8) uniform sampler2D uDrapeMultiplier;  // rgb: what the base albedo is multiplied by
layout(binding = 9) uniform sampler2D uDrapeAdded;       // rgb: what is added after

vec2 drapeUv(vec2 xz) {
    vec2 samples = uSpacingValid.zw / uSpacingValid.xy + 1.0;  // the real grid, not the padding
    return (xz / uSpacingValid.xy + 0.5) / samples;
}

vec3 surfaceAlbedo(vec3 world, Ground g) {
    vec2 uv = drapeUv(world.xz);
    return baseSurfaceAlbedo(world, g) * texture(uDrapeMultiplier, uv).rgb +
           texture(uDrapeAdded, uv).rgb;
}
