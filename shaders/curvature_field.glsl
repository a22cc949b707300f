// The curvature field on the GPU: the same four-direction field as the CPU
// reference (engine: analysis/Curvature.h, whose definitions, border rule and
// order of operations this copies), drawn as a full-screen triangle
// (solid.vert) in two passes of this file:
//   CURVATURE_GRADIENT: the surface gradient (dy/dx, dy/dz) of every vertex
//     from its normal (edge, triangle or quad);
//   otherwise: the four directions' values of every vertex from the heights
//     and that gradient.
// No data is NaN in the heights. NaN is detected from its bits and
// produced from bits, never through arithmetic, so fast-math in a driver
// cannot drop it; a stencil with a no-data sample gives NaN explicitly.
//
// Laid out for a software rasteriser (llvmpipe): a fragment computes a run
// of CURVATURE_RUN (8) consecutive samples of a row and writes them to
// colour attachments, which llvmpipe stores as whole vectors (a compute
// shader's storage-buffer stores are a scalar loop over lanes and
// components there, and were half of its time). Fragment (c, j) computes
// samples (c * 8 + k, j), k = 0 ... 7; the engine attaches the layers of 2D
// array textures (render::CurvatureGpu):
//   field: RGBA32F, layer k = sample c * 8 + k, the 4 directions;
//   gradient: RGBA32F, layer q = samples c * 8 + 2q (.xy) and 2q + 1 (.zw).
// Three programs per pass (four with no data):
//   CURVATURE_RUNS: the interior formulas only, the run's window (rows
//     j - 1 ... j + 1 of 10 heights or gradients; at a reinforcement
//     distance D > 1 (CURVATURE_RUN_DISTANCE) rows j - D, j - 1 ... j + 1 and
//     j + D of 8 + 2D) read once as vec4 texels and shared by its samples;
//     drawn over rows R ... height - 1 - R (with no data only where the
//     window is clear of it, see below), R = 1 for the gradients and R = D
//     for the field, where all but the first and last R samples of a row are
//     interior; then
//   the general program: every sample on its own (border rule, no data,
//     reinforcement), the CPU's per-sample code; drawn over the first and
//     last R rows after the runs, or over the whole grid at distances
//     beyond CurvatureGpu::kMaxRunDistance; with no data, a stencil
//     (CurvatureGpu::runClearance) keeps the runs where their window is
//     clear of it, CURVATURE_NO_DATA writes NaN where a run has no data at
//     all, and the general program draws the rest of the interior rows; and
//   CURVATURE_ONE_SAMPLE: the general code for sample uSample of the run
//     only, into every output; drawn over one run of rows R ... height - 1 -
//     R with the other outputs masked (glColorMaski), once for each of the
//     first and last R samples of those rows.
// With CURVATURE_COMPUTE (curvature.comp) the general code runs as a compute
// shader instead, one sample (or gradient texel) per invocation, stored into
// the same layers as images: the path for GPUs, whose compute units outnumber
// the units that run fragments (on an H100 the fragment runs take 1.3-2.4 ms
// per 2049^2 field, the compute shader 0.1-0.3 ms); render::CurvatureGpu
// picks it for every driver but a software rasteriser.
const int kRun = 8;  // samples per fragment; CurvatureGpu::kRun

uniform ivec2 uSize;     // samples along x and z
uniform vec2 uSpacing;   // world distance between samples along x and z

bool noData(float v) {
    uint b = floatBitsToUint(v);
    return (b & 0x7f800000u) == 0x7f800000u && (b & 0x007fffffu) != 0u;
}
float nanValue() { return uintBitsToFloat(0x7fc00000u); }

// World heights (stored height * vertical scale), NaN = no data: sample
// (i, j) at float (j + 1) * CURVATURE_PITCH + i + 1 (rows of CURVATURE_PITCH
// floats, a multiple of 4, with a row and a float of padding before), so a
// run's window row starts a texel of the vec4 view.
#ifndef CURVATURE_PITCH
#define CURVATURE_PITCH 16
#endif
// Runs per row, ceil(width / 8): the layers' width.
#ifndef CURVATURE_RUNS_PER_ROW
#define CURVATURE_RUNS_PER_ROW 2
#endif
layout(binding = 2) uniform samplerBuffer uHeights;   // R32F view
layout(binding = 3) uniform samplerBuffer uHeights4;  // RGBA32F view
float heightAt(ivec2 ij) { return texelFetch(uHeights, (ij.y + 1) * CURVATURE_PITCH + ij.x + 1).r; }

