#version 450 core
// Curvature lines: one quad per polyline segment (gl_VertexID >> 2; its
// corner gl_VertexID & 3, drawn in indexed batches, render/passes/QuadBatch.h),
// pulled from a buffer of segments (grid x, z and alpha of both ends, the
// polyline's rank) and expanded to an antialiased quad of uWidth pixels
// (overlay_common.glsl).
//
// Distance thinning: where a grid cell covers c < kFullCellPixels * w on the
// screen (w = max(1, uWidth)), a segment is drawn only when its polyline's
// rank (evenly spread over [0, 1), LinePass) is below (c / (kFullCellPixels
// * w))^2. A far polyline shrinks to a blob of the quad's least size (its
// width and antialiasing ramp), so the polylines per screen area, (1 / c)^2
// times those per cell, each covering about w^2 pixels, are what blackens a
// far slope: keeping that fraction keeps them at the density of one polyline
// per cell of kFullCellPixels * w pixels, whatever the width (hatches thin
// by the same square, a stride in both axes). A polyline stays whole where c
// does not cross its rank. The segment's first end decides for all four
// corners.
#include "frame.glsl"
#include "terrain_common.glsl"
#include "overlay_common.glsl"

struct Segment {
    vec4 a;  // xy: grid x, z; z: alpha; w: the polyline's rank in [0, 1)
    vec4 b;  // xy: grid x, z; z: alpha
};
layout(std430, binding = 0) readonly buffer Segments { Segment uSegments[]; };
uniform float uWidth;  // pixels

const float kFullCellPixels = 1.0;  // LinePass::kFullCellPixels

out vec3 vWorld;
out float vAcross;
out float vAlpha;

void main() {
    Segment s = uSegments[gl_VertexID >> 2];
    vec3 a = overlayPoint(s.a.xy), b = overlayPoint(s.b.xy);
    int corner = gl_VertexID & 3;
    float cell = cellPixels(a, uViewProj * vec4(a, 1.0)) / (kFullCellPixels * max(uWidth, 1.0));
    if (s.a.w >= cell * cell) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // thinned out: outside the clip volume
        vAcross = 0.0;
        vWorld = a;
        vAlpha = 0.0;
        return;
    }
    gl_Position = segmentCorner(a, b, corner, 0.5 * uWidth, vAcross);
    bool atB = (corner & 1) != 0;
    vWorld = atB ? b : a;
    vAlpha = atB ? s.b.z : s.a.z;
}
