// Relief fields: exact on the shapes that have a closed form (a plane, a step,
// a V-trench, a conical pit), the sweep equal to a brute-force walk along the
// same digital lines (docs/relief.md), no data neither casting nor receiving,
// the same bytes on any thread count, and one clear error for bad input.
#include <sierra/analysis/Relief.h>
#include <sierra/core/Error.h>

#include "analysis_test_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

using namespace sierra;
using namespace sierra::analysis;
using sierra::analysis::test::sampleSurface;

namespace {

constexpr double kPi = 3.14159265358979323846;

double deg(double radians) {
    return radians * 180.0 / kPi;
}

// The digital line of an azimuth, written out again from docs/relief.md.
struct RefLine {
    double ux, uz;
    bool iMajor;
    int look;
    double slope;
    bool diagonal;
    int r(int m) const { return int(std::floor(slope * m + 0.5)); }
};

RefLine refLine(double degrees, double sx, double sz) {
    const double a = std::fmod(degrees, 360.0) * kPi / 180.0;
    double sa = std::sin(a), ca = std::cos(a);
    if (std::fabs(sa) < 1e-12) sa = 0.0;
    if (std::fabs(ca) < 1e-12) ca = 0.0;
    RefLine l{};
    l.ux = sa;
    l.uz = -ca;
    const double gi = sa / sx, gj = -ca / sz;
    l.iMajor = std::fabs(gi) >= std::fabs(gj);
    const double major = l.iMajor ? gi : gj, minor = l.iMajor ? gj : gi;
    l.look = major > 0.0 ? 1 : -1;
    l.slope = minor / major;
    if (std::fabs(std::fabs(l.slope) - 1.0) < 1e-12) l.slope = l.slope > 0.0 ? 1.0 : -1.0;
    l.diagonal = std::fabs(l.slope) == 1.0;
    return l;
}

// Horizon angle of every sample by walking its digital line outwards (O(N L)):
// the occluder is the point of largest projected slope (the farthest of equal
// ones), its angle taken with its true horizontal distance. NaN at no data and
// in the padding; -pi/2 where nothing casts.
std::vector<double> bruteHorizon(const terrain::Heightfield& f, double degrees, double radius,
                                 int vw = 0, int vh = 0, bool inverted = false) {
    const int W = f.width(), H = f.height();
    vw = vw ? vw : W;
    vh = vh ? vh : H;
    const double sx = f.spacingX(), sz = f.spacingZ();
    const double scale = (inverted ? -1.0 : 1.0) * f.verticalScale();
    const RefLine l = refLine(degrees, sx, sz);
    const int M = l.iMajor ? vw : vh, N = l.iMajor ? vh : vw;
    auto h = [&](int i, int j) { return double(float(f.at(i, j) * float(scale))); };
    auto t = [&](double i, double j) { return i * sx * l.ux + j * sz * l.uz; };
    auto w = [&](double i, double j) { return -i * sx * l.uz + j * sz * l.ux; };
    std::vector<double> out(size_t(W) * H, NAN);
    for (int j = 0; j < vh; ++j)
        for (int i = 0; i < vw; ++i) {
            if (!f.valid(i, j)) continue;
            const int mp = l.iMajor ? i : j, np = l.iMajor ? j : i;
            const int o = np - l.r(mp);
            const double hp = h(i, j), tp = t(i, j), wp = w(i, j);
            double best = -INFINITY, bestDh = 0, bestDist = 0;
            bool any = false;
            auto consider = [&](double hq, double tq, double wq) {
                const double dt = tq - tp;
                if (radius > 0 && dt > radius) return;
                const double s = (hq - hp) / dt;
                if (!any || s >= best) {
                    any = true;
                    best = s;
                    bestDh = hq - hp;
                    bestDist = std::sqrt(dt * dt + (wq - wp) * (wq - wp));
                }
            };
            int pi = i, pj = j;
            for (int m = mp + l.look; m >= 0 && m < M; m += l.look) {
                const int n = o + l.r(m);
                if (n < 0 || n >= N) break;
                const int qi = l.iMajor ? m : n, qj = l.iMajor ? n : m;
                if (l.diagonal) {
                    const int ci = std::min(qi, pi), cj = std::min(qj, pj);
                    const bool even = (ci + cj) % 2 == 0;
                    const int ai = even ? ci : ci + 1, bi = even ? ci + 1 : ci;
                    if (f.valid(ai, cj) && f.valid(bi, cj + 1))
                        consider(double(0.5f * (float(h(ai, cj)) + float(h(bi, cj + 1)))),
                                 t(ci + 0.5, cj + 0.5), w(ci + 0.5, cj + 0.5));
                }
                if (f.valid(qi, qj)) consider(h(qi, qj), t(qi, qj), w(qi, qj));
                pi = qi;
                pj = qj;
            }
            out[size_t(j) * W + i] = any ? std::atan(bestDh / bestDist) : -kPi / 2;
        }
    return out;
}

terrain::Heightfield randomField(int w, int h, float sx, float sz, uint32_t seed) {
    terrain::Heightfield f(w, h);
    f.setSpacing(sx, sz);
    f.setVerticalScale(1.7f);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 6.0f);
    for (float& v : f.samples()) v = u(rng);
    return f;
}