#ifndef CURVATURE_COMPUTE
// The first sample of this fragment's run.
ivec2 runStart() { return ivec2(gl_FragCoord.xy) * ivec2(kRun, 1); }
#endif

// The reinforcement distance D the field's runs are compiled for (1 = none,
// and always 1 for the gradients; CurvatureGpu::kMaxRunDistance at most): a
// run's window reaches D samples beyond it on either side, and rows j - D and
// j + D.
#ifndef CURVATURE_RUN_DISTANCE
#define CURVATURE_RUN_DISTANCE 1
#endif
#if defined(CURVATURE_GRADIENT) && CURVATURE_RUN_DISTANCE != 1
#error "the gradient runs read a window of reach 1"
#endif
const int kD = CURVATURE_RUN_DISTANCE;
const int kW = kRun + 2 * kD;  // window samples per row: c * 8 - D ... c * 8 + 7 + D

// One window row of heights, samples c * 8 - D ... c * 8 + 7 + D of row j,
// read as whole texels (the bounds are constants: the loops unroll and the
// tests fold). Texel t + q holds samples c * 8 - 1 + 4q ... c * 8 + 2 + 4q.
void heightRow(int c, int j, out float w[kW]) {
    int t = (j + 1) * (CURVATURE_PITCH / 4) + c * (kRun / 4);
    for (int q = (1 - kD) >> 2; q <= (kRun + kD) >> 2; ++q) {
        vec4 v = texelFetch(uHeights4, t + q);
        for (int k = 0; k < 4; ++k) {
            int e = 4 * q + k - 1 + kD;
            if (e >= 0 && e < kW) w[e] = v[k];
        }
    }
}

#ifdef CURVATURE_GRADIENT

#ifndef CURVATURE_COMPUTE
layout(location = 0) out vec4 oGradient[kRun / 2];
#endif

// The normals are compiled in (CURVATURE_NORMALS 0 edge, 1 triangle, 2 quad,
// analysis::NormalMethod): a software rasteriser runs every branch of a
// uniform switch otherwise.
#ifndef CURVATURE_NORMALS
#define CURVATURE_NORMALS 2
#endif
const int uNormals = CURVATURE_NORMALS;

vec3 triangleNormal(vec3 a, vec3 b) { return normalize(cross(b, a)); }

#ifdef CURVATURE_RUNS

void main() {
    ivec2 f = ivec2(gl_FragCoord.xy);
    float s[kW], m[kW], n[kW];  // rows -1 (south), 0, +1 (north)
    heightRow(f.x, f.y - 1, s);
    heightRow(f.x, f.y, m);
    heightRow(f.x, f.y + 1, n);
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
    for (int q = 0; q < kRun / 2; ++q) oGradient[q] = vec4(g[2 * q], g[2 * q + 1]);
}

#else

// The 8 neighbours counter-clockwise from above: E, NE, N, NW, W, SW, S, SE.
const ivec2 kRing[8] = ivec2[8](ivec2(1, 0), ivec2(1, 1), ivec2(0, 1), ivec2(-1, 1), ivec2(-1, 0), ivec2(-1, -1),
                                ivec2(0, -1), ivec2(1, -1));

vec2 gradientAt(ivec2 ij) {
    if (ij.x >= uSize.x) return vec2(0.0);  // past the row's end in the last run
    float yc = heightAt(ij);
    if (noData(yc)) return vec2(nanValue());
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
    return vec2(-sum.x / sum.y, -sum.z / sum.y);
}

