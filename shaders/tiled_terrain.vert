#version 450 core
// The tiled terrain's mesh (render/TiledTerrain.h): each index is a position
// in the frame's vertex buffer of (i, j) sample pairs, strips restarted at
// 0xFFFFFFFF; the height comes from the tile holding the sample.
// SIERRA_CONTOURS: vFacing, dot(normal, towards the eye) at the vertex from
// the finest heights resident there (contour.glsl).
#include "tiled_common.glsl"

layout(std430, binding = 0) readonly buffer Vertices {
    uvec2 vertices[];
};

uniform mat4 uViewProj;

out vec3 vWorld;
#ifdef SIERRA_CONTOURS
uniform vec3 uEye;
out float vFacing;
#endif

void main() {
    ivec2 ij = ivec2(vertices[gl_VertexID]);
    vWorld = vec3(float(ij.x) * uSpacingValid.x, tiledSampleHeight(ij), float(ij.y) * uSpacingValid.y);
    gl_Position = uViewProj * vec4(vWorld, 1.0);
#ifdef SIERRA_CONTOURS
    vFacing = dot(groundAt(vWorld.xz).normal, normalize(uEye - vWorld));
#endif
}
