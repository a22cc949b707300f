#version 450 core
// The shaded terrain: albedo from the surface function chosen when the program
// is built (surface.glsl stands for one of the surface_*.glsl files), Lambert
// light from the sun, and fog towards the sky colour. Height and normal come
// from the full-resolution data at the fragment's ground position, so a
// simplified mesh shades like the full grid and only its geometry differs.
//
// Contour edges (render/passes/ContourPass.h), built with SIERRA_CONTOURS:
// the view-dependent silhouettes, recomputed every frame where
// s = dot(normal, towards the eye) changes sign. s comes from the vertices
// (terrain.vert, full-resolution normals) interpolated across each triangle,
// so its zero crossings are clean lines at the mesh's scale (the same s per
// fragment, from this fragment's normal, breaks them into sub-pixel specks
// where the grid is finer than the pixels); |s| / fwidth(s) is the distance
// to the crossing in pixels, and the line covers what lies within half the
// width, antialiased over one pixel. Drawn here they cost a few operations a
// vertex and a fragment instead of a second pass over the mesh.
#include "frame.glsl"
#include "terrain_common.glsl"
#include "surface.glsl"

in vec3 vWorld;
out vec4 fragColour;

#ifdef SIERRA_CONTOURS
uniform float uContourWidth;  // pixels, > 0
uniform vec4 uContourColour;  // RGBA 0..1
in float vFacing;

// Coverage 0..1 of this fragment by a contour edge through the zero crossing of s.
float contourCoverage(float s) {
    float pixels = abs(s) / max(fwidth(s), 1e-6);
    return clamp(0.5 * uContourWidth + 0.5 - pixels, 0.0, 1.0);
}
#endif

void main() {
    if (overPadding(vWorld)) discard;
    Ground g = groundAt(vWorld.xz);
    vec3 albedo = surfaceAlbedo(vWorld, g);
    float ambient = uSun.w;
    float light = ambient + (1.0 - ambient) * max(dot(g.normal, uSun.xyz), 0.0);
    vec3 colour = albedo * light;
    float fog = 1.0 - exp(-uFog.x * distance(vWorld, uEye.xyz));
    colour = mix(colour, uSky.rgb, clamp(fog, 0.0, 1.0));
#ifdef SIERRA_CONTOURS
    colour = mix(colour, uContourColour.rgb, uContourColour.a * contourCoverage(vFacing));
#endif
    fragColour = vec4(colour, 1.0);
}