double segmentFraction(double horizon, double altitude, double radius) {
    const double y = (horizon - altitude) / radius;
    if (y <= -1) return 1;
    if (y >= 1) return 0;
    return (std::acos(y) - y * std::sqrt(1 - y * y)) / kPi;
}

}  // namespace

TEST(AnalysisRelief, FlatPlaneIsOpenSky) {
    auto f = sampleSurface(33, 29, 2.0, 3.0, [](double, double) { return 5.0; });
    HorizonOptions o;
    auto hz = computeHorizons(f, o);
    ASSERT_EQ(hz.directions, 16);
    for (int d = 0; d < 16; ++d) {
        EXPECT_EQ(hz.at(d, 16, 14), 0.0f) << d;
        // Looking out of the grid nothing casts.
        EXPECT_EQ(hz.at(4, 32, 14), float(-kPi / 2));  // east at the east edge
        EXPECT_EQ(hz.at(0, 16, 0), float(-kPi / 2));   // north at row 0
        EXPECT_EQ(hz.at(8, 16, 28), float(-kPi / 2));  // south at the last row
    }
    auto svf = skyViewFactor(hz);
    auto sky = skyLight(f, hz);
    auto sun = sunVisibility(f, {.azimuth = 200.0f, .altitude = 20.0f});
    auto pos = opennessPositive(f, o);
    auto neg = opennessNegative(f, o);
    for (size_t k = 0; k < svf.size(); ++k) {
        ASSERT_FLOAT_EQ(svf[k], 1.0f) << k;
        ASSERT_FLOAT_EQ(sky[k], 1.0f) << k;
        ASSERT_FLOAT_EQ(sun[k], 1.0f) << k;
        ASSERT_NEAR(pos[k], 90.0f, 1e-4) << k;
        ASSERT_NEAR(neg[k], 90.0f, 1e-4) << k;
    }
}

TEST(AnalysisRelief, SunOnTheHorizonIsHalfADisc) {
    // A flat plane's horizon is at elevation 0 inside the grid: a sun centred on
    // it shows half its disc; at the edge facing the sun nothing casts. A sun
    // whose whole disc is below the horizontal gives 0 everywhere.
    auto f = sampleSurface(20, 20, 1.0, 1.0, [](double, double) { return 0.0; });
    auto v = sunVisibility(f, {.azimuth = 90.0f, .altitude = 0.0f});
    EXPECT_NEAR(v[5 * 20 + 10], 0.5f, 1e-6);
    EXPECT_FLOAT_EQ(v[5 * 20 + 19], 1.0f);
    // A quarter of the diameter above the horizon: the segment formula.
    auto q = sunVisibility(f, {.azimuth = 90.0f, .altitude = 0.25f, .diameter = 1.0f});
    EXPECT_NEAR(q[5 * 20 + 10], segmentFraction(0, 0.25 * kPi / 180, 0.5 * kPi / 180), 1e-5);
    auto night = sunVisibility(f, {.azimuth = 90.0f, .altitude = -0.3f, .diameter = 0.53f});
    for (float x : night) ASSERT_EQ(x, 0.0f);
}