#if defined(CURVATURE_COMPUTE)
// One texel of the gradient layers per invocation: samples (8c + 2q, j) and
// (8c + 2q + 1, j) into layer q at (c, j), and into the buffer the field
// pass reads (uGradient's layout there) when uGradientCopy is set.
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba32f) uniform writeonly image2DArray uGradientLayers;
layout(binding = 1, rgba32f) uniform writeonly imageBuffer uGradientBuffer;
uniform int uGradientCopy;
void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID);  // (run * 4 + q, j)
    int c = id.x / (kRun / 2), q = id.x % (kRun / 2), j = id.y;
    if (c >= CURVATURE_RUNS_PER_ROW || j >= uSize.y) return;
    ivec2 s = ivec2(c * kRun + 2 * q, j);
    vec4 t = vec4(gradientAt(s), gradientAt(s + ivec2(1, 0)));
    imageStore(uGradientLayers, ivec3(c, j, q), t);
    if (uGradientCopy != 0) imageStore(uGradientBuffer, (q * uSize.y + j) * CURVATURE_RUNS_PER_ROW + c, t);
}
#elif defined(CURVATURE_NO_DATA)
// A run whose samples all have no data.
void main() {
    for (int q = 0; q < kRun / 2; ++q) oGradient[q] = vec4(nanValue());
}
#elif defined(CURVATURE_ONE_SAMPLE)
uniform int uSample;  // the sample of the run, 0 ... kRun - 1
void main() {
    vec2 g = gradientAt(runStart() + ivec2(uSample, 0));
    for (int q = 0; q < kRun / 2; ++q) oGradient[q] = vec4(g, g);
}
#else
void main() {
    ivec2 start = runStart();
    for (int q = 0; q < kRun / 2; ++q)
        oGradient[q] = vec4(gradientAt(start + ivec2(2 * q, 0)), gradientAt(start + ivec2(2 * q + 1, 0)));
}
#endif

#endif  // CURVATURE_RUNS

#else

#ifndef CURVATURE_COMPUTE
layout(location = 0) out vec4 oValue[kRun];
#endif

// (dy/dx, dy/dz) per sample, NaN = no data: the gradient pass's layers
// copied to a buffer (layer-major, then rows, then runs; llvmpipe fetches
// from a buffer texture far cheaper than from a 2D array texture), texel
// (layer * height + j) * CURVATURE_RUNS_PER_ROW + run.
layout(binding = 1) uniform samplerBuffer uGradient;
vec4 gradientTexel(int run, int j, int layer) {
    return texelFetch(uGradient, (layer * uSize.y + j) * CURVATURE_RUNS_PER_ROW + run);
}
vec2 gradientAt(ivec2 ij) {
    vec4 t = gradientTexel(ij.x / kRun, ij.y, (ij.x % kRun) / 2);
    return (ij.x & 1) == 0 ? t.xy : t.zw;
}
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

// Scale is applied by the caller; then level control and the sign.
float shaped(float value, float ypp) {
#ifdef CURVATURE_LEVELS
    float t = clamp((value - uLevels.y) / (uLevels.z - uLevels.y), 0.0, 1.0);
    value = t > 0.0 ? pow(t, 1.0 / uLevels.w) : 0.0;
#endif
    return uSigned == 1 && ypp < 0.0 ? -value : value;
}

#ifdef CURVATURE_RUNS

// One window row of row j: the gradients (normal methods) or the heights (in
// .x; the others) of samples c * 8 - D ... c * 8 + 7 + D, read as whole
// texels.
void windowRow(int c, int j, out vec2 w[kW]) {
    if (uMethod == 0 || uMethod == 1) {
        // Texel p (relative to the run, negative before it) holds samples
        // c * 8 + 2p and 2p + 1: run c + floor(p / 4), layer p mod 4.
        for (int p = (-kD) >> 1; p <= (kRun - 1 + kD) >> 1; ++p) {
            vec4 v = gradientTexel(c + (p >> 2), j, p & 3);
            int e = 2 * p + kD;  // window index of sample c * 8 + 2p
            if (e >= 0) w[e] = v.xy;
            if (e + 1 < kW) w[e + 1] = v.zw;
        }
    } else {
        float h[kW];
        heightRow(c, j, h);
        for (int k = 0; k < kW; ++k) w[k] = vec2(h[k], 0.0);
    }
}

// The measure of the interior stencil (p, v, n) along direction s, m steps
// apart: the CPU's arithmetic (analysis: Curvature.cpp, measure) without the
// no-data checks (the runs draw fields without no data only).
float runMeasure(vec2 p, vec2 v, vec2 n, ivec2 s, int m, out float ypp) {
    vec2 world = vec2(s) * uSpacing;
    float invLength = 1.0 / length(world);
    vec2 u = world * invLength;
    float invStep = invLength / float(m);
    if (uMethod == 0) {
        float sv = dot(v, u), sn = dot(n, u);
        ypp = (sn - sv) * invStep;
        return equation1(ypp, sv);
    } else if (uMethod == 1) {
        float sp = dot(p, u), sv = dot(v, u), sn = dot(n, u);
        ypp = 0.5 * (sn - sp) * invStep;
        float t = 1.0 + sv * sv;
        return 0.5 * (abs(sv - sp) + abs(sn - sv)) * invStep / (t * sqrt(t));
    } else if (uMethod == 2) {
        float s1 = (v.x - p.x) * invStep, s2 = (n.x - v.x) * invStep;
        ypp = (s2 - s1) * invStep;
        return equation1(ypp, 0.5 * (s1 + s2));
    } else {
        float hx = float(s.x * m) * uSpacing.x, hz = float(s.y * m) * uSpacing.y;
        float a = p.x - v.x, b = n.x - v.x;
        float d = -hx * hx + a * b - hz * hz;
        float cosTheta = d / sqrt((hx * hx + hz * hz + a * a) * (hx * hx + hz * hz + b * b));
        ypp = a + b;
        return clamp(1.0 + cosTheta, 0.0, 1.0);
    }
}

