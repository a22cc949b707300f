#include <sierra/analysis/Curvature.h>

#include "Internal.h"

#include <sierra/core/Error.h>

#include <algorithm>
#include <cmath>

namespace sierra::analysis {

const char* curvatureMethodName(CurvatureMethod method) {
    switch (method) {
        case CurvatureMethod::TwoNormal: return "two-normal";
        case CurvatureMethod::ThreeNormal: return "three-normal";
        case CurvatureMethod::ThreeVertex: return "three-vertex";
        case CurvatureMethod::EdgeAngle: return "edge-angle";
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
    SIERRA_CHECK(o.distance >= 1, "curvature: reinforcement distance must be an integer >= 1 (1 = none), got ",
                 o.distance);
    SIERRA_CHECK(o.method != CurvatureMethod::TwoNormal || o.distance == 1,
                 "curvature: two-normal has no reinforcement (distance must be 1, got ", o.distance,
                 "); use three-normal for a reinforcement distance");
    SIERRA_CHECK(std::isfinite(o.scale) && o.scale >= 0.0f, "curvature: scale must be finite and >= 0, got ",
                 o.scale);
    if (o.levels.enabled) {
        SIERRA_CHECK(std::isfinite(o.levels.black) && o.levels.black >= 0.0f,
                     "curvature: levels black point must be finite and >= 0, got ", o.levels.black);
        SIERRA_CHECK(std::isfinite(o.levels.white) && o.levels.white > o.levels.black,
                     "curvature: levels white point must be finite and above the black point (", o.levels.black,
                     "), got ", o.levels.white);
        SIERRA_CHECK(std::isfinite(o.levels.gamma) && o.levels.gamma > 0.0f,
                     "curvature: levels gamma must be finite and > 0, got ", o.levels.gamma);
    }
    if (o.output == CurvatureOutput::SecondDerivative) {
        SIERRA_CHECK(o.method != CurvatureMethod::EdgeAngle,
                     "curvature: edge-angle has no second derivative (it does not use Equation 1)");
        SIERRA_CHECK(o.distance == 1, "curvature: the second-derivative output takes no reinforcement (distance ",
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

struct Kernel {
    const detail::WorldGrid* g = nullptr;
    const float* gx = nullptr;  // surface gradient dy/dx per vertex (normal methods)
    const float* gz = nullptr;  // dy/dz
    CurvatureOptions opt;
    DirectionSetup dir[kDirectionCount];

    // Slope of the tangent plane at index k along direction d.
    float slope(int64_t k, const DirectionSetup& d) const { return gx[k] * d.ux + gz[k] * d.uz; }

    static float equation1(float ypp, float yp) {
        float t = 1.0f + yp * yp;
        return std::fabs(ypp) / (t * std::sqrt(t));
    }

    // Near (m = 1) or reinforcement (m = distance) measure at centre index k;
    // ypp receives the signed second derivative (or a value of its sign).
    template <CurvatureMethod kMethod>
    float measure(int64_t k, const DirectionSetup& d, int m, float& ypp) const {
        const int64_t s = d.offset * m;
        const float invStep = d.invLength / float(m);
        if constexpr (kMethod == CurvatureMethod::TwoNormal) {
            float sv = slope(k, d), sn = slope(k + s, d);
            ypp = (sn - sv) * invStep;
            return equation1(ypp, sv);
        } else if constexpr (kMethod == CurvatureMethod::ThreeNormal) {
            float sp = slope(k - s, d), sv = slope(k, d), sn = slope(k + s, d);
            ypp = 0.5f * (sn - sp) * invStep;  // the mean of the two pairs' y''
            float t = 1.0f + sv * sv;
            return 0.5f * (std::fabs(sv - sp) + std::fabs(sn - sv)) * invStep / (t * std::sqrt(t));
        } else if constexpr (kMethod == CurvatureMethod::ThreeVertex) {
            const float* y = g->y.data();
            float s1 = (y[k] - y[k - s]) * invStep, s2 = (y[k + s] - y[k]) * invStep;
            ypp = (s2 - s1) * invStep;
            return equation1(ypp, 0.5f * (s1 + s2));
        } else {
            const float* y = g->y.data();
            float hx = float(d.di * m) * g->spacingX, hz = float(d.dj * m) * g->spacingZ;
            float a = y[k - s] - y[k], b = y[k + s] - y[k];
            // e1 = (-hx, a, -hz), e2 = (hx, b, hz)
            float dot = -hx * hx + a * b - hz * hz;
            float cosTheta = dot / std::sqrt((hx * hx + hz * hz + a * a) * (hx * hx + hz * hz + b * b));
            ypp = a + b;  // sign of y''
            return std::clamp(1.0f + cosTheta, 0.0f, 1.0f);
        }
    }

    template <CurvatureMethod kMethod>
    void rows(int j0, int j1, float* out) const {
        const int w = g->width;
        const bool levels = opt.levels.enabled;
        const float black = opt.levels.black, invRange = 1.0f / (opt.levels.white - opt.levels.black);
        const float invGamma = 1.0f / opt.levels.gamma;
        const bool rawSecond = opt.output == CurvatureOutput::SecondDerivative;
        for (int j = j0; j < j1; ++j) {
            for (int i = 0; i < w; ++i) {
                const int64_t v = int64_t(j) * w + i;
                float* o = out + v * kDirectionCount;
                if (std::isnan(g->y[size_t(v)])) {
                    for (int d = 0; d < kDirectionCount; ++d) o[d] = NAN;
                    continue;
                }
                for (int d = 0; d < kDirectionCount; ++d) {
                    const DirectionSetup& ds = dir[d];
                    const int ci = std::clamp(i, ds.loI, ds.hiI), cj = std::clamp(j, ds.loJ, ds.hiJ);
                    const int64_t c = int64_t(cj) * w + ci;
                    float ypp = 0.0f;
                    float value = measure<kMethod>(c, ds, 1, ypp);
                    if (rawSecond) {
                        o[d] = ypp;
                        continue;
                    }
                    if (opt.distance > 1) {
                        float farYpp;
                        value *= measure<kMethod>(c, ds, opt.distance, farYpp);
                    }
                    value *= opt.scale;
                    if (levels) value = std::pow(std::clamp((value - black) * invRange, 0.0f, 1.0f), invGamma);
                    if (opt.signedValues && ypp < 0.0f) value = -value;
                    o[d] = value;
                }
            }
        }
    }
};

}  // namespace

CurvatureField computeCurvature(const terrain::Heightfield& field, const CurvatureOptions& options) {
    validate(options);
    SIERRA_CHECK(!field.empty(), "curvature: the heightfield is empty");
    const int minSide = 2 * options.distance + 1;
    SIERRA_CHECK(field.width() >= std::max(3, minSide) && field.height() >= std::max(3, minSide),
                 "curvature: a ", field.width(), "x", field.height(), " grid is too small for reinforcement distance ",
                 options.distance, " (each side needs at least ", std::max(3, minSide), " samples)");

    const int threads = options.threads;
    detail::WorldGrid g = detail::makeWorldGrid(field, threads);
    const int w = g.width, h = g.height;

    Kernel kernel;
    kernel.g = &g;
    kernel.opt = options;
    const int back = options.method == CurvatureMethod::TwoNormal ? 0 : options.distance;
    const int forward = options.method == CurvatureMethod::TwoNormal ? 1 : options.distance;
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

    // The normal methods need the slope of each vertex's tangent plane: keep
    // the gradient (-nx/ny, -nz/ny), from which any direction's slope is a dot
    // product. Normalising the normal first would cancel out.
    std::vector<float> gx, gz;
    const bool normalBased =
        options.method == CurvatureMethod::TwoNormal || options.method == CurvatureMethod::ThreeNormal;
    if (normalBased) {
        gx.resize(g.y.size());
        gz.resize(g.y.size());
        detail::dispatchNormalMethod(options.normals, [&]<NormalMethod kNormals>() {
            detail::forRows(w, h, threads, [&](int j0, int j1) {
                detail::forNormalSums<kNormals>(g, j0, j1, [&](int i, int j, detail::V3 s) {
                    size_t k = size_t(j) * size_t(w) + size_t(i);
                    float inv = 1.0f / s.y;
                    gx[k] = -s.x * inv;
                    gz[k] = -s.z * inv;
                });
            });
        });
        kernel.gx = gx.data();
        kernel.gz = gz.data();
    }

    CurvatureField out;
    out.width = w;
    out.height = h;
    out.spacingX = g.spacingX;
    out.spacingZ = g.spacingZ;
    out.values.resize(g.y.size() * kDirectionCount);
    float* data = out.values.data();
    auto run = [&]<CurvatureMethod kMethod>() {
        detail::forRows(w, h, threads, [&](int j0, int j1) { kernel.rows<kMethod>(j0, j1, data); });
    };
    switch (options.method) {
        case CurvatureMethod::TwoNormal: run.template operator()<CurvatureMethod::TwoNormal>(); break;
        case CurvatureMethod::ThreeNormal: run.template operator()<CurvatureMethod::ThreeNormal>(); break;
        case CurvatureMethod::ThreeVertex: run.template operator()<CurvatureMethod::ThreeVertex>(); break;
        case CurvatureMethod::EdgeAngle: run.template operator()<CurvatureMethod::EdgeAngle>(); break;
    }
    return out;
}

}  // namespace sierra::analysis
