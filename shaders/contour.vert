#version 450 core
// Contour edges: the terrain mesh (terrainVertex, as terrain.vert) with
// s = dot(normal, towards the eye) per vertex, the normal from the
// full-resolution heights. Interpolated linearly across each triangle, s has
// clean zero crossings that contour.frag draws at a fixed width in pixels.
#include "frame.glsl"
#include "terrain_common.glsl"
#include "overlay_common.glsl"

out vec3 vWorld;
out float vFacing;

void main() {
    vWorld = terrainVertex(gl_VertexID);
    vFacing = dot(groundAt(vWorld.xz).normal, towardsEye(vWorld));
    gl_Position = uViewProj * vec4(vWorld, 1.0);
}
