#include <sierra/analysis/Lines.h>

#include <sierra/analysis/Hatch.h>
#include <sierra/core/Error.h>

#include <algorithm>
#include <cmath>

namespace sierra::analysis {

const char* linePolarityName(LinePolarity polarity) {
    switch (polarity) {
        case LinePolarity::Any:
            return "any";
        case LinePolarity::Ridges:
            return "ridges";
        case LinePolarity::Valleys:
            return "valleys";
    }
    return "?";
}

LinePolarity parseLinePolarity(const std::string& name) {
    if (name == "any") return LinePolarity::Any;
    if (name == "ridges") return LinePolarity::Ridges;
    if (name == "valleys") return LinePolarity::Valleys;
    throw Error(msg("unknown line polarity '", name, "' (expected any, ridges or valleys)"));
}

void validate(const LineOptions& o) {
    SIERRA_CHECK(std::isfinite(o.threshold) && o.threshold >= 0.0f,
                 "lines: threshold must be finite and >= 0, got ", o.threshold);
    SIERRA_CHECK(o.minVertices >= 2, "lines: minimum length must be at least 2 vertices, got ",
                 o.minVertices);
    SIERRA_CHECK(std::isfinite(o.step) && o.step > 0.0f && o.step <= 2.0f,
                 "lines: blended step must be in (0, 2] grid units, got ", o.step);
    SIERRA_CHECK(o.maxPoints >= 0, "lines: maximum points must be >= 0 (0 = automatic), got ",
                 o.maxPoints);
}

namespace {

// The curvature of direction d as this polarity counts it (NaN stays NaN).
inline float counted(float k, LinePolarity p) {
    switch (p) {
        case LinePolarity::Any:
            return std::fabs(k);
        case LinePolarity::Ridges:
            return k < 0.0f ? -k : (std::isnan(k) ? k : 0.0f);
        case LinePolarity::Valleys:
            return k > 0.0f ? k : (std::isnan(k) ? k : 0.0f);
    }
    return k;
}

// The perpendicular step of each direction: +x <-> +z, x+z <-> x-z.
constexpr int kPerpendicular[kDirectionCount] = {1, 0, 3, 2};

class DiscreteTracer {
  public:
    DiscreteTracer(const CurvatureField& c, const LineOptions& o) : c_(c), o_(o) {
        const size_t n = size_t(c.width) * size_t(c.height);
        strength_.resize(n);
        direction_.resize(n);
        owner_.assign(n, -1);
        tried_.assign(n, 0);
        for (size_t k = 0; k < n; ++k) {
            int best = -1;
            float bestValue = 0.0f;
            for (int d = 0; d < kDirectionCount; ++d) {
                float v = counted(c.values[k * kDirectionCount + size_t(d)], o.polarity);
                if (!std::isnan(v) && (best < 0 || v > bestValue)) {
                    best = d;
                    bestValue = v;
                }
            }
            strength_[k] = best < 0 ? NAN : bestValue;
            direction_[k] = int8_t(best);
        }
    }

    LineSet run() {
        LineSet out;
        int32_t id = 0;
        for (int j = 0; j < c_.height; ++j)
            for (int i = 0; i < c_.width; ++i) {
                size_t v = index(i, j);
                if (owner_[v] >= 0 || tried_[v] || !passes(v)) continue;
                owner_[v] = id;
                int pd = kPerpendicular[direction_[v]];
                int sx = kDirectionSteps[size_t(pd)][0], sz = kDirectionSteps[size_t(pd)][1];
                std::vector<size_t> forward = trace(i, j, sx, sz, id);
                std::vector<size_t> backward = trace(i, j, -sx, -sz, id);
                std::vector<size_t> path(backward.rbegin(), backward.rend());
                path.push_back(v);
                path.insert(path.end(), forward.begin(), forward.end());
                if (int(path.size()) < o_.minVertices) {
                    for (size_t k : path)
                        if (owner_[k] == id) {
                            owner_[k] = -1;
                            tried_[k] = 1;
                        }
                    continue;
                }
                for (size_t k : path)
                    out.vertices.push_back({float(k % size_t(c_.width)),
                                            float(k / size_t(c_.width)),
                                            std::min(1.0f, strength_[k])});
                out.offsets.push_back(uint32_t(out.vertices.size()));
                ++id;
            }
        return out;
    }

