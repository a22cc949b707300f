#version 450 core
// Curvature lines: one quad per polyline segment (gl_VertexID >> 2; its
// corner gl_VertexID & 3, drawn in indexed batches, render/passes/QuadBatch.h),
// pulled from a buffer of segments (grid x, z and alpha of both ends) and
// expanded to an antialiased quad of uWidth pixels (overlay_common.glsl).
#include "frame.glsl"
#include "terrain_common.glsl"
#include "overlay_common.glsl"

struct Segment {
    vec4 a;  // xy: grid x, z; z: alpha
    vec4 b;
};
layout(std430, binding = 0) readonly buffer Segments { Segment uSegments[]; };
uniform float uWidth;  // pixels

out vec3 vWorld;
out float vAcross;
out float vAlpha;

void main() {
    Segment s = uSegments[gl_VertexID >> 2];
    vec3 a = overlayPoint(s.a.xy), b = overlayPoint(s.b.xy);
    int corner = gl_VertexID & 3;
    gl_Position = segmentCorner(a, b, corner, 0.5 * uWidth, vAcross);
    bool atB = (corner & 1) != 0;
    vWorld = atB ? b : a;
    vAlpha = atB ? s.b.z : s.a.z;
}
