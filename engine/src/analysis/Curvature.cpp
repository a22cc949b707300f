#include <sierra/analysis/Curvature.h>

#include "Internal.h"

#include <sierra/core/Error.h>

#include <algorithm>
#include <cmath>

namespace sierra::analysis {

const char* curvatureMethodName(CurvatureMethod method) {
    switch (method) {
        case CurvatureMethod::TwoNormal:
            return "two-normal";
        case CurvatureMethod::ThreeNormal:
            return "three-normal";
        case CurvatureMethod::ThreeVertex:
            return "three-vertex";
        case CurvatureMethod::EdgeAngle:
            return "edge-angle";
    }
    return "?";
}

CurvatureMethod parseCurvatureMethod(const std::string& name) {
    if (name == "two-normal") return CurvatureMethod::TwoNormal;
    if (name == "three-normal") return CurvatureMethod::ThreeNormal;
    if (name == "three-vertex") return CurvatureMethod::ThreeVertex;
    if (name == "edge-angle") return CurvatureMethod::EdgeAngle;
    throw Error(msg("unknown curvature method '", name,
                    "' (expected two-normal, three-normal, three-vertex or edge-angle)"));
}

void validate(const CurvatureOptions& o) {
    SIERRA_CHECK(o.distance >= 1,
                 "curvature: reinforcement distance must be an integer >= 1 (1 = none), got ",
                 o.distance);
    SIERRA_CHECK(o.method != CurvatureMethod::TwoNormal || o.distance == 1,
                 "curvature: two-normal has no reinforcement (distance must be 1, got ", o.distance,
                 "); use three-normal for a reinforcement distance");
    SIERRA_CHECK(std::isfinite(o.scale) && o.scale >= 0.0f,
                 "curvature: scale must be finite and >= 0, got ", o.scale);
    if (o.levels.enabled) {
        SIERRA_CHECK(std::isfinite(o.levels.black) && o.levels.black >= 0.0f,
                     "curvature: levels black point must be finite and >= 0, got ", o.levels.black);
        SIERRA_CHECK(std::isfinite(o.levels.white) && o.levels.white > o.levels.black,
                     "curvature: levels white point must be finite and above the black point (",
                     o.levels.black, "), got ", o.levels.white);
        SIERRA_CHECK(std::isfinite(o.levels.gamma) && o.levels.gamma > 0.0f,
                     "curvature: levels gamma must be finite and > 0, got ", o.levels.gamma);
    }
    if (o.output == CurvatureOutput::SecondDerivative) {
        SIERRA_CHECK(o.method != CurvatureMethod::EdgeAngle,
                     "curvature: edge-angle has no second derivative (it does not use Equation 1)");
        SIERRA_CHECK(o.distance == 1,
                     "curvature: the second-derivative output takes no reinforcement (distance ",
                     o.distance, ")");
    }
}

float CurvatureField::maxMagnitude(int i, int j) const {
    int d = maxDirection(i, j);
    return d < 0 ? NAN : std::fabs(at(i, j, d));
}

int CurvatureField::maxDirection(int i, int j) const {
    int best = -1;
    float bestValue = 0.0f;
    for (int d = 0; d < kDirectionCount; ++d) {
        float v = std::fabs(at(i, j, d));
        if (std::isnan(v)) continue;
        if (best < 0 || v > bestValue) {
            best = d;
            bestValue = v;
        }
    }
    return best;
}

std::vector<float> largestMagnitudes(const CurvatureField& field) {
    std::vector<float> largest;
    largest.reserve(size_t(field.width) * size_t(field.height));
    for (int j = 0; j < field.height; ++j)
        for (int i = 0; i < field.width; ++i)
            if (const float v = field.maxMagnitude(i, j); std::isfinite(v)) largest.push_back(v);
    return largest;
}

float topFivePercent(std::vector<float>& values) {
    if (values.empty()) return 0.0f;
    const auto top = values.begin() + std::ptrdiff_t(0.95 * double(values.size() - 1));
    std::nth_element(values.begin(), top, values.end());
    return *top;
}

float scaleToReach(float top, float scale, float target) {
    if (!(top > 0.0f) || !std::isfinite(top) || !(target > 0.0f) || scale == 0.0f) return scale;
    return float(double(scale) * double(target) / double(top));
}

namespace {

// Per-direction constants: step, its world length, the horizontal unit
// vector, and the range the stencil centre is clamped to.
struct DirectionSetup {
    int di = 0, dj = 0;
    int64_t offset = 0;  // index step
    float length = 1.0f, invLength = 1.0f;
    float ux = 0.0f, uz = 0.0f;
    int loI = 0, hiI = 0, loJ = 0, hiJ = 0;
};

// Clamp range of one axis for a stencil reaching `back` steps behind and
// `forward` steps ahead along a step component `c` in {-1, 0, 1}.
void axisRange(int c, int size, int back, int forward, int& lo, int& hi) {
    if (c == 0) {
        lo = 0;
        hi = size - 1;
    } else if (c > 0) {
        lo = back;
        hi = size - 1 - forward;
    } else {
        lo = forward;
        hi = size - 1 - back;
    }
}

// Everything one direction's measure reads, as plain values: built as a
// local in each loop, so the compiler knows no store to the output changes
// them and vectorises the loops without reloading or alias checks.
struct View {
    const float* raw = nullptr;  // stored heights (world = raw * yScale)
    float yScale = 1.0f;
    const float* gx = nullptr;  // gradient rows, vertex k at gx[k - gradBase]
    const float* gz = nullptr;
    int64_t gradBase = 0;
    int64_t offset = 0;  // index step of the direction
    float invLength = 1.0f;
    float ux = 0.0f, uz = 0.0f;
    float hx = 0.0f, hz = 0.0f;  // world step along x and z

