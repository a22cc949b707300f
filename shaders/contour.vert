#version 450 core
// Contour edges: the terrain mesh (terrainVertex, as terrain.vert) with
// s = dot(normal, towards the eye) per vertex, the normal from the
// full-resolution heights. Interpolated linearly across each triangle, s has
// clean zero crossings that contour.frag draws at a fixed width in pixels;
// contour_geom.glsl passes on only the triangles near one.
#include "frame.glsl"
#include "terrain_common.glsl"
#include "overlay_common.glsl"

out ContourVertex {
    vec3 world;
    float facing;
} vOut;

void main() {
    vOut.world = terrainVertex(gl_VertexID);
    vOut.facing = dot(groundAt(vOut.world.xz).normal, towardsEye(vOut.world));
    gl_Position = uViewProj * vec4(vOut.world, 1.0);
}
