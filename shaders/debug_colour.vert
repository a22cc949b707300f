#version 450 core
// Debug colourings: the terrain vertex and its grid index, for the geometry
// stage that colours each triangle (debug_colour_geom.glsl).
#include "frame.glsl"
#include "terrain_common.glsl"

out vec3 vWorld;
flat out int vId;

void main() {
    vWorld = terrainVertex(gl_VertexID);
    vId = gl_VertexID;
    gl_Position = uViewProj * vec4(vWorld, 1.0);
}
