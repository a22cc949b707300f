#version 450 core
// Debug colourings, one flat colour per triangle from its three grid indices
// (strips give no gl_PrimitiveID per SBT triangle, so the level is computed
// here, not looked up):
//   uMode 0: SBT level. The legs of a level-l triangle are (side - 1) / 2^(l/2)
//            samples long, so 2^l = (side - 1)^2 / leg^2; hue from red
//            (level 0) to violet (level 2n).
//   uMode 1: screen-space error of the split vertex m (the hypotenuse
//            midpoint), lambda * e(m) / (|m - eye| - r(m)) in pixels, as a
//            heat map over 0 .. 2 tau: blue 0, green tau / 2, yellow tau,
//            red 2 tau and more; the finest level (no split vertex) is 0.
#include "frame.glsl"
#include "terrain_common.glsl"

layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;

uniform int uMode;
in vec3 vWorld[];
flat in int vId[];
out vec3 gWorld;
flat out vec4 gColour;

ivec2 gridOf(int id) { return ivec2(id % uGrid.x, id / uGrid.x); }
int len2(ivec2 a, ivec2 b) { ivec2 d = a - b; return d.x * d.x + d.y * d.y; }

vec3 hue(float h) {  // h 0..1 -> saturated colour
    vec3 k = clamp(abs(fract(h + vec3(0.0, 2.0 / 3.0, 1.0 / 3.0)) * 6.0 - 3.0) - 1.0, 0.0, 1.0);
    return k;
}

vec3 heat(float t) {  // t = error / tau
    const vec3 stops[4] = vec3[](vec3(0.1, 0.2, 0.9), vec3(0.1, 0.75, 0.2), vec3(0.95, 0.9, 0.1), vec3(0.9, 0.1, 0.05));
    if (t <= 0.5) return mix(stops[0], stops[1], t / 0.5);
    if (t <= 1.0) return mix(stops[1], stops[2], (t - 0.5) / 0.5);
    return mix(stops[2], stops[3], clamp(t - 1.0, 0.0, 1.0));
}

void main() {
    ivec2 g[3] = ivec2[](gridOf(vId[0]), gridOf(vId[1]), gridOf(vId[2]));
    int l01 = len2(g[0], g[1]), l12 = len2(g[1], g[2]), l20 = len2(g[2], g[0]);
    vec3 colour;
    if (uMode == 0) {
        int leg = max(min(l01, min(l12, l20)), 1);
        int full = (uGrid.x - 1) * (uGrid.x - 1);
        int level = findMSB(full / leg);
        int levels = 2 * findMSB(uGrid.x - 1);  // 2n
        colour = hue(0.8 * float(level) / float(max(levels, 1)));
    } else {
        ivec2 a = g[0], b = g[1];
        if (l12 > len2(a, b)) { a = g[1]; b = g[2]; }
        if (l20 > len2(a, b)) { a = g[2]; b = g[0]; }
        ivec2 s = a + b;
        float err = 0.0;
        if ((s.x & 1) == 0 && (s.y & 1) == 0) {
            ivec2 m = s / 2;
            vec4 d = texelFetch(uData, m, 0);  // r: height, b: error, a: radius (world units)
            float dist = distance(gridToWorld(m, d.r), uLodEye.xyz) - d.a;
            err = dist > 0.0 ? uFrameSize.z * d.b / dist : 1e6;
        }
        colour = heat(err / max(uFrameSize.w, 1e-6));
    }
    for (int k = 0; k < 3; ++k) {
        gWorld = vWorld[k];
        gColour = vec4(colour, 1.0);
        gl_Position = gl_in[k].gl_Position;
        EmitVertex();
    }
    EndPrimitive();
}
