#version 450 core
// Terrain vertices with no attributes: each index is a linear grid position
// j * side + i, which indexed draws deliver as gl_VertexID; the height comes
// from the data texture. Used by every pass that draws the terrain mesh.
#include "frame.glsl"
#include "terrain_common.glsl"

out vec3 vWorld;

void main() {
    vWorld = terrainVertex(gl_VertexID);
    gl_Position = uViewProj * vec4(vWorld, 1.0);
}