  private:
    size_t index(int i, int j) const { return size_t(j) * size_t(c_.width) + size_t(i); }
    bool inside(int i, int j) const { return i >= 0 && j >= 0 && i < c_.width && j < c_.height; }
    bool passes(size_t k) const { return strength_[k] >= o_.threshold; }  // false for NaN

    // Vertices after (i, j) going first by (si, sj); the last one may be a
    // vertex of another line (or of this one) where the path joins it.
    std::vector<size_t> trace(int i, int j, int si, int sj, int32_t id) {
        std::vector<size_t> out;
        for (;;) {
            int ni = i + si, nj = j + sj;
            if (!inside(ni, nj)) break;
            size_t n = index(ni, nj);
            if (owner_[n] >= 0) {
                out.push_back(n);  // join: the segment (i, j) -> n is new, n's segments are not
                break;
            }
            if (!passes(n)) break;
            owner_[n] = id;
            out.push_back(n);
            i = ni;
            j = nj;
            int pd = kPerpendicular[direction_[n]];
            int pi = kDirectionSteps[size_t(pd)][0], pj = kDirectionSteps[size_t(pd)][1];
            int dot = pi * si + pj * sj;
            if (dot < 0 || (dot == 0 && betterSide(i, j, -pi, -pj, pi, pj))) {
                pi = -pi;
                pj = -pj;
            }
            si = pi;
            sj = pj;
        }
        return out;
    }

    // On a right-angle turn: does the step (ai, aj) reach a stronger vertex than (bi, bj)?
    bool betterSide(int i, int j, int ai, int aj, int bi, int bj) const {
        auto value = [&](int di, int dj) {
            if (!inside(i + di, j + dj)) return -1.0f;
            float s = strength_[index(i + di, j + dj)];
            return std::isnan(s) ? -1.0f : s;
        };
        return value(ai, aj) > value(bi, bj);
    }

    const CurvatureField& c_;
    const LineOptions& o_;
    std::vector<float> strength_;
    std::vector<int8_t> direction_;
    std::vector<int32_t> owner_;
    std::vector<uint8_t> tried_;
};

class BlendedTracer {
  public:
    BlendedTracer(const CurvatureField& c, const LineOptions& o) : c_(c), o_(o) {
        const size_t n = size_t(c.width) * size_t(c.height);
        owner_.assign(n, -1);
        claims_.resize(n);
        tried_.assign(n, 0);
        maxPoints_ = o.maxPoints > 0 ? o.maxPoints : 4 * (c.width + c.height);
        // Points closer than this along one trace may round to the same vertex.
        recent_ = int(std::ceil(2.0f / o.step)) + 1;
    }

    LineSet run() {
        LineSet out;
        int32_t id = 0;
        for (int j = 0; j < c_.height; ++j)
            for (int i = 0; i < c_.width; ++i) {
                size_t v = size_t(j) * size_t(c_.width) + size_t(i);
                if (owner_[v] >= 0 || tried_[v]) continue;
                // Cheap test first: at a vertex the interpolated strength is its own.
                float strongest = 0.0f;
                for (int d = 0; d < kDirectionCount; ++d)
                    strongest =
                        std::max(strongest,
                                 counted(c_.values[v * kDirectionCount + size_t(d)], o_.polarity));
                if (!(strongest >= o_.threshold)) continue;
                Sample s0;
                if (!sample(float(i), float(j), s0) || !(s0.strength >= o_.threshold)) continue;
                LineVertex start{float(i), float(j), std::min(1.0f, s0.strength)};
                claim(v, id, 0, 0, start);
                std::vector<LineVertex> forward = trace(start, s0.px, s0.pz, id, 1);
                std::vector<LineVertex> backward = trace(start, -s0.px, -s0.pz, id, 2);
                std::vector<LineVertex> path(backward.rbegin(), backward.rend());
                path.push_back(start);
                path.insert(path.end(), forward.begin(), forward.end());
                if (int(path.size()) < o_.minVertices) {
                    for (size_t k : claimed_) {
                        owner_[k] = -1;
                        tried_[k] = 1;
                    }
                } else {
                    out.vertices.insert(out.vertices.end(), path.begin(), path.end());
                    out.offsets.push_back(uint32_t(out.vertices.size()));
                    ++id;
                }
                claimed_.clear();
            }
        return out;
    }

