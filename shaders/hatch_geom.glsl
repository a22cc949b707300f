#version 450 core
// Hatch strokes, geometry stage: each point of hatch.vert (a stroke's world
// ends and opacity, computed once per stroke) becomes its antialiased quad
// of uWidth pixels (overlay_common.glsl's segmentCorner, corners in strip
// order); a point with opacity 0 (culled, thinned out, no curvature) emits
// nothing.
#include "frame.glsl"
#include "terrain_common.glsl"
#include "overlay_common.glsl"

layout(points) in;
layout(triangle_strip, max_vertices = 4) out;

uniform float uWidth;  // pixels

in HatchStroke {
    vec3 a;
    vec3 b;
    float alpha;
} gIn[];
out vec3 vWorld;
out float vAcross;
out float vAlpha;

void main() {
    if (gIn[0].alpha <= 0.0) return;
    for (int corner = 0; corner < 4; ++corner) {
        gl_Position = segmentCorner(gIn[0].a, gIn[0].b, corner, 0.5 * uWidth, vAcross);
        vWorld = (corner & 1) != 0 ? gIn[0].b : gIn[0].a;
        vAlpha = gIn[0].alpha;
        EmitVertex();
    }
    EndPrimitive();
}