    // Slope of the tangent plane at index k along the direction.
    float slope(int64_t k) const { return gx[k - gradBase] * ux + gz[k - gradBase] * uz; }
    float y(int64_t k) const { return raw[k] * yScale; }
};

inline float equation1(float ypp, float yp) {
    float t = 1.0f + yp * yp;
    return std::fabs(ypp) / (t * std::sqrt(t));
}

// Near (m = 1) or reinforcement (m = distance) measure at centre index k;
// ypp receives the signed second derivative (or a value of its sign).
template <CurvatureMethod kMethod>
[[gnu::always_inline]] inline float measure(const View& v, int64_t k, int m, float& ypp) {
    const int64_t s = v.offset * m;
    const float invStep = v.invLength / float(m);
    if constexpr (kMethod == CurvatureMethod::TwoNormal) {
        float sv = v.slope(k), sn = v.slope(k + s);
        ypp = (sn - sv) * invStep;
        return equation1(ypp, sv);
    } else if constexpr (kMethod == CurvatureMethod::ThreeNormal) {
        float sp = v.slope(k - s), sv = v.slope(k), sn = v.slope(k + s);
        ypp = 0.5f * (sn - sp) * invStep;  // the mean of the two pairs' y''
        float t = 1.0f + sv * sv;
        return 0.5f * (std::fabs(sv - sp) + std::fabs(sn - sv)) * invStep / (t * std::sqrt(t));
    } else if constexpr (kMethod == CurvatureMethod::ThreeVertex) {
        const float yp = v.y(k - s), yv = v.y(k), yn = v.y(k + s);
        float s1 = (yv - yp) * invStep, s2 = (yn - yv) * invStep;
        ypp = (s2 - s1) * invStep;
        return equation1(ypp, 0.5f * (s1 + s2));
    } else {
        const float hx = v.hx * float(m), hz = v.hz * float(m);
        const float yv = v.y(k);
        float a = v.y(k - s) - yv, b = v.y(k + s) - yv;
        // e1 = (-hx, a, -hz), e2 = (hx, b, hz)
        float dot = -hx * hx + a * b - hz * hz;
        float cosTheta = dot / std::sqrt((hx * hx + hz * hz + a * a) * (hx * hx + hz * hz + b * b));
        ypp = a + b;  // sign of y''
        // Clamp to [0, 1]; std::max(v, 0) and std::min(v, 1) keep a NaN
        // (no data) and map to min/max instructions.
        return std::min(std::max(1.0f + cosTheta, 0.0f), 1.0f);
    }
}

struct Kernel {
    const detail::WorldGrid* g = nullptr;
    // Surface gradient dy/dx, dy/dz (normal methods) of the rows a chunk
    // needs, from row index gradBase on: vertex k is at gx[k - gradBase].
    const float* gx = nullptr;
    const float* gz = nullptr;
    int64_t gradBase = 0;
    CurvatureOptions opt;
    DirectionSetup dir[kDirectionCount];

    View view(const DirectionSetup& d) const {
        return {.raw = g->raw,
                .yScale = g->scale,
                .gx = gx,
                .gz = gz,
                .gradBase = gradBase,
                .offset = d.offset,
                .invLength = d.invLength,
                .ux = d.ux,
                .uz = d.uz,
                .hx = float(d.di) * g->spacingX,
                .hz = float(d.dj) * g->spacingZ};
    }