TEST(AnalysisRelief, TiltedPlaneSeesItsWholeHemisphere) {
    // A plane rising at 20 degrees to the east: uphill the horizon is the
    // plane itself, which is its tangent plane, so the sky light integrates the
    // hemisphere around the normal (1 up to the 16-azimuth quadrature), while
    // the sky-view factor loses the sky under the uphill horizon.
    const double slope = std::tan(20.0 * kPi / 180);
    auto f = sampleSurface(41, 41, 1.0, 1.0, [&](double x, double) { return slope * x; });
    auto hz = computeHorizons(f, {});
    EXPECT_NEAR(hz.at(4, 20, 20), 20.0 * kPi / 180, 1e-6);    // east, uphill
    EXPECT_NEAR(hz.at(12, 20, 20), -20.0 * kPi / 180, 1e-6);  // west, downhill
    const float sky = skyLight(f, hz)[20 * 41 + 20];
    EXPECT_GT(sky, 0.98f);
    EXPECT_LE(sky, 1.0f);
    double sum = 0;
    for (int d = 0; d < 16; ++d) sum += std::sin(std::max(double(hz.at(d, 20, 20)), 0.0));
    EXPECT_NEAR(skyViewFactor(hz)[20 * 41 + 20], 1 - sum / 16, 1e-6);
    EXPECT_LT(skyViewFactor(hz)[20 * 41 + 20], 0.9f);
}

TEST(AnalysisRelief, StepCastsShadowAndPenumbraOfTheDiscsSize) {
    // A plateau of world height h for columns < 20, a plain at 0 beyond, the sun
    // in the west: the plateau's edge (column 19) shades the plain out to
    // h / tan(altitude), and the penumbra spans h / tan(alt - d/2) - h / tan(alt + d/2).
    const double s = 0.5, h = 40.0;
    const int edge = 19;
    auto f = sampleSurface(240, 3, s, 2.0, [&](double x, double) { return x < 19.5 * s ? h : 0; });
    for (double alt : {30.0, 45.0}) {
        for (double diameter : {0.53, 5.0}) {
            auto v = sunVisibility(
                f, {.azimuth = 270.0f, .altitude = float(alt), .diameter = float(diameter)});
            const double a = alt * kPi / 180, r = diameter * kPi / 360;
            int lastShadow = -1, penumbra = 0;
            for (int i = edge + 1; i < 240; ++i) {
                const float x = v[size_t(1) * 240 + i];
                if (x < 0.5f) lastShadow = i;
                if (x > 0.0f && x < 1.0f) ++penumbra;
                // The plateau is in the sun.
                ASSERT_FLOAT_EQ(v[size_t(1) * 240 + (i - edge - 1) % edge], 1.0f);
            }
            ASSERT_GT(lastShadow, edge);
            const double length = h / std::tan(a);
            const double measured = (lastShadow - edge) * s;  // the last shaded distance
            EXPECT_LE(measured, length) << alt << " " << diameter;
            EXPECT_GE(measured, length - s - 1e-9) << alt << " " << diameter;
            const double width = h / std::tan(a - r) - h / std::tan(a + r);
            EXPECT_NEAR(penumbra * s, width, s) << alt << " " << diameter;
        }
    }
}

