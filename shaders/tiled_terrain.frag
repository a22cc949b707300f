#version 450 core
// The tiled terrain's colour (render/TiledTerrain.h): the albedo of the
// surface function chosen when the program is built (surface.glsl stands for
// a surface_*.glsl file, render/Surface.h: the hypsometric ramp unless one is
// set), lit by the sun with an ambient term, hazed towards the sky with
// distance. Height and normal from the finest heights on the GPU at the
// fragment; cast shadows and sky light from the overview's relief fields
// (render/TiledRelief.h). SIERRA_UNLIT (the paper surface): no light at all.
// SIERRA_CONTOURS: contour edges (contour.glsl) from the vertices' facing.
#include "tiled_common.glsl"
#include "surface.glsl"

uniform vec3 uEye;
uniform vec3 uSun;       // towards the sun, unit
uniform vec3 uSky;       // the frame's clear colour, 0..1
uniform float uFog;      // haze per world unit
uniform float uAmbient;  // 0..1
uniform vec4 uReliefUv;  // world x, z to the relief fields' uv: xz * xy + zw
layout(binding = 27) uniform sampler2D uSunVisibility;  // the visible share of the sun's disc
layout(binding = 28) uniform sampler2D uSkyLight;       // the cosine-weighted sky light

in vec3 vWorld;
out vec4 fragColour;

#ifdef SIERRA_CONTOURS
#include "contour.glsl"
in float vFacing;
#endif

// As the in-memory renderer's terrainLight (terrain.frag): the ambient term
// scaled by the sky light, the sun's Lambert term by the share of its disc
// seen (both 1 when off; uSun is 0 for a sun below the horizon).
float tiledLight(Ground g) {
#ifdef SIERRA_UNLIT
    return 1.0;
#else
    vec2 uv = vWorld.xz * uReliefUv.xy + uReliefUv.zw;
    float sun = textureLod(uSunVisibility, uv, 0.0).r, sky = textureLod(uSkyLight, uv, 0.0).r;
    return uAmbient * sky + (1.0 - uAmbient) * max(dot(g.normal, uSun), 0.0) * sun;
#endif
}

void main() {
    if (overPadding(vWorld)) discard;
    Ground g = groundAt(vWorld.xz);
    if (isnan(g.height)) discard;  // no data here
    // As terrain.frag: the surfaces' albedos are display colours (the ramp,
    // imagery), lit, then hazed towards the sky the frame is cleared to.
    vec3 colour = surfaceAlbedo(vWorld, g) * tiledLight(g);
    float haze = 1.0 - exp(-uFog * distance(uEye, vWorld));
    colour = mix(colour, uSky, clamp(haze, 0.0, 1.0));
#ifdef SIERRA_CONTOURS
    colour = withContour(colour, vFacing);
#endif
    fragColour = vec4(colour, 1.0);
}