    // Level control and sign on a finished magnitude.
    float finish(float value, float ypp) const {
        if (opt.levels.enabled) {
            float t = std::clamp((value - opt.levels.black) / (opt.levels.white - opt.levels.black),
                                 0.0f, 1.0f);
            value = std::pow(t, 1.0f / opt.levels.gamma);
        }
        return opt.signedValues && ypp < 0.0f ? -value : value;
    }

    // Direction d at vertices [iLo, iHi) of row j, all with their stencils
    // inside the grid (no clamping): plain loops, one per option set, that
    // the compiler vectorises. Writes buf[i]; levels are applied afterwards.
    template <CurvatureMethod kMethod>
    void interior(int j, int iLo, int iHi, const DirectionSetup& ds, float* __restrict buf,
                  float* __restrict second) const {
        const View v = view(ds);
        const int64_t row = int64_t(j) * g->width;
        const float scale = opt.scale;
        const int dist = opt.distance;
        // Straight arithmetic first, selects in loops of their own: GCC 12
        // does not vectorise the measure with a select in the same loop. buf
        // and second never overlap the heights or gradients (SIERRA_IVDEP: no
        // run-time alias checks).
        SIERRA_IVDEP
        for (int i = iLo; i < iHi; ++i) buf[i] = measure<kMethod>(v, row + i, 1, second[i]);
        if (opt.output == CurvatureOutput::SecondDerivative) {
            for (int i = iLo; i < iHi; ++i) buf[i] = second[i];
            return;
        }
        for (int i = iLo; i < iHi; ++i) buf[i] *= scale;
        if (dist > 1) {
            SIERRA_IVDEP
            for (int i = iLo; i < iHi; ++i) {
                float farYpp;
                buf[i] *= measure<kMethod>(v, row + i, dist, farYpp);
            }
        }
        if (opt.levels.enabled) {
            for (int i = iLo; i < iHi; ++i) buf[i] = finish(buf[i], second[i]);  // pow: scalar
        } else if (opt.signedValues) {
            for (int i = iLo; i < iHi; ++i) buf[i] = second[i] < 0.0f ? -buf[i] : buf[i];
        }
    }

    // One vertex, one direction, with the border clamp.
    template <CurvatureMethod kMethod>
    float clamped(int i, int j, const DirectionSetup& ds) const {
        const int ci = std::clamp(i, ds.loI, ds.hiI), cj = std::clamp(j, ds.loJ, ds.hiJ);
        const int64_t c = int64_t(cj) * g->width + ci;
        const View v = view(ds);
        float ypp = 0.0f;
        float value = measure<kMethod>(v, c, 1, ypp);
        if (opt.output == CurvatureOutput::SecondDerivative) return ypp;
        value *= opt.scale;
        if (opt.distance > 1) {
            float farYpp;
            value *= measure<kMethod>(v, c, opt.distance, farYpp);
        }
        return finish(value, ypp);
    }

    template <CurvatureMethod kMethod>
    void rows(int j0, int j1, float* out) const {
        const int w = g->width, h = g->height;
        std::vector<float> buf(size_t(w) * kDirectionCount);
        std::vector<float> yppRow(size_t(w), 0.0f);  // y'' (or its sign) of the near measure
        for (int j = j0; j < j1; ++j) {
            const bool interiorRow = j >= reach && j < h - reach;
            const int iLo = interiorRow ? reach : w, iHi = interiorRow ? w - reach : w;
            for (int d = 0; d < kDirectionCount; ++d) {
                float* b = buf.data() + size_t(d) * size_t(w);
                if (iLo < iHi) interior<kMethod>(j, iLo, iHi, dir[d], b, yppRow.data());
                for (int i = 0; i < w; ++i) {
                    if (i == iLo && iLo < iHi) i = iHi;
                    if (i >= w) break;
                    b[i] = clamped<kMethod>(i, j, dir[d]);
                }
            }
            float* o = out + int64_t(j) * w * kDirectionCount;
            for (int i = 0; i < w; ++i) {
                if (std::isnan(g->raw[size_t(j) * size_t(w) + size_t(i)])) {
                    for (int d = 0; d < kDirectionCount; ++d) o[i * kDirectionCount + d] = NAN;
                } else {
                    for (int d = 0; d < kDirectionCount; ++d)
                        o[i * kDirectionCount + d] = buf[size_t(d) * size_t(w) + size_t(i)];
                }
            }
        }
    }

