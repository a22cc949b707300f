#version 450 core
// Terrain vertices with no attributes: each index is a linear grid position
// j * side + i, which indexed draws deliver as gl_VertexID; the height comes
// from the data texture. Used by every pass that draws the terrain mesh.
// With SIERRA_CONTOURS (the terrain pass drawing contour edges, terrain.frag)
// it also gives s = dot(normal, towards the eye) at the vertex, the normal
// from the full-resolution heights.
#include "frame.glsl"
#include "terrain_common.glsl"

out vec3 vWorld;
#ifdef SIERRA_CONTOURS
out float vFacing;
#endif

void main() {
    vWorld = terrainVertex(gl_VertexID);
#ifdef SIERRA_CONTOURS
    vFacing = dot(groundAt(vWorld.xz).normal, towardsEye(vWorld));
#endif
    gl_Position = uViewProj * vec4(vWorld, 1.0);
}
