#version 450 core
// Curvature lines and hatch strokes: the colour with alpha = curvature times
// the antialiased coverage across the line.
#include "frame.glsl"
#include "terrain_common.glsl"
#include "overlay_common.glsl"

uniform vec4 uColour;  // RGBA, 0..1; alpha multiplies
uniform float uWidth;  // pixels
in vec3 vWorld;
in float vAcross;
in float vAlpha;
out vec4 fragColour;

void main() {
    if (overPadding(vWorld)) discard;
    float a = uColour.a * clamp(vAlpha, 0.0, 1.0) * lineCoverage(vAcross, 0.5 * uWidth);
    if (a <= 0.0) discard;
    fragColour = vec4(uColour.rgb, a);
}