    int reach = 1;  // largest stencil reach in steps: no clamping within it of the border
};

}  // namespace

CurvatureField computeCurvature(const terrain::Heightfield& field,
                                const CurvatureOptions& options) {
    CurvatureField out;
    computeCurvature(field, options, out);
    return out;
}

void computeCurvature(const terrain::Heightfield& field, const CurvatureOptions& options,
                      CurvatureField& out) {
    validate(options);
    SIERRA_CHECK(!field.empty(), "curvature: the heightfield is empty");
    const int minSide = 2 * options.distance + 1;
    SIERRA_CHECK(field.width() >= std::max(3, minSide) && field.height() >= std::max(3, minSide),
                 "curvature: a ", field.width(), "x", field.height(),
                 " grid is too small for reinforcement distance ", options.distance,
                 " (each side needs at least ", std::max(3, minSide), " samples)");

    const int threads = options.threads;
    detail::WorldGrid g;
    detail::makeWorldGrid(field, threads, g);
    const int w = g.width, h = g.height;

    Kernel kernel;
    kernel.g = &g;
    kernel.opt = options;
    const int back = options.method == CurvatureMethod::TwoNormal ? 0 : options.distance;
    const int forward = options.method == CurvatureMethod::TwoNormal ? 1 : options.distance;
    kernel.reach = std::max(1, options.distance);
    for (int d = 0; d < kDirectionCount; ++d) {
        DirectionSetup& s = kernel.dir[d];
        s.di = kDirectionSteps[size_t(d)][0];
        s.dj = kDirectionSteps[size_t(d)][1];
        s.offset = int64_t(s.dj) * w + s.di;
        float wx = float(s.di) * g.spacingX, wz = float(s.dj) * g.spacingZ;
        s.length = std::sqrt(wx * wx + wz * wz);
        s.invLength = 1.0f / s.length;
        s.ux = wx * s.invLength;
        s.uz = wz * s.invLength;
        axisRange(s.di, w, back, forward, s.loI, s.hiI);
        axisRange(s.dj, h, back, forward, s.loJ, s.hiJ);
    }

    out.width = w;
    out.height = h;
    out.spacingX = g.spacingX;
    out.spacingZ = g.spacingZ;
    out.values.resize(size_t(field.sampleCount()) * kDirectionCount);
    float* data = out.values.data();
    const bool normalBased = options.method == CurvatureMethod::TwoNormal ||
                             options.method == CurvatureMethod::ThreeNormal;

    auto run = [&]<CurvatureMethod kMethod>() {
        detail::forRows(w, h, threads, [&](int j0, int j1) {
            if (!normalBased) {
                kernel.rows<kMethod>(j0, j1, data);
                return;
            }
            // The normal methods need the slope of the tangent plane at each
            // stencil vertex: keep the gradient (-nx/ny, -nz/ny), from which
            // any direction's slope is a dot product (normalising the normal
            // first would cancel out). Only the rows this chunk's stencils
            // reach (clamped centres included), in a per-thread buffer that
            // stays warm in cache and is reused by the next call.
            const int r = kernel.reach;
            const int lo = std::max(0, std::min(j0, h - 1 - r) - r);
            const int hi = std::min(h - 1, std::max(j1 - 1, r) + r);
            const size_t n = size_t(hi - lo + 1) * size_t(w);
            thread_local std::vector<float> gradient;
            if (gradient.size() < 2 * n) gradient.resize(2 * n);
            float* gx = gradient.data();
            float* gz = gx + n;
            detail::dispatchNormalMethod(options.normals, [&]<NormalMethod kNormals>() {
                detail::forNormalRows<kNormals>(
                    g, lo, hi + 1, [&](int j, const float* ox, const float* oy, const float* oz) {
                        float* __restrict rx = gx + size_t(j - lo) * size_t(w);
                        float* __restrict rz = gz + size_t(j - lo) * size_t(w);
                        for (int i = 0; i < w; ++i) {
                            float inv = 1.0f / oy[i];
                            rx[i] = -ox[i] * inv;
                            rz[i] = -oz[i] * inv;
                        }
                    });
            });
            Kernel local = kernel;
            local.gx = gx;
            local.gz = gz;
            local.gradBase = int64_t(lo) * w;
            local.rows<kMethod>(j0, j1, data);
        });
    };
    switch (options.method) {
        case CurvatureMethod::TwoNormal:
            run.template operator()<CurvatureMethod::TwoNormal>();
            break;
        case CurvatureMethod::ThreeNormal:
            run.template operator()<CurvatureMethod::ThreeNormal>();
            break;
        case CurvatureMethod::ThreeVertex:
            run.template operator()<CurvatureMethod::ThreeVertex>();
            break;
        case CurvatureMethod::EdgeAngle:
            run.template operator()<CurvatureMethod::EdgeAngle>();
            break;
    }
}

}  // namespace sierra::analysis