TEST(AnalysisRelief, VTrenchSkyViewFactorFromItsWalls) {
    // A trench along z with walls of angle beta up to |x| = 15, flat beyond: from
    // its floor the horizon towards bearing phi is atan(tan(beta) |sin(phi)|).
    // The 8 grid-aligned azimuths are exact; 16 azimuths add 8 digital lines,
    // whose occluders lie off the ray by less than a sample.
    const double beta = 25.0 * kPi / 180;
    auto f = sampleSurface(41, 101, 1.0, 1.0, [&](double x, double) {
        return std::min(std::fabs(x - 20.0), 15.0) * std::tan(beta);
    });
    for (int D : {8, 16}) {
        auto hz = computeHorizons(f, {.directions = D});
        double sum = 0;
        for (int d = 0; d < D; ++d) {
            const double phi = 2 * kPi * d / D;
            const double g = std::atan(std::tan(beta) * std::fabs(std::sin(phi)));
            sum += std::sin(std::max(g, 0.0));
            if (D == 8) {
                EXPECT_NEAR(hz.at(d, 20, 50), g, 1e-6) << d;
            }
        }
        const double expected = 1 - sum / D;
        auto svf = skyViewFactor(hz);
        // 16 azimuths: the first step of the 22.5-degree digital line from the
        // floor goes to a neighbour at bearing 45 degrees, one column up the
        // wall, which raises that horizon by up to 8 degrees (docs/relief.md).
        EXPECT_NEAR(svf[50 * 41 + 20], expected, D == 8 ? 1e-6 : 0.03) << D;
        if (D == 16) {
            EXPECT_LT(svf[50 * 41 + 20], expected);
        }
    }
}

TEST(AnalysisRelief, ConicalPitHorizonIsItsWallAngle) {
    // y = r tan(beta) around (20, 20), a vertex whose 4-8 cells all take the
    // diagonal through it: every profile from the centre rises at beta (the
    // occluder's angle is taken at its true distance), so the horizon is beta
    // in every azimuth, SVF = 1 - sin(beta) and, the normal being vertical,
    // the sky light cos^2(beta).
    const double beta = 30.0 * kPi / 180;
    struct Case {
        float sx, sz, first;
    };
    // Square spacing (the diagonals are azimuths), then spacings where no
    // azimuth is a grid diagonal.
    for (Case c : {Case{1.0f, 1.0f, 0.0f}, Case{1.5f, 0.5f, 10.0f}}) {
        terrain::Heightfield f(41, 41);
        f.setSpacing(c.sx, c.sz);
        f.setVerticalScale(0.5f);
        for (int j = 0; j < 41; ++j)
            for (int i = 0; i < 41; ++i)
                f.at(i, j) =
                    float(std::hypot(c.sx * (i - 20), c.sz * (j - 20)) * std::tan(beta) / 0.5);
        const float first = c.first;
        auto hz = computeHorizons(f, {.directions = 16, .firstAzimuth = first});
        for (int d = 0; d < 16; ++d) EXPECT_NEAR(hz.at(d, 20, 20), beta, 1e-5) << d;
        EXPECT_NEAR(skyViewFactor(hz)[20 * 41 + 20], 1 - std::sin(beta), 1e-5);
        EXPECT_NEAR(skyLight(f, hz)[20 * 41 + 20], std::cos(beta) * std::cos(beta), 1e-5);
    }
}

