#version 450 core
// The hatch field on the GPU, once per terrain and style (it does not depend
// on the view): per sample the unit stroke direction on the tangent plane and
// the opacity, as analysis::hatchStrokeDirection and computeHatchField. The
// axis is the curvature-weighted sum of the 4 directions taken as axes
// (doubled angles, halved back), or the single largest direction when the sum
// is nearly zero; Along lifts it onto the tangent plane, Across turns it a
// right angle on that plane. No data: opacity 0.
layout(local_size_x = 16, local_size_y = 16) in;

// render::CurvatureGpu's 2D array textures: sample (i, j) at texel (i / 8, j).
layout(binding = 0) uniform sampler2DArray uCurvature;  // the 4 directions, layer i % 8
layout(binding = 1) uniform sampler2DArray uGradient;   // dy/dx, dy/dz: layer (i % 8) / 2, .xy even i, .zw odd
layout(rgba32f, binding = 0) uniform writeonly image2D uStrokesOut;  // xyz: direction, w: opacity
uniform ivec2 uSize;
uniform vec2 uSpacing;
uniform int uAcross;  // 1 = perpendicular to the axis on the tangent plane

const ivec2 kSteps[4] = ivec2[4](ivec2(1, 0), ivec2(0, 1), ivec2(1, 1), ivec2(1, -1));

bool finite(float v) { return (floatBitsToUint(v) & 0x7f800000u) != 0x7f800000u; }

void main() {
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(ij, uSize))) return;
    vec4 k = texelFetch(uCurvature, ivec3(ij.x / 8, ij.y, ij.x % 8), 0);
    vec4 g2 = texelFetch(uGradient, ivec3(ij.x / 8, ij.y, (ij.x % 8) / 2), 0);
    vec2 grad = (ij.x & 1) == 0 ? g2.xy : g2.zw;
    float sx = 0.0, sz = 0.0, largest = 0.0, bestAngle = 0.0;
    for (int d = 0; d < 4; ++d) {
        float w = abs(k[d]);
        if (!finite(w)) continue;
        float angle = atan(float(kSteps[d].y) * uSpacing.y, float(kSteps[d].x) * uSpacing.x);
        sx += w * cos(2.0 * angle);
        sz += w * sin(2.0 * angle);
        if (w > largest) {
            largest = w;
            bestAngle = angle;
        }
    }
    if (!finite(grad.x) || !finite(grad.y)) {
        imageStore(uStrokesOut, ij, vec4(1.0, 0.0, 0.0, 0.0));
        return;
    }
    float angle = length(vec2(sx, sz)) > 1e-3 * largest ? 0.5 * atan(sz, sx) : bestAngle;
    vec2 axis = largest > 0.0 ? vec2(cos(angle), sin(angle)) : vec2(1.0, 0.0);
    vec3 n = normalize(vec3(-grad.x, 1.0, -grad.y));
    vec3 t = normalize(vec3(axis.x, -(n.x * axis.x + n.z * axis.y) / n.y, axis.y));
    if (uAcross == 1) t = normalize(cross(n, t));
    imageStore(uStrokesOut, ij, vec4(t, min(largest, 1.0)));
}
