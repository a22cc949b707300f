#version 450 core
// Wireframe pass: the triangulation's edges in one colour.
#include "frame.glsl"
#include "terrain_common.glsl"

uniform vec4 uColour;
in vec3 vWorld;
out vec4 fragColour;

void main() {
    if (overPadding(vWorld)) discard;
    fragColour = uColour;
}