TEST(AnalysisRelief, SweepMatchesBruteForceOnTheSameDigitalLines) {
    struct Case {
        int w, h;
        float sx, sz;
        float first, radius;
        bool mask;
    };
    const Case cases[] = {
        {37, 23, 1.0f, 1.0f, 0.0f, 0.0f, false},  {37, 23, 1.0f, 1.0f, 0.0f, 5.3f, false},
        {29, 41, 1.3f, 0.8f, 7.5f, 0.0f, true},   {29, 41, 1.3f, 0.8f, 7.5f, 6.1f, true},
        {50, 17, 0.7f, 2.1f, 33.0f, 11.7f, true}, {1, 9, 1.0f, 1.0f, 0.0f, 0.0f, false},
        {12, 12, 2.0f, 2.0f, 0.0f, 1.5f, false},
    };
    uint32_t seed = 1;
    for (const Case& c : cases) {
        auto f = randomField(c.w, c.h, c.sx, c.sz, seed++);
        if (c.mask) {
            std::vector<uint8_t> m(size_t(c.w) * c.h, 1);
            std::mt19937 rng(seed);
            for (auto& b : m) b = rng() % 7 != 0;
            f.setMask(m);
        }
        HorizonOptions o{.directions = 16, .firstAzimuth = c.first, .radius = c.radius};
        auto hz = computeHorizons(f, o);
        std::vector<float> posSum(size_t(c.w) * c.h, 0.0f);
        for (int d = 0; d < 16; ++d) {
            auto ref = bruteHorizon(f, hz.azimuthDegrees(d), c.radius);
            for (int j = 0; j < c.h; ++j)
                for (int i = 0; i < c.w; ++i) {
                    const double r = ref[size_t(j) * c.w + i];
                    const float a = hz.at(d, i, j);
                    if (std::isnan(r)) {
                        ASSERT_TRUE(std::isnan(a)) << i << "," << j << " d" << d;
                    } else {
                        ASSERT_NEAR(a, r, 1e-6) << i << "," << j << " d" << d << " w" << c.w;
                    }
                }
        }
        // The sun in one azimuth and openness follow the same horizons.
        SunDisc sun{.azimuth = 123.0f, .altitude = 12.0f, .diameter = 4.0f};
        auto v = sunVisibility(f, sun, o);
        auto ref = bruteHorizon(f, 123.0, c.radius);
        for (size_t k = 0; k < v.size(); ++k) {
            if (std::isnan(ref[k])) {
                ASSERT_TRUE(std::isnan(v[k]));
                continue;
            }
            ASSERT_NEAR(v[k], segmentFraction(ref[k], 12.0 * kPi / 180, 2.0 * kPi / 180), 2e-5);
        }
        for (bool inverted : {false, true}) {
            auto open = inverted ? opennessNegative(f, o) : opennessPositive(f, o);
            std::vector<double> sum(v.size(), 0.0), count(v.size(), 0.0);
            for (int d = 0; d < 16; ++d) {
                auto r = bruteHorizon(f, hz.azimuthDegrees(d), c.radius, 0, 0, inverted);
                for (size_t k = 0; k < r.size(); ++k)
                    if (!(r[k] == -kPi / 2)) {
                        sum[k] += 90 - deg(r[k]);
                        count[k] += 1;
                    }
            }
            for (size_t k = 0; k < v.size(); ++k) {
                if (std::isnan(sum[k]) || count[k] == 0) {
                    ASSERT_TRUE(std::isnan(open[k])) << k;
                } else {
                    ASSERT_NEAR(open[k], sum[k] / count[k], 1e-4) << k;
                }
            }
        }
    }
}

