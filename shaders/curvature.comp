#version 450 core
#ifdef CURVATURE_RUNS
#extension GL_ARB_gpu_shader_int64 : require  // 64-bit stores: 2 floats per lane and component
#endif
// The curvature field on the GPU: the same four-direction field as the CPU
// reference (engine: analysis/Curvature.h, whose definitions, border rule and
// order of operations this copies), in two dispatches of this file:
//   CURVATURE_GRADIENT: the surface gradient (dy/dx, dy/dz) of every vertex
//     from its normal (edge, triangle or quad), into uGradientData;
//   otherwise: the four directions' values of every vertex from the heights
//     and that gradient, into uFieldData (4 floats per sample).
// No data is NaN in the heights. NaN is detected from its bits and
// produced from bits, never through arithmetic, so fast-math in a driver
// cannot drop it; a stencil with a no-data sample gives NaN explicitly.
//
// Laid out for a software rasteriser (llvmpipe runs each invocation as a lane
// of a SIMD loop): inputs are read through buffer textures (texelFetch from a
// samplerBuffer: a vector gather) and results written to storage buffers,
// which cost a quarter of an imageStore there; the heights or gradients
// around a vertex are fetched once (a 3x3 window) and shared by the four
// directions instead of being fetched per direction (see CURVATURE_NEAR).
//
// Fields without no-data take the fast path (CURVATURE_RUNS): each
// invocation computes a run of CURVATURE_RUN consecutive samples in
// row-major order with the interior formulas only, reading its heights or
// gradients as vec4 texels and writing 2 (field) or 4 (gradients) samples per
// 64-bit vector store; llvmpipe's per-invocation costs (a coroutine per 8
// invocations, one scalar store per lane and component, a gather per fetch)
// are then paid once per run instead of once per sample. The samples on the
// grid's border (clamped stencils, one-sided normals) are then overwritten
// by a second dispatch of the per-sample code (CURVATURE_BORDER).
// Workgroup size, set by the engine (CurvatureGpu.cpp); 16x16 by default.
#ifndef CURVATURE_GROUP_X
#define CURVATURE_GROUP_X 16
#define CURVATURE_GROUP_Y 16
#endif
layout(local_size_x = CURVATURE_GROUP_X, local_size_y = CURVATURE_GROUP_Y) in;

uniform ivec2 uSize;     // samples along x and z
uniform vec2 uSpacing;   // world distance between samples along x and z

bool noData(float v) {
    uint b = floatBitsToUint(v);
    return (b & 0x7f800000u) == 0x7f800000u && (b & 0x007fffffu) != 0u;
}
float nanValue() { return uintBitsToFloat(0x7fc00000u); }
// World heights (stored height * vertical scale), NaN = no data, row-major
// after a lead of CURVATURE_LEAD floats (the engine's padding, which aligns
// the runs' texels).
#ifndef CURVATURE_LEAD
#define CURVATURE_LEAD 4
#endif
// Gradients before sample 0 in the gradient buffer (a multiple of 4; the
// engine's padding, see CurvatureGpu.cpp).
#ifndef CURVATURE_GRADIENT_LEAD
#define CURVATURE_GRADIENT_LEAD 4
#endif
layout(binding = 2) uniform samplerBuffer uHeights;
float heightAt(ivec2 ij) { return texelFetch(uHeights, CURVATURE_LEAD + ij.y * uSize.x + ij.x).r; }

// The sample of this invocation: its grid position, or with CURVATURE_BORDER
// (a 1D dispatch over the 2 (width + height) - 4 border samples) the b-th
// border sample: row 0, row height - 1, then columns 0 and width - 1.
ivec2 sampleIndex() {
#ifdef CURVATURE_BORDER
    int b = int(gl_GlobalInvocationID.x);
    int w = uSize.x, h = uSize.y;
    if (b < w) return ivec2(b, 0);
    if (b < 2 * w) return ivec2(b - w, h - 1);
    b -= 2 * w;
    if (b < h - 2) return ivec2(0, 1 + b);
    if (b < 2 * (h - 2)) return ivec2(w - 1, 1 + b - (h - 2));
    return uSize;  // past the end: no sample
#else
    return ivec2(gl_GlobalInvocationID.xy);
#endif
}

