#version 450 core
// Hatch strokes pulled from the GPU hatch field: one point per grid vertex
// of the frame's lattice (gl_VertexID), which hatch_geom.glsl expands into the
// stroke's quad, so the work per stroke runs once and not per corner; nothing
// built on the CPU per frame. The field
// (hatch_strokes.comp, computed once from the GPU curvature field) gives the
// stroke's direction on the vertex's tangent plane, along or across the
// curvature-weighted axis of greatest curvature (as
// analysis::hatchStrokeDirection), and its opacity = the largest |curvature|
// clamped to [0, 1]; the stroke is uLength grid units long, uWidth pixels
// wide (hatch_geom.glsl).
//
// Distance thinning: where a grid cell covers fewer than kMinCellPixels on
// the screen, only every s-th vertex along each axis draws (s the power of
// two that brings s cells back above that size) with a stroke s times longer,
// and opacity fades in proportion to the cell's screen size over the sparser
// grid, so a far mountainside keeps the density of a near one and does not
// turn black. Culling: a vertex outside the frustum (with a margin of one
// stroke) or without curvature emits no quad. A stroke is cut at the
// terrain's outer edge.
#include "frame.glsl"
#include "terrain_common.glsl"
#include "overlay_common.glsl"

layout(binding = 3) uniform sampler2D uStrokes;  // RGBA32F: stroke direction, opacity (hatch_strokes.comp)
uniform float uLength;   // grid units
uniform float uOpacityGain;  // multiplies the stroke field's opacity (HatchPassDesc::opacityGain)
uniform int uBaseStride;   // strokes sit on every uBaseStride-th vertex (HatchPass::baseStride)
uniform int uLatticeSide;  // strokes per lattice row

const float kMinCellPixels = 6.0;  // HatchPass::kMinCellPixels

out HatchStroke {
    vec3 a;        // world ends of the stroke
    vec3 b;
    float alpha;   // opacity with the distance fade; 0 = no quad
} vOut;

bool finite(float v) { return (floatBitsToUint(v) & 0x7f800000u) != 0x7f800000u; }

// Narrows the offsets [lo, hi] along a direction whose component on one
// axis is d, from a start at c on that axis, to where c + s d stays in [0, e].
// Called per axis with scalar components: with uSpacingValid.zw indexed in a
// loop instead, Mesa 22.3's llvmpipe cut every stroke away.
void clipToRange(float c, float d, float e, inout float lo, inout float hi) {
    if (abs(d) < 1e-6) return;
    float s0 = -c / d, s1 = (e - c) / d;
    lo = max(lo, min(s0, s1));
    hi = min(hi, max(s0, s1));
}

void main() {
    vOut.a = vOut.b = vec3(0.0);
    vOut.alpha = 0.0;
    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);  // unused: hatch_geom.glsl places the corners
    int strokeId = gl_VertexID;
    ivec2 ij = ivec2(strokeId % uLatticeSide, strokeId / uLatticeSide) * uBaseStride;
    vec4 stroke = texelFetch(uStrokes, ij, 0);
    float opacity = min(stroke.w * uOpacityGain, 1.0);
    if (opacity < 1.0 / 255.0) return;
    vec3 centre = overlayPoint(vec2(ij));
    vec4 clip = uViewProj * vec4(centre, 1.0);
    float cellPx = cellPixels(centre, clip);
    int stride = 1;
    if (cellPx < kMinCellPixels) stride = 1 << clamp(int(ceil(log2(kMinCellPixels / max(cellPx, 1e-6)))), 0, 12);
    float fade = min(1.0, cellPx * float(stride) / (2.0 * kMinCellPixels));
    bool kept = (ij.x % stride) == 0 && (ij.y % stride) == 0;
    float margin = 1.0 + uLength * float(stride) * cellPx * 2.0 / max(min(uFrameSize.x, uFrameSize.y), 1.0);
    bool inside = clip.w > 1e-6 && all(lessThanEqual(abs(clip.xyz), vec3(clip.w * margin)));
    if (!kept || !inside || opacity * fade < 1.0 / 255.0 || !finite(centre.y)) return;
    vec3 t = stroke.xyz;
    float halfLength = 0.5 * uLength * float(stride) * 0.5 * (uSpacingValid.x + uSpacingValid.y);
    // The stroke's part over the terrain (the real samples, not the padding):
    // centred on a vertex of the outer edge, half of it would hang in the sky.
    // lo, hi: the ends' offsets along t from the centre.
    float lo = -halfLength, hi = halfLength;
    vec2 ground = vec2(ij) * uSpacingValid.xy;
    clipToRange(ground.x, t.x, uSpacingValid.z, lo, hi);
    clipToRange(ground.y, t.z, uSpacingValid.w, lo, hi);
    if (hi <= lo) return;
    vOut.a = centre + t * lo;
    vOut.b = centre + t * hi;
    vOut.alpha = opacity * fade;
}
