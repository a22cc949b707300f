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

// With multiply layers (SIERRA_DRAPE_MULTIPLY), two maps. Replace layers
// alone multiply the base by a grey (1 - a): one map then, premultiplied
// colour and its alpha a, half the memory and one fetch.
layout(binding = 9) uniform sampler2D uDrapeAdded;  // rgb: what is added; a: 1 - the multiplier (replace only)
#ifdef SIERRA_DRAPE_MULTIPLY
layout(binding = 8) uniform sampler2D uDrapeMultiplier;  // rgb: what the base albedo is multiplied by
#endif

vec2 drapeUv(vec2 xz) {
    vec2 samples = uSpacingValid.zw / uSpacingValid.xy + 1.0;  // the real grid, not the padding
    return (xz / uSpacingValid.xy + 0.5) / samples;
}

// Far vector lines (SIERRA_DRAPE_LINES; render/VectorOverlay.h): premultiplied,
// each mip level drawn at its own resolution, so the level GL picks holds
// the line at its width in pixels. Where the finest level is magnified
// (level of detail < 0) the line fades out over one level: LinePass draws it
// there as quads.
#ifdef SIERRA_DRAPE_LINES
layout(binding = 10) uniform sampler2D uDrapeLines;
#endif

vec3 surfaceAlbedo(vec3 world, Ground g) {
    vec2 uv = drapeUv(world.xz);
    vec4 added = texture(uDrapeAdded, uv);
#ifdef SIERRA_DRAPE_MULTIPLY
    vec3 albedo = baseSurfaceAlbedo(world, g) * texture(uDrapeMultiplier, uv).rgb + added.rgb;
#else
    vec3 albedo = baseSurfaceAlbedo(world, g) * (1.0 - added.a) + added.rgb;
#endif
#ifdef SIERRA_DRAPE_LINES
    vec4 line = texture(uDrapeLines, uv) * clamp(1.0 + textureQueryLod(uDrapeLines, uv).y, 0.0, 1.0);
    albedo = albedo * (1.0 - line.a) + line.rgb;
#endif
    return albedo;
}