TEST(AnalysisRelief, NoDataNeitherCastsNorReceives) {
    // Holes filled with a tower or a pit give the same bytes: they never cast.
    // Their own values are NaN in every field. The padding behaves the same.
    auto f = randomField(40, 30, 1.0f, 1.2f, 7);
    std::vector<uint8_t> m(40 * 30, 1);
    for (int j = 10; j < 15; ++j)
        for (int i = 12; i < 20; ++i) m[size_t(j) * 40 + i] = 0;
    m[3 * 40 + 33] = 0;
    f.setMask(m);
    auto g = f;
    for (size_t k = 0; k < m.size(); ++k)
        if (!m[k]) {
            f.samples()[k] = 1e4f;
            g.samples()[k] = -1e4f;
        }
    // Padding: the last 4 columns and 3 rows, filled differently in the two.
    HorizonOptions o{.validWidth = 36, .validHeight = 27};
    for (int j = 0; j < 30; ++j)
        for (int i = 0; i < 40; ++i)
            if (i >= 36 || j >= 27) {
                f.at(i, j) = 500.0f;
                g.at(i, j) = -500.0f;
            }
    auto hf = computeHorizons(f, o), hg = computeHorizons(g, o);
    ASSERT_EQ(0, std::memcmp(hf.angle.data(), hg.angle.data(), hf.angle.size() * sizeof(float)));
    SunDisc sun{.azimuth = 80.0f, .altitude = 8.0f};
    auto sf = sunVisibility(f, sun, o), sg = sunVisibility(g, sun, o);
    auto pf = opennessPositive(f, o), pg = opennessPositive(g, o);
    auto nf = opennessNegative(f, o), ng = opennessNegative(g, o);
    auto svf = skyViewFactor(hf);
    auto sky = skyLight(f, hf);
    for (int j = 0; j < 30; ++j)
        for (int i = 0; i < 40; ++i) {
            const size_t k = size_t(j) * 40 + i;
            const bool out = !m[k] || i >= 36 || j >= 27;
            if (!std::isnan(sf[k]) || !std::isnan(sg[k])) {
                ASSERT_EQ(sf[k], sg[k]) << k;
            }
            if (!std::isnan(pf[k]) || !std::isnan(pg[k])) {
                ASSERT_EQ(pf[k], pg[k]) << k;
            }
            if (!std::isnan(nf[k]) || !std::isnan(ng[k])) {
                ASSERT_EQ(nf[k], ng[k]) << k;
            }
            ASSERT_EQ(out, std::isnan(sf[k])) << i << "," << j;
            ASSERT_EQ(out, std::isnan(pf[k])) << i << "," << j;
            ASSERT_EQ(out, std::isnan(nf[k])) << i << "," << j;
            ASSERT_EQ(out, std::isnan(svf[k])) << i << "," << j;
            for (int d = 0; d < 16; ++d) ASSERT_EQ(out, std::isnan(hf.at(d, i, j)));
            // Sky light also needs the normal, which reads the neighbours: NaN
            // wherever the horizons are.
            if (out) {
                ASSERT_TRUE(std::isnan(sky[k]));
            }
        }
    // And the holes match the brute force, which skips them.
    for (int d = 0; d < 16; d += 3) {
        auto ref = bruteHorizon(f, hf.azimuthDegrees(d), 0, 36, 27);
        for (int j = 0; j < 27; ++j)
            for (int i = 0; i < 36; ++i)
                if (m[size_t(j) * 40 + i]) {
                    ASSERT_NEAR(hf.at(d, i, j), ref[size_t(j) * 40 + i], 1e-6);
                }
    }
}

TEST(AnalysisRelief, ThreadCountDoesNotChangeTheBytes) {
    auto f = randomField(301, 257, 1.0f, 1.0f, 3);
    for (float radius : {0.0f, 20.5f}) {
        auto a = computeHorizons(f, {.radius = radius, .threads = 1});
        auto b = computeHorizons(f, {.radius = radius, .threads = 2});
        ASSERT_EQ(0, std::memcmp(a.angle.data(), b.angle.data(), a.angle.size() * sizeof(float)));
        SunDisc sun{.azimuth = 30.0f, .altitude = 10.0f};
        auto va = sunVisibility(f, sun, {.radius = radius, .threads = 1});
        auto vb = sunVisibility(f, sun, {.radius = radius, .threads = 2});
        ASSERT_EQ(0, std::memcmp(va.data(), vb.data(), va.size() * sizeof(float)));
        auto pa = opennessNegative(f, {.radius = radius, .threads = 1});
        auto pb = opennessNegative(f, {.radius = radius, .threads = 2});
        ASSERT_EQ(0, std::memcmp(pa.data(), pb.data(), pa.size() * sizeof(float)));
    }
}

