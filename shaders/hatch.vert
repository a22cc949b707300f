#version 450 core
// Hatch strokes pulled from the GPU hatch field: one quad per grid vertex
// of the frame's lattice (gl_VertexID >> 2; its corner gl_VertexID & 3, drawn
// in indexed batches, render/passes/QuadBatch.h), nothing built on the CPU per
// frame. The field
// (hatch_strokes.comp, computed once from the GPU curvature field) gives the
// stroke's direction on the vertex's tangent plane, along or across the
// curvature-weighted axis of greatest curvature (as
// analysis::hatchStrokeDirection), and its opacity = the largest |curvature|
// clamped to [0, 1]; the stroke is uLength grid units long, uWidth pixels wide.
//
// Distance thinning: where a grid cell covers fewer than kMinCellPixels on
// the screen, only every s-th vertex along each axis draws (s the power of
// two that brings s cells back above that size) with a stroke s times longer,
// and opacity fades in proportion to the cell's screen size over the sparser
// grid, so a far mountainside keeps the density of a near one and does not
// turn black. Culling: a vertex outside the frustum (with a margin of one
// stroke) or without curvature gives a degenerate quad outside the clip volume.
#include "frame.glsl"
#include "terrain_common.glsl"
#include "overlay_common.glsl"

layout(binding = 3) uniform sampler2D uStrokes;  // RGBA32F: stroke direction, opacity (hatch_strokes.comp)
uniform float uLength;   // grid units
uniform float uWidth;    // pixels
uniform int uBaseStride;   // strokes sit on every uBaseStride-th vertex (HatchPass::baseStride)
uniform int uLatticeSide;  // strokes per lattice row

const float kMinCellPixels = 6.0;  // HatchPass::kMinCellPixels

out vec3 vWorld;
out float vAcross;
out float vAlpha;

vec4 culled() { return vec4(2.0, 2.0, 2.0, 1.0); }

bool finite(float v) { return (floatBitsToUint(v) & 0x7f800000u) != 0x7f800000u; }

void main() {
    vAcross = 0.0;
    vAlpha = 0.0;
    vWorld = vec3(0.0);
    int strokeId = gl_VertexID >> 2;
    ivec2 ij = ivec2(strokeId % uLatticeSide, strokeId / uLatticeSide) * uBaseStride;
    vec4 stroke = texelFetch(uStrokes, ij, 0);
    float opacity = stroke.w;
    if (opacity < 1.0 / 255.0) {
        gl_Position = culled();
        return;
    }
    vec3 centre = overlayPoint(vec2(ij));
    vec4 clip = uViewProj * vec4(centre, 1.0);
    // Screen size of one grid cell at the vertex, from a world step across the view.
    vec3 across = normalize(cross(uViewDir.xyz, abs(uViewDir.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0)));
    vec4 clip2 = uViewProj * vec4(centre + across * uSpacingValid.x, 1.0);
    float cellPx = clip.w > 1e-6 && clip2.w > 1e-6
                       ? length((clip2.xy / clip2.w - clip.xy / clip.w) * 0.5 * uFrameSize.xy) : 0.0;
    int stride = 1;
    if (cellPx < kMinCellPixels) stride = 1 << clamp(int(ceil(log2(kMinCellPixels / max(cellPx, 1e-6)))), 0, 12);
    float fade = min(1.0, cellPx * float(stride) / (2.0 * kMinCellPixels));
    bool kept = (ij.x % stride) == 0 && (ij.y % stride) == 0;
    float margin = 1.0 + uLength * float(stride) * cellPx * 2.0 / max(min(uFrameSize.x, uFrameSize.y), 1.0);
    bool inside = clip.w > 1e-6 && all(lessThanEqual(abs(clip.xyz), vec3(clip.w * margin)));
    if (!kept || !inside || opacity * fade < 1.0 / 255.0 || !finite(centre.y)) {
        gl_Position = culled();
        return;
    }
    vec3 t = stroke.xyz;
    float halfLength = 0.5 * uLength * float(stride) * 0.5 * (uSpacingValid.x + uSpacingValid.y);
    vec3 a = centre - t * halfLength, b = centre + t * halfLength;
    int corner = gl_VertexID & 3;
    gl_Position = segmentCorner(a, b, corner, 0.5 * uWidth, vAcross);
    vWorld = (corner & 1) != 0 ? b : a;
    vAlpha = opacity * fade;
}
