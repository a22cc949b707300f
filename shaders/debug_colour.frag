#version 450 core
// Debug colourings: the triangle's flat colour, unlit, so a colour reads as
// one level or one error (see debug_colour_geom.glsl).
#include "frame.glsl"
#include "terrain_common.glsl"

in vec3 gWorld;
flat in vec4 gColour;
out vec4 fragColour;

void main() {
    if (overPadding(gWorld)) discard;
    fragColour = gColour;
}
