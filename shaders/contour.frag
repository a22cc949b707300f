#version 450 core
// Contour edges: the view-dependent silhouettes of the terrain, every frame.
// s = dot(normal, towards the eye), from contour.vert (the triangles far
// from a contour dropped by contour_geom.glsl), interpolated across the
// triangles; the contour is where s changes sign, drawn uWidth pixels
// wide by dividing |s| by its screen-space rate of change (fwidth), which
// gives the distance to the zero crossing in pixels. Antialiased over one
// pixel.
#include "frame.glsl"
#include "terrain_common.glsl"
#include "overlay_common.glsl"

uniform vec4 uColour;  // RGBA 0..1
uniform float uWidth;  // pixels
in ContourVertex {
    vec3 world;
    float facing;
} fIn;
out vec4 fragColour;

void main() {
    if (overPadding(fIn.world)) discard;
    float s = fIn.facing;
    float pixels = abs(s) / max(fwidth(s), 1e-6);
    float a = uColour.a * lineCoverage(pixels, 0.5 * uWidth);
    if (a <= 0.0) discard;
    fragColour = vec4(uColour.rgb, a);
}