TEST(AnalysisRelief, SkyFieldsFromTheSweepEqualThoseFromStoredHorizons) {
    // From one azimuth's angles at a time every sample adds the same terms in
    // the same order as from the stored horizons: the same bytes (NaN where
    // the other is NaN), with no data, padding, a radius, spacings that make
    // no azimuth a diagonal, and on one thread or two.
    auto f = randomField(131, 97, 1.3f, 0.8f, 11);
    std::vector<uint8_t> m(size_t(131) * 97, 1);
    std::mt19937 rng(5);
    for (auto& b : m) b = rng() % 9 != 0;
    f.setMask(m);
    auto same = [](const std::vector<float>& a, const std::vector<float>& b, const char* what) {
        ASSERT_EQ(a.size(), b.size()) << what;
        size_t nan = 0;
        for (size_t k = 0; k < a.size(); ++k) {
            if (std::isnan(a[k]) || std::isnan(b[k])) {
                ASSERT_TRUE(std::isnan(a[k]) && std::isnan(b[k])) << what << " " << k;
                ++nan;
                continue;
            }
            ASSERT_EQ(0, std::memcmp(&a[k], &b[k], sizeof(float))) << what << " " << k;
        }
        EXPECT_LT(nan, a.size() / 2) << what;  // most samples have a value
    };
    const HorizonOptions cases[] = {
        {},
        {.directions = 12, .firstAzimuth = 7.5f, .validWidth = 120, .validHeight = 90},
        {.directions = 16, .radius = 9.5f, .threads = 1},
        {.directions = 5, .firstAzimuth = 200.0f, .threads = 2},
    };
    for (const HorizonOptions& o : cases) {
        const Horizons hz = computeHorizons(f, o);
        same(skyViewFactor(f, o), skyViewFactor(hz), "sky-view factor");
        same(skyLight(f, o), skyLight(f, hz), "sky light");
    }
}

TEST(AnalysisRelief, BadParametersAreErrors) {
    auto f = randomField(8, 8, 1.0f, 1.0f, 1);
    auto expectError = [](auto&& call, const char* needle) {
        try {
            call();
            ADD_FAILURE() << "no error for " << needle;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
        }
    };
    expectError([&] { sunVisibility(f, {.diameter = 0.0f}); }, "diameter");
    expectError([&] { sunVisibility(f, {.diameter = -1.0f}); }, "diameter");
    expectError([&] { sunVisibility(f, {.diameter = NAN}); }, "diameter");
    expectError([&] { sunVisibility(f, {.diameter = INFINITY}); }, "diameter");
    expectError([&] { sunVisibility(f, {.azimuth = NAN}); }, "azimuth");
    expectError([&] { sunVisibility(f, {.altitude = NAN}); }, "altitude");
    expectError([&] { sunVisibility(f, {.altitude = 91.0f}); }, "altitude");
    expectError([&] { computeHorizons(f, {.directions = 0}); }, "directions");
    expectError([&] { computeHorizons(f, {.directions = -3}); }, "directions");
    expectError([&] { opennessPositive(f, {.directions = 0}); }, "directions");
    expectError([&] { computeHorizons(f, {.firstAzimuth = NAN}); }, "firstAzimuth");
    expectError([&] { computeHorizons(f, {.radius = -1.0f}); }, "radius");
    expectError([&] { computeHorizons(f, {.validWidth = 9}); }, "validWidth");
    expectError([&] { computeHorizons(terrain::Heightfield(), {}); }, "empty");
    expectError([&] { skyLight(f, HorizonOptions{.directions = 0}); }, "skyLight: directions");
    expectError([&] { skyViewFactor(f, HorizonOptions{.radius = NAN}); }, "skyViewFactor: radius");
    auto hz = computeHorizons(f, {});
    expectError([&] { skyLight(randomField(9, 8, 1.0f, 1.0f, 1), hz); }, "skyLight");
    Horizons broken = hz;
    broken.angle.pop_back();
    expectError([&] { skyViewFactor(broken); }, "skyViewFactor");
}
