#version 450 core
// The shaded terrain: albedo from the surface function chosen when the program
// is built (surface.glsl stands for one of the surface_*.glsl files), lit by
// terrainLight, and fog towards the sky colour. Height, normal and the relief
// fields come from the full-resolution data at the fragment's ground position,
// so a simplified mesh (the SBT as it refines, a TIN) shades like the full
// grid and only its geometry differs: no shadow pops.
//
// Built with SIERRA_RELIEF_LIGHT (render/TerrainGpu.h, prepareRelief): the
// relief fields on unit 7 shade too, r the visible share of the sun's disc
// (soft cast shadows), g the cosine-weighted sky light (the ambient a point
// receives from the sky its horizons leave open). Without it both are 1,
// compiled out (llvmpipe runs every branch, so a field that is off would
// still cost its fetch). SIERRA_UNLIT (the paper surface): no light at all.
//
// Contour edges (render/passes/ContourPass.h, contour.glsl), built with
// SIERRA_CONTOURS: s = dot(normal, towards the eye) from the vertices
// (terrain.vert). Drawn here they cost a few operations a vertex and a
// fragment instead of a second pass over the mesh.
#include "frame.glsl"
#include "terrain_common.glsl"
#include "surface.glsl"

in vec3 vWorld;
out vec4 fragColour;

#ifdef SIERRA_CONTOURS
#include "contour.glsl"
in float vFacing;
#endif

#ifdef SIERRA_RELIEF_LIGHT
layout(binding = 7) uniform sampler2D uRelief;  // RG16F, one texel per sample: r sun visibility, g sky light
#endif

// The light a ground point receives, 0..1: the ambient term (the sky) scaled
// by its sky light, and the sun's Lambert term by the share of its disc the
// point sees:
//   ambient * skyLight + (1 - ambient) * max(n . sun, 0) * sunVisibility
// (uSun.xyz is 0 for a sun below the horizon: the sky alone lights).
float terrainLight(vec2 xz, Ground g) {
#ifdef SIERRA_UNLIT
    return 1.0;
#else
    float ambient = uSun.w;
    float direct = max(dot(g.normal, uSun.xyz), 0.0);
#ifdef SIERRA_RELIEF_LIGHT
    vec2 relief = texture(uRelief, groundUv(xz)).rg;
    return ambient * relief.g + (1.0 - ambient) * direct * relief.r;
#else
    return ambient + (1.0 - ambient) * direct;
#endif
#endif
}

// Aerial perspective: none up to uFog.z from the eye, then exponential.
float fogAmount(vec3 world) {
    return 1.0 - exp(-uFog.x * max(distance(world, uEye.xyz) - uFog.z, 0.0));
}

void main() {
    if (overPadding(vWorld)) discard;
    Ground g = groundAt(vWorld.xz);
    vec3 albedo = surfaceAlbedo(vWorld, g);
    vec3 colour = albedo * terrainLight(vWorld.xz, g);
    colour = mix(colour, uSky.rgb, clamp(fogAmount(vWorld), 0.0, 1.0));
#ifdef SIERRA_CONTOURS
    colour = withContour(colour, vFacing);
#endif
    fragColour = vec4(colour, 1.0);
}