// One direction's output from its near stencil (p, v, n) and, at distance
// D > 1, its reinforcement stencil (fp, v, fn): the general code's order of
// operations (directionValue).
float runValue(vec2 p, vec2 v, vec2 n, vec2 fp, vec2 fn, ivec2 s) {
    float ypp;
    float value = runMeasure(p, v, n, s, 1, ypp);
    if (uSecond == 1) return ypp;
    value *= uScale;
#if CURVATURE_RUN_DISTANCE > 1
    float farYpp;
    value *= runMeasure(fp, v, fn, s, kD, farYpp);
#endif
    return shaped(value, ypp);
}

void main() {
    ivec2 f = ivec2(gl_FragCoord.xy);
    vec2 s[kW], m[kW], n[kW];  // rows -1 (south), 0, +1 (north)
    windowRow(f.x, f.y - 1, s);
    windowRow(f.x, f.y, m);
    windowRow(f.x, f.y + 1, n);
#if CURVATURE_RUN_DISTANCE > 1
    vec2 fs[kW], fn[kW];  // rows -D and +D
    windowRow(f.x, f.y - kD, fs);
    windowRow(f.x, f.y + kD, fn);
#else
#define fs s  // the reinforcement's stencils are never read at D = 1
#define fn n
#endif
    for (int k = 0; k < kRun; ++k) {
        // Direction steps (1, 0), (0, 1), (1, 1), (1, -1): previous, vertex,
        // next, then the reinforcement's previous and next (unused at D = 1).
        int v = k + kD;  // window index of sample c * 8 + k
        oValue[k] = vec4(runValue(m[v - 1], m[v], m[v + 1], m[v - kD], m[v + kD], ivec2(1, 0)),
                         runValue(s[v], m[v], n[v], fs[v], fn[v], ivec2(0, 1)),
                         runValue(s[v - 1], m[v], n[v + 1], fs[v - kD], fn[v + kD], ivec2(1, 1)),
                         runValue(n[v - 1], m[v], s[v + 1], fn[v - kD], fs[v + kD], ivec2(1, -1)));
    }
}

#else

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

vec4 sampleValue(ivec2 ij) {
    if (ij.x >= uSize.x) return vec4(0.0);  // past the row's end in the last run
    if (noData(heightAt(ij))) return vec4(nanValue());
    // Unrolled so each direction's step is a constant.
    return vec4(directionValue(ij, 0), directionValue(ij, 1), directionValue(ij, 2), directionValue(ij, 3));
}

#if defined(CURVATURE_COMPUTE)
// One sample per invocation, into layer i % 8 at (i / 8, j).
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba32f) uniform writeonly image2DArray uFieldLayers;
void main() {
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    if (ij.x >= CURVATURE_RUNS_PER_ROW * kRun || ij.y >= uSize.y) return;
    imageStore(uFieldLayers, ivec3(ij.x / kRun, ij.y, ij.x % kRun), sampleValue(ij));
}
#elif defined(CURVATURE_NO_DATA)
// A run whose samples all have no data.
void main() {
    for (int k = 0; k < kRun; ++k) oValue[k] = vec4(nanValue());
}
#elif defined(CURVATURE_ONE_SAMPLE)
uniform int uSample;  // the sample of the run, 0 ... kRun - 1
void main() {
    vec4 v = sampleValue(runStart() + ivec2(uSample, 0));
    for (int k = 0; k < kRun; ++k) oValue[k] = v;
}
#else
void main() {
    ivec2 start = runStart();
    for (int k = 0; k < kRun; ++k) oValue[k] = sampleValue(start + ivec2(k, 0));
}
#endif

#endif  // CURVATURE_RUNS

#endif  // CURVATURE_GRADIENT
