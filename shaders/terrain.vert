#version 450 core
// Terrain vertices with no attributes: each index is a linear grid position
// j * side + i, which indexed draws deliver as gl_VertexID; the height comes
// from the data texture.
#include "terrain_common.glsl"

uniform mat4 uViewProj;
uniform vec3 uEye;
// lambda / tau (pixels per unit error at unit distance, over the pixel
// threshold); 0 turns geomorphing off (full grid, fixed-error meshes).
uniform float uLambdaOverTau;

out vec3 vWorld;

void main() {
    ivec2 ij = ivec2(gl_VertexID % uSide, gl_VertexID / uSide);
    vec4 d = texelFetch(uData, ij, 0);
    float height = d.r;
    if (uLambdaOverTau > 0.0) {
        // The CPU activates the vertex when (lambda e / tau + r) > distance; the
        // ratio is 1 when it has just become active. Blend from the mean of its
        // hypotenuse endpoints (where the coarser mesh had the surface) at ratio
        // 1 to its own height at ratio 2, so vertices never pop.
        float dist = max(distance(gridToWorld(ij, d.r), uEye), 1e-6);
        float ratio = (uLambdaOverTau * d.b + d.a) / dist;
        height = mix(d.g, d.r, clamp(ratio - 1.0, 0.0, 1.0));
    }
    vWorld = gridToWorld(ij, height);
    gl_Position = uViewProj * vec4(vWorld, 1.0);
}
