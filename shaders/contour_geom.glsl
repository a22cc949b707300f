#version 450 core
// Contour edges, geometry stage: passes on only the triangles that can draw
// part of a contour, so the fragment stage runs near the silhouettes instead
// of over the whole terrain a second time (on llvmpipe that second
// rasterisation was most of the contour pass's cost).
//
// contour.frag covers a fragment where |s| < (uWidth / 2 + 0.5) * fwidth(s),
// s = dot(normal, towards the eye). A triangle whose three s share a sign
// and whose smallest |s| is beyond that reach everywhere on it draws nothing
// and is dropped. fwidth(s) is estimated from the affine screen-space
// gradient of s over the triangle; perspective-correct interpolation can make
// the true derivative differ from that by up to the ratio of the vertices'
// clip w squared, which, and a factor 4, the reach takes in (the test errs on
// the side of keeping). Triangles with a vertex behind the eye are kept;
// zero-area ones (the strip's turns) have no fragments and are dropped.
#include "frame.glsl"

layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;

uniform float uWidth;  // pixels, as contour.frag

in ContourVertex {
    vec3 world;
    float facing;
} gIn[];
out ContourVertex {
    vec3 world;
    float facing;
} gOut;

bool mayDrawContour() {
    float s0 = gIn[0].facing, s1 = gIn[1].facing, s2 = gIn[2].facing;
    if (min(s0, min(s1, s2)) <= 0.0 && max(s0, max(s1, s2)) >= 0.0) return true;  // a sign change
    vec4 c0 = gl_in[0].gl_Position, c1 = gl_in[1].gl_Position, c2 = gl_in[2].gl_Position;
    float wMin = min(c0.w, min(c1.w, c2.w)), wMax = max(c0.w, max(c1.w, c2.w));
    if (wMin <= 1e-6) return true;
    vec2 halfSize = 0.5 * uFrameSize.xy;
    vec2 p0 = c0.xy / c0.w * halfSize, p1 = c1.xy / c1.w * halfSize, p2 = c2.xy / c2.w * halfSize;
    vec2 e1 = p1 - p0, e2 = p2 - p0;
    float area = e1.x * e2.y - e1.y * e2.x;  // twice the signed area in pixels^2
    if (abs(area) < 1e-8) return false;
    vec2 gradient = ((s1 - s0) * vec2(e2.y, -e2.x) + (s2 - s0) * vec2(-e1.y, e1.x)) / area;
    float perspective = (wMax / wMin) * (wMax / wMin);
    float reach = (0.5 * uWidth + 0.5) * (abs(gradient.x) + abs(gradient.y)) * 4.0 * perspective;
    return min(abs(s0), min(abs(s1), abs(s2))) <= reach;
}

void main() {
    if (!mayDrawContour()) return;
    for (int k = 0; k < 3; ++k) {
        gOut.world = gIn[k].world;
        gOut.facing = gIn[k].facing;
        gl_Position = gl_in[k].gl_Position;
        EmitVertex();
    }
    EndPrimitive();
}
