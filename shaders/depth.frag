#version 450 core
// Depth pass: the linear eye-space depth of the terrain (distance along the
// view direction, world units) into a float target.
#include "frame.glsl"
#include "terrain_common.glsl"

in vec3 vWorld;
out float fragDepth;

void main() {
    if (overPadding(vWorld)) discard;
    fragDepth = dot(vWorld - uEye.xyz, uViewDir.xyz);
}