  private:
    struct Sample {
        float strength = 0.0f;
        float px = 0.0f,
              pz = 1.0f;  // unit step perpendicular to the axis of largest curvature, grid units
    };
    struct Claim {
        int trace = 0;   // 0: the start point, 1: forward, 2: backward
        int serial = 0;  // point number along that trace
        float x = 0.0f, z = 0.0f;
    };

    // Bilinear curvature at (x, z); false outside the grid or next to no data.
    bool sample(float x, float z, Sample& s) const {
        if (!(x >= 0.0f && z >= 0.0f && x <= float(c_.width - 1) && z <= float(c_.height - 1)))
            return false;
        int i0 = std::min(int(x), c_.width - 2), j0 = std::min(int(z), c_.height - 2);
        float fx = x - float(i0), fz = z - float(j0);
        float k[kDirectionCount];
        float strength = 0.0f;
        for (int d = 0; d < kDirectionCount; ++d) {
            auto at = [&](int i, int j) { return counted(c_.at(i, j, d), o_.polarity); };
            float v = (1 - fz) * ((1 - fx) * at(i0, j0) + fx * at(i0 + 1, j0)) +
                      fz * ((1 - fx) * at(i0, j0 + 1) + fx * at(i0 + 1, j0 + 1));
            if (std::isnan(v)) return false;
            k[d] = v;
            strength = std::max(strength, v);
        }
        float wx = 1.0f, wz = 0.0f;
        if (!blendedCurvatureAxis(k, c_.spacingX, c_.spacingZ, wx, wz)) return false;
        // The perpendicular in world space, then in grid units.
        float px = -wz / c_.spacingX, pz = wx / c_.spacingZ;
        float len = std::hypot(px, pz);
        s.strength = strength;
        s.px = px / len;
        s.pz = pz / len;
        return true;
    }

    void claim(size_t v, int32_t id, int trace, int serial, const LineVertex& p) {
        owner_[v] = id;
        claims_[v] = {trace, serial, p.x, p.z};
        claimed_.push_back(v);
    }

    std::vector<LineVertex> trace(LineVertex from, float tx, float tz, int32_t id, int traceNo) {
        std::vector<LineVertex> out;
        float x = from.x, z = from.z;
        for (int serial = 1; serial <= maxPoints_; ++serial) {
            float nx = x + o_.step * tx, nz = z + o_.step * tz;
            Sample s;
            if (!sample(nx, nz, s) || !(s.strength >= o_.threshold)) break;
            size_t v = size_t(std::lround(nz)) * size_t(c_.width) + size_t(std::lround(nx));
            if (owner_[v] >= 0) {
                const Claim& c = claims_[v];
                bool nearby =
                    owner_[v] == id && ((c.trace == traceNo && serial - c.serial <= recent_) ||
                                        (c.trace == 0 && serial <= recent_));
                if (!nearby) {
                    // Another line, or this one coming back: end on its point.
                    Sample j;
                    float alpha = sample(c.x, c.z, j) ? std::min(1.0f, j.strength) : 0.0f;
                    out.push_back({c.x, c.z, alpha});
                    break;
                }
            }
            out.push_back({nx, nz, std::min(1.0f, s.strength)});
            if (owner_[v] < 0) claim(v, id, traceNo, serial, out.back());
            // Keep heading the same way: the axis has no sign.
            float px = s.px, pz = s.pz;
            if (px * tx + pz * tz < 0.0f) {
                px = -px;
                pz = -pz;
            }
            x = nx;
            z = nz;
            tx = px;
            tz = pz;
        }
        return out;
    }

    const CurvatureField& c_;
    const LineOptions& o_;
    int maxPoints_ = 0;
    int recent_ = 3;
    std::vector<int32_t> owner_;
    std::vector<Claim> claims_;
    std::vector<uint8_t> tried_;
    std::vector<size_t> claimed_;
};

}  // namespace

LineSet traceLines(const CurvatureField& curvature, const LineOptions& options) {
    validate(options);
    SIERRA_CHECK(curvature.width >= 2 && curvature.height >= 2 &&
                     curvature.values.size() ==
                         size_t(curvature.width) * size_t(curvature.height) * kDirectionCount,
                 "lines: the curvature field is empty or its values do not match its ",
                 curvature.width, "x", curvature.height, " size");
    if (options.blended) return BlendedTracer(curvature, options).run();
    return DiscreteTracer(curvature, options).run();
}

}  // namespace sierra::analysis
