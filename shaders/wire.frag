#version 450 core
// Wireframe overlay: the triangulation's edges in one colour.
#include "terrain_common.glsl"

uniform vec4 uColour;
in vec3 vWorld;
out vec4 fragColour;

void main() {
    if (overPadding(vWorld)) discard;
    fragColour = uColour;
}
