#version 450 core
// Hatch strokes pulled from the GPU curvature field: one instance per grid
// vertex, four corners each, nothing built on the CPU per frame. The stroke
// lies on the vertex's tangent plane (its normal from the gradient texture of
// the curvature pass), along or across the curvature-weighted axis of
// greatest curvature (the same formula as analysis::hatchStrokeDirection),
// uLength grid units long, uWidth pixels wide, with opacity = the largest
// |curvature| clamped to [0, 1].
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

layout(binding = 3) uniform sampler2D uCurvature;  // RGBA32F: the 4 directions per sample
layout(binding = 4) uniform sampler2D uGradient;   // RG32F: dy/dx, dy/dz per sample
uniform float uLength;   // grid units
uniform float uWidth;    // pixels
uniform int uAcross;     // 1 = perpendicular to the axis on the tangent plane

const float kMinCellPixels = 4.0;
const ivec2 kSteps[4] = ivec2[4](ivec2(1, 0), ivec2(0, 1), ivec2(1, 1), ivec2(1, -1));

out vec3 vWorld;
out float vAcross;
out float vAlpha;

vec4 culled() { return vec4(2.0, 2.0, 2.0, 1.0); }

bool finite(float v) { return (floatBitsToUint(v) & 0x7f800000u) != 0x7f800000u; }

void main() {
    vAcross = 0.0;
    vAlpha = 0.0;
    vWorld = vec3(0.0);
    int side = uGrid.x;
    ivec2 ij = ivec2(gl_InstanceID % side, gl_InstanceID / side);
    vec4 k = texelFetch(uCurvature, ij, 0);
    vec2 grad = texelFetch(uGradient, ij, 0).rg;
    float opacity = 0.0;
    float sx = 0.0, sz = 0.0, largest = 0.0, bestAngle = 0.0;
    for (int d = 0; d < 4; ++d) {
        float w = abs(k[d]);
        if (!finite(w)) continue;
        float angle = atan(float(kSteps[d].y) * uSpacingValid.y, float(kSteps[d].x) * uSpacingValid.x);
        sx += w * cos(2.0 * angle);
        sz += w * sin(2.0 * angle);
        if (w > largest) {
            largest = w;
            bestAngle = angle;
        }
    }
    opacity = min(largest, 1.0);
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
    if (!kept || !inside || opacity * fade < 1.0 / 255.0 || !finite(grad.x) || !finite(centre.y)) {
        gl_Position = culled();
        return;
    }
    // The axis (as hatchStrokeDirection): weighted sum of the doubled angles.
    float angle = length(vec2(sx, sz)) > 1e-3 * largest ? 0.5 * atan(sz, sx) : bestAngle;
    vec2 axis = vec2(cos(angle), sin(angle));
    vec3 n = normalize(vec3(-grad.x, 1.0, -grad.y));
    vec3 t = normalize(vec3(axis.x, -(n.x * axis.x + n.z * axis.y) / n.y, axis.y));
    if (uAcross == 1) t = normalize(cross(n, t));
    float halfLength = 0.5 * uLength * float(stride) * 0.5 * (uSpacingValid.x + uSpacingValid.y);
    vec3 a = centre - t * halfLength, b = centre + t * halfLength;
    int corner = gl_VertexID;
    gl_Position = segmentCorner(a, b, corner, 0.5 * uWidth, vAcross);
    vWorld = (corner & 1) != 0 ? b : a;
    vAlpha = opacity * fade;
}