#ifdef CURVATURE_RUNS
// Runs: CURVATURE_RUN samples per invocation (a multiple of 4), run r covers
// samples r * run ... in row-major order (a run may cross a row end; the
// border samples it gets wrong are overwritten). Rows -1, 0, +1 of the
// window: the values at samples r * run - 1 + rho * width ... + run + 1,
// which the engine locates as texel (base + CURVATURE_T<rho>) component
// CURVATURE_A<rho> onwards of the vec4 views (compile-time constants).
#ifndef CURVATURE_RUN
#define CURVATURE_RUN 8
#define CURVATURE_T0 0
#define CURVATURE_A0 0
#define CURVATURE_T1 0
#define CURVATURE_A1 0
#define CURVATURE_T2 0
#define CURVATURE_A2 0
#endif
const int kRun = CURVATURE_RUN;
const int kWin = CURVATURE_RUN + 2;  // window columns: -1 ... run
int runIndex() { return int(gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * int(gl_WorkGroupSize.x * gl_WorkGroupSize.y) + int(gl_LocalInvocationIndex); }
uint64_t pack2(float a, float b) { return packUint2x32(uvec2(floatBitsToUint(a), floatBitsToUint(b))); }
#endif

#ifdef CURVATURE_GRADIENT

// (dy/dx, dy/dz) per sample, row-major; NaN = no data.
#ifndef CURVATURE_RUNS
layout(std430, binding = 1) writeonly buffer GradientOut { vec2 uGradientData[]; };
#endif
// The normals are compiled in (CURVATURE_NORMALS 0 edge, 1 triangle, 2 quad,
// analysis::NormalMethod): a software rasteriser runs every branch of a
// uniform switch otherwise.
#ifndef CURVATURE_NORMALS
#define CURVATURE_NORMALS 2
#endif
const int uNormals = CURVATURE_NORMALS;

// The 8 neighbours counter-clockwise from above: E, NE, N, NW, W, SW, S, SE.
const ivec2 kRing[8] = ivec2[8](ivec2(1, 0), ivec2(1, 1), ivec2(0, 1), ivec2(-1, 1), ivec2(-1, 0), ivec2(-1, -1),
                                ivec2(0, -1), ivec2(1, -1));

vec3 triangleNormal(vec3 a, vec3 b) { return normalize(cross(b, a)); }

#ifdef CURVATURE_RUNS
// 4 gradients per 64-bit vector, row-major.
layout(std430, binding = 1) writeonly buffer GradientRuns { u64vec4 uGradientRuns[]; };
layout(binding = 3) uniform samplerBuffer uHeights4;  // the heights, 4 per texel

// One window row of heights: kWin values from texel t, component a.
void heightRow(int t, int a, out float w[kWin]) {
    for (int q = 0; q < (kWin + 3 + 3) / 4; ++q) {
        vec4 v = texelFetch(uHeights4, t + q);
        for (int c = 0; c < 4; ++c) {
            int k = 4 * q + c - a;
            if (k >= 0 && k < kWin) w[k] = v[c];
        }
    }
}

void main() {
    int r = runIndex();
    if (r * kRun >= uSize.x * uSize.y) return;
    int base = r * kRun / 4;
    float s[kWin], m[kWin], n[kWin];  // rows -1 (south), 0, +1 (north)
    heightRow(base + CURVATURE_T0, CURVATURE_A0, s);
    heightRow(base + CURVATURE_T1, CURVATURE_A1, m);
    heightRow(base + CURVATURE_T2, CURVATURE_A2, n);
    const float hx = uSpacing.x, hz = uSpacing.y;
    vec2 g[kRun];
    for (int k = 0; k < kRun; ++k) {
        // The interior sums of the CPU (analysis: Internal.h, interiorNormalSums).
        float c = m[k + 1];
        vec3 e = vec3(hx, m[k + 2] - c, 0.0), w = vec3(-hx, m[k] - c, 0.0);
        vec3 no = vec3(0.0, n[k + 1] - c, hz), so = vec3(0.0, s[k + 1] - c, -hz);
        vec3 sum;
        if (uNormals == 0) {
            sum = vec3(-(e.y - w.y) / (2.0 * hx), 1.0, -(no.y - so.y) / (2.0 * hz));
        } else if (uNormals == 1) {
            sum = triangleNormal(e, no) + triangleNormal(no, w) + triangleNormal(w, so) + triangleNormal(so, e);
        } else {
            vec3 ne = vec3(hx, n[k + 2] - c, hz), nw = vec3(-hx, n[k] - c, hz);
            vec3 sw = vec3(-hx, s[k] - c, -hz), se = vec3(hx, s[k + 2] - c, -hz);
            sum = normalize(triangleNormal(e, ne) + triangleNormal(ne, no)) +
                  normalize(triangleNormal(no, nw) + triangleNormal(nw, w)) +
                  normalize(triangleNormal(w, sw) + triangleNormal(sw, so)) +
                  normalize(triangleNormal(so, se) + triangleNormal(se, e));
        }
        float inv = 1.0 / sum.y;
        g[k] = vec2(-sum.x * inv, -sum.z * inv);
    }
    for (int q = 0; q < kRun / 4; ++q) {
        uGradientRuns[(CURVATURE_GRADIENT_LEAD + r * kRun) / 4 + q] = u64vec4(pack2(g[4 * q].x, g[4 * q].y), pack2(g[4 * q + 1].x, g[4 * q + 1].y),
                                                    pack2(g[4 * q + 2].x, g[4 * q + 2].y), pack2(g[4 * q + 3].x, g[4 * q + 3].y));
    }
}

#else

void main() {
    ivec2 ij = sampleIndex();
    if (any(greaterThanEqual(ij, uSize))) return;
    float yc = heightAt(ij);
    if (noData(yc)) {
        uGradientData[CURVATURE_GRADIENT_LEAD + ij.y * uSize.x + ij.x] = vec2(nanValue());
        return;
    }
    vec3 e[8];
    bool ok[8];
    for (int k = 0; k < 8; ++k) {
        ivec2 n = ij + kRing[k];
        ok[k] = all(greaterThanEqual(n, ivec2(0))) && all(lessThan(n, uSize));
        float y = ok[k] ? heightAt(n) : 0.0;
        ok[k] = ok[k] && !noData(y);
        e[k] = vec3(float(kRing[k].x) * uSpacing.x, ok[k] ? y - yc : 0.0, float(kRing[k].y) * uSpacing.y);
    }
    vec3 sum = vec3(0.0);
    if (uNormals == 0) {
        // Mean edge slope per axis, one-sided at the border or beside no data.
        float sx = 0.0, sz = 0.0;
        int nx = 0, nz = 0;
        if (ok[0]) { sx += e[0].y / uSpacing.x; ++nx; }
        if (ok[4]) { sx -= e[4].y / uSpacing.x; ++nx; }
        if (ok[2]) { sz += e[2].y / uSpacing.y; ++nz; }
        if (ok[6]) { sz -= e[6].y / uSpacing.y; ++nz; }
        sum = vec3(nx > 0 ? -sx / float(nx) : 0.0, 1.0, nz > 0 ? -sz / float(nz) : 0.0);
    } else {
        for (int q = 0; q < 4; ++q) {
            int a = 2 * q, c = 2 * q + 1, b = (2 * q + 2) & 7;
            if (uNormals == 1) {
                if (ok[a] && ok[b]) sum += triangleNormal(e[a], e[b]);
            } else if (ok[a] && ok[b] && ok[c]) {
                sum += normalize(triangleNormal(e[a], e[c]) + triangleNormal(e[c], e[b]));
            }
        }
    }
    if (sum.y <= 0.0) sum = vec3(0.0, 1.0, 0.0);  // no usable neighbour
    uGradientData[CURVATURE_GRADIENT_LEAD + ij.y * uSize.x + ij.x] = vec2(-sum.x / sum.y, -sum.z / sum.y);
}

#endif  // CURVATURE_RUNS

#else

layout(binding = 1) uniform samplerBuffer uGradient;  // (dy/dx, dy/dz) per sample, NaN = no data
vec2 gradientAt(ivec2 ij) { return texelFetch(uGradient, ij.y * uSize.x + ij.x).rg; }
// The 4 directions per sample, row-major.
#ifndef CURVATURE_RUNS
layout(std430, binding = 1) writeonly buffer FieldOut { vec4 uFieldData[]; };
#endif
// The method is compiled in (CURVATURE_METHOD 0 two-normal, 1 three-normal,
// 2 three-vertex, 3 edge-angle): a software rasteriser runs every branch of
// a uniform switch otherwise.
#ifndef CURVATURE_METHOD
#define CURVATURE_METHOD 1
#endif
const int uMethod = CURVATURE_METHOD;
uniform int uDistance;   // reinforcement distance in steps, 1 = none
uniform float uScale;    // multiplies every value
// Level control is compiled in (CURVATURE_LEVELS) rather than switched by a
// uniform: a software rasteriser runs a uniform branch's body (pow) anyway.
uniform vec4 uLevels;    // with CURVATURE_LEVELS: y black, z white, w gamma
uniform int uSigned;     // 1 = keep the sign of y''
uniform int uSecond;     // 1 = output y'' itself (CurvatureOutput::SecondDerivative)

const ivec2 kSteps[4] = ivec2[4](ivec2(1, 0), ivec2(0, 1), ivec2(1, 1), ivec2(1, -1));

float equation1(float ypp, float yp) {
    float t = 1.0 + yp * yp;
    return abs(ypp) / (t * sqrt(t));
}

// One measure from its stencil along a direction with unit horizontal
// vector u, 1 / step length invStep: the gradients (normal methods) or the
// heights (in .x; the others) of the previous vertex p, the vertex v and the
// next one n (p unused by two-normal). False when one has no data.
bool measureFrom(vec2 p, vec2 v, vec2 n, ivec2 sm, vec2 u, float invStep, out float value, out float ypp) {
    value = 0.0;
    ypp = 0.0;
    if (uMethod == 0 || uMethod == 1) {
        if (noData(v.x) || noData(n.x)) return false;
        float sv = dot(v, u), sn = dot(n, u);
        if (uMethod == 0) {
            ypp = (sn - sv) * invStep;
            value = equation1(ypp, sv);
        } else {
            if (noData(p.x)) return false;
            float sp = dot(p, u);
            ypp = 0.5 * (sn - sp) * invStep;
            float t = 1.0 + sv * sv;
            value = 0.5 * (abs(sv - sp) + abs(sn - sv)) * invStep / (t * sqrt(t));
        }
        return true;
    }
    float yp = p.x, yv = v.x, yn = n.x;
    if (noData(yp) || noData(yv) || noData(yn)) return false;
    if (uMethod == 2) {
        float s1 = (yv - yp) * invStep, s2 = (yn - yv) * invStep;
        ypp = (s2 - s1) * invStep;
        value = equation1(ypp, 0.5 * (s1 + s2));
    } else {
        float hx = float(sm.x) * uSpacing.x, hz = float(sm.y) * uSpacing.y;
        float a = yp - yv, b = yn - yv;
        float d = -hx * hx + a * b - hz * hz;
        float cosTheta = d / sqrt((hx * hx + hz * hz + a * a) * (hx * hx + hz * hz + b * b));
        ypp = a + b;
        value = clamp(1.0 + cosTheta, 0.0, 1.0);
    }
    return true;
}

// What a measure reads at a sample: its gradient or its height (in .x).
vec2 stencilValue(ivec2 ij) {
    if (uMethod == 0 || uMethod == 1) return gradientAt(ij);
    return vec2(heightAt(ij), 0.0);
}

// One measure (m = 1 near, m = distance for reinforcement) centred on c along
// step s with unit horizontal direction u and step length 1 / invLength,
// fetching its stencil.
bool measure(ivec2 c, ivec2 s, vec2 u, float invLength, int m, out float value, out float ypp) {
    ivec2 sm = s * m;
    vec2 p = uMethod == 0 ? vec2(0.0) : stencilValue(c - sm);
    return measureFrom(p, stencilValue(c), stencilValue(c + sm), sm, u, invLength / float(m), value, ypp);
}

// The clamp range of one axis (the stencil centre stays inside the grid).
ivec2 axisRange(int c, int size, int back, int forward) {
    if (c == 0) return ivec2(0, size - 1);
    return c > 0 ? ivec2(back, size - 1 - forward) : ivec2(forward, size - 1 - back);
}

// The border rule: the stencil centre of direction step s for vertex ij.
ivec2 stencilCentre(ivec2 ij, ivec2 s) {
    int back = uMethod == 0 ? 0 : uDistance;
    int forward = uMethod == 0 ? 1 : uDistance;
    ivec2 ri = axisRange(s.x, uSize.x, back, forward);
    ivec2 rj = axisRange(s.y, uSize.y, back, forward);
    return ivec2(clamp(ij.x, ri.x, ri.y), clamp(ij.y, rj.x, rj.y));
}

// Scale is applied by the caller; then level control and the sign.
float shaped(float value, float ypp) {
#ifdef CURVATURE_LEVELS
    float t = clamp((value - uLevels.y) / (uLevels.z - uLevels.y), 0.0, 1.0);
    value = t > 0.0 ? pow(t, 1.0 / uLevels.w) : 0.0;
#endif
    return uSigned == 1 && ypp < 0.0 ? -value : value;
}

#ifdef CURVATURE_RUNS

// 2 samples (8 floats) per 64-bit vector, row-major.
layout(std430, binding = 1) writeonly buffer FieldRuns { u64vec4 uFieldRuns[]; };
// What the methods read, 4 floats per texel: heights, or 2 gradients.
layout(binding = 3) uniform samplerBuffer uWindow4;

// One window row: kWin heights (x only) or gradients from texel t, float a.
void windowRow(int t, int a, out vec2 w[kWin]) {
    if (uMethod == 0 || uMethod == 1) {
        for (int q = 0; q < (2 * kWin + 3 + 3) / 4; ++q) {
            vec4 v = texelFetch(uWindow4, t + q);
            for (int c = 0; c < 2; ++c) {
                int k = 2 * q + c - a / 2;
                if (k >= 0 && k < kWin) w[k] = c == 0 ? v.xy : v.zw;
            }
        }
    } else {
        for (int q = 0; q < (kWin + 3 + 3) / 4; ++q) {
            vec4 v = texelFetch(uWindow4, t + q);
            for (int c = 0; c < 4; ++c) {
                int k = 4 * q + c - a;
                if (k >= 0 && k < kWin) w[k] = vec2(v[c], 0.0);
            }
        }
    }
}

// The measure of the interior stencil (p, v, n) along direction s: the
// CPU's arithmetic (analysis: Curvature.cpp, measure) without the no-data
// checks (the fast path runs on fields without no data only).
float runValue(vec2 p, vec2 v, vec2 n, ivec2 s) {
    vec2 world = vec2(s) * uSpacing;
    float invStep = 1.0 / length(world);
    vec2 u = world * invStep;
    float value, ypp;
    if (uMethod == 0) {
        float sv = dot(v, u), sn = dot(n, u);
        ypp = (sn - sv) * invStep;
        value = equation1(ypp, sv);
    } else if (uMethod == 1) {
        float sp = dot(p, u), sv = dot(v, u), sn = dot(n, u);
        ypp = 0.5 * (sn - sp) * invStep;
        float t = 1.0 + sv * sv;
        value = 0.5 * (abs(sv - sp) + abs(sn - sv)) * invStep / (t * sqrt(t));
    } else if (uMethod == 2) {
        float s1 = (v.x - p.x) * invStep, s2 = (n.x - v.x) * invStep;
        ypp = (s2 - s1) * invStep;
        value = equation1(ypp, 0.5 * (s1 + s2));
    } else {
        float hx = world.x, hz = world.y;
        float a = p.x - v.x, b = n.x - v.x;
        float d = -hx * hx + a * b - hz * hz;
        float cosTheta = d / sqrt((hx * hx + hz * hz + a * a) * (hx * hx + hz * hz + b * b));
        ypp = a + b;
        value = clamp(1.0 + cosTheta, 0.0, 1.0);
    }
    return uSecond == 1 ? ypp : shaped(value * uScale, ypp);
}

void main() {
    int r = runIndex();
    if (r * kRun >= uSize.x * uSize.y) return;
    int base = r * kRun / (uMethod <= 1 ? 2 : 4);
    vec2 s[kWin], m[kWin], n[kWin];  // rows -1 (south), 0, +1 (north)
    windowRow(base + CURVATURE_T0, CURVATURE_A0, s);
    windowRow(base + CURVATURE_T1, CURVATURE_A1, m);
    windowRow(base + CURVATURE_T2, CURVATURE_A2, n);
    vec4 f[kRun];
    for (int k = 0; k < kRun; ++k) {
        // Direction steps (1, 0), (0, 1), (1, 1), (1, -1): previous, vertex, next.
        f[k] = vec4(runValue(m[k], m[k + 1], m[k + 2], ivec2(1, 0)), runValue(s[k + 1], m[k + 1], n[k + 1], ivec2(0, 1)),
                    runValue(s[k], m[k + 1], n[k + 2], ivec2(1, 1)), runValue(n[k], m[k + 1], s[k + 2], ivec2(1, -1)));
    }
    for (int q = 0; q < kRun / 2; ++q) {
        vec4 a = f[2 * q], b = f[2 * q + 1];
        uFieldRuns[r * (kRun / 2) + q] = u64vec4(pack2(a.x, a.y), pack2(a.z, a.w), pack2(b.x, b.y), pack2(b.z, b.w));
    }
}

#elif defined(CURVATURE_NEAR)

// Without reinforcement (distance 1) every direction's stencil, border rule
// included, lies in the 3x3 window of samples around
// clamp(ij, 1, size - 2): it is fetched once, and a direction picks its
// three values by selects (a software rasteriser turns indexing by a
// varying value into memory traffic).
vec2 pick(vec2 w[9], ivec2 o) {
    vec2 r0 = o.x == 0 ? w[0] : (o.x == 1 ? w[1] : w[2]);
    vec2 r1 = o.x == 0 ? w[3] : (o.x == 1 ? w[4] : w[5]);
    vec2 r2 = o.x == 0 ? w[6] : (o.x == 1 ? w[7] : w[8]);
    return o.y == 0 ? r0 : (o.y == 1 ? r1 : r2);
}

vec2 pick3(vec2 a, vec2 b, vec2 c, int k) { return k == 0 ? a : (k == 1 ? b : c); }

float directionValue(vec2 w[9], ivec2 ij, ivec2 cc, int d) {
    ivec2 s = kSteps[d];
    vec2 world = vec2(s) * uSpacing;
    float invLength = 1.0 / length(world);
    vec2 u = world * invLength;
    vec2 p, v, n;
    if (uMethod == 0) {
        ivec2 o = stencilCentre(ij, s) - cc + 1;
        p = vec2(0.0);
        v = pick(w, o);
        n = pick(w, o + s);
    } else if (d == 0) {
        // Three-point stencils: along the axes the direction moves on, the
        // clamped centre is cc's own, so only the other axis's offset varies.
        int r = ij.y - cc.y + 1;
        p = pick3(w[0], w[3], w[6], r);
        v = pick3(w[1], w[4], w[7], r);
        n = pick3(w[2], w[5], w[8], r);
    } else if (d == 1) {
        int q = ij.x - cc.x + 1;
        p = pick3(w[0], w[1], w[2], q);
        v = pick3(w[3], w[4], w[5], q);
        n = pick3(w[6], w[7], w[8], q);
    } else if (d == 2) {
        p = w[0];
        v = w[4];
        n = w[8];
    } else {
        p = w[6];
        v = w[4];
        n = w[2];
    }
    float value, ypp;
    if (!measureFrom(p, v, n, s, u, invLength, value, ypp)) return nanValue();
    if (uSecond == 1) return ypp;
    return shaped(value * uScale, ypp);
}

void main() {
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(ij, uSize))) return;
    ivec2 cc = clamp(ij, ivec2(1), uSize - 2);
    vec2 w[9];
    for (int k = 0; k < 9; ++k) w[k] = stencilValue(cc + ivec2(k % 3 - 1, k / 3 - 1));
    vec4 out4;
    // A gradient has no data exactly where its height has none.
    if (noData(pick(w, ij - cc + 1).x)) {
        out4 = vec4(nanValue());
    } else {
        // Unrolled so each direction's step is a constant.
        out4 = vec4(directionValue(w, ij, cc, 0), directionValue(w, ij, cc, 1), directionValue(w, ij, cc, 2),
                    directionValue(w, ij, cc, 3));
    }
    uFieldData[ij.y * uSize.x + ij.x] = out4;
}

#else

float directionValue(ivec2 ij, int d) {
    ivec2 s = kSteps[d];
    vec2 world = vec2(s) * uSpacing;
    float invLength = 1.0 / length(world);
    vec2 u = world * invLength;
    ivec2 c = stencilCentre(ij, s);
    float value, ypp;
    if (!measure(c, s, u, invLength, 1, value, ypp)) return nanValue();
    if (uSecond == 1) return ypp;
    value *= uScale;
    if (uDistance > 1) {
        float far, farYpp;
        if (!measure(c, s, u, invLength, uDistance, far, farYpp)) return nanValue();
        value *= far;
    }
    return shaped(value, ypp);
}

void main() {
    ivec2 ij = sampleIndex();
    if (any(greaterThanEqual(ij, uSize))) return;
    vec4 out4;
    if (noData(heightAt(ij))) {
        out4 = vec4(nanValue());
    } else {
        // Unrolled so each direction's step is a constant.
        out4 = vec4(directionValue(ij, 0), directionValue(ij, 1), directionValue(ij, 2), directionValue(ij, 3));
    }
    uFieldData[ij.y * uSize.x + ij.x] = out4;
}

#endif  // CURVATURE_RUNS, CURVATURE_NEAR

#endif
