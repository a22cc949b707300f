// Curvature on analytic surfaces: every method and direction, with the
// tolerances stated next to each check.
#include <sierra/analysis/Curvature.h>
#include <sierra/core/Error.h>
#include <sierra/terrain/DiamondSquare.h>

#include "analysis_test_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>

using namespace sierra;
using namespace sierra::analysis;
using sierra::analysis::test::sampleSurface;

namespace {

constexpr CurvatureMethod kAllMethods[] = {CurvatureMethod::TwoNormal, CurvatureMethod::ThreeNormal,
                                           CurvatureMethod::ThreeVertex,
                                           CurvatureMethod::EdgeAngle};
constexpr NormalMethod kAllNormals[] = {NormalMethod::Edge, NormalMethod::Triangle,
                                        NormalMethod::Quad};

CurvatureField curvature(const terrain::Heightfield& f, CurvatureMethod m,
                         NormalMethod n = NormalMethod::Quad,
                         CurvatureOutput out = CurvatureOutput::Curvature, int distance = 1) {
    return computeCurvature(f, {.method = m, .normals = n, .distance = distance, .output = out});
}

// Unit horizontal vector (x, z) and step length of direction d for spacing h.
void directionOf(int d, double h, double& ux, double& uz, double& length) {
    double wx = kDirectionSteps[size_t(d)][0] * h, wz = kDirectionSteps[size_t(d)][1] * h;
    length = std::hypot(wx, wz);
    ux = wx / length;
    uz = wz / length;
}

}  // namespace

TEST(AnalysisCurvature, PlaneIsZeroForEveryMethodNormalAndDirection) {
    // A tilted plane in world units (spacing 2, vertical scale 0.5), borders
    // included. Tolerance 1e-5: float rounding of heights up to ~30.
    auto plane =
        sampleSurface(33, 29, 2.0, 0.5, [](double x, double z) { return 0.3 * x - 0.2 * z + 5.0; });
    for (CurvatureMethod m : kAllMethods)
        for (NormalMethod n : kAllNormals) {
            auto c = curvature(plane, m, n);
            ASSERT_EQ(c.width, 33);
            ASSERT_EQ(c.height, 29);
            ASSERT_EQ(c.values.size(), size_t(33 * 29 * 4));
            for (int j = 0; j < c.height; ++j)
                for (int i = 0; i < c.width; ++i)
                    for (int d = 0; d < 4; ++d)
                        ASSERT_NEAR(c.at(i, j, d), 0.0f, 1e-5f)
                            << curvatureMethodName(m) << "/" << normalMethodName(n) << " at " << i
                            << "," << j << " dir " << d;
        }
}

TEST(AnalysisCurvature, QuadricThreeVertexSecondDerivativeIsExact) {
    // (a x^2 + b z^2)/2 + c x z, origin at the grid centre, spacing 2.
    // Three-vertex y'' is exact for a quadric: a along x, b along z, (a+b)/2
    // + c on x+z and (a+b)/2 - c on x-z. Tolerance 1e-5 (float rounding).
    const double a = 0.03, b = -0.02, c = 0.01, h = 2.0;
    auto f = sampleSurface(
        33, 33, h, 0.5, [&](double x, double z) { return (a * x * x + b * z * z) / 2 + c * x * z; },
        -32.0, -32.0);
    auto ypp = curvature(f, CurvatureMethod::ThreeVertex, NormalMethod::Quad,
                         CurvatureOutput::SecondDerivative);
    auto k = curvature(f, CurvatureMethod::ThreeVertex);
    const double expected[4] = {a, b, (a + b) / 2 + c, (a + b) / 2 - c};
    for (int j = 0; j < 33; ++j)
        for (int i = 0; i < 33; ++i)
            for (int d = 0; d < 4; ++d) {
                // Exact everywhere: the border repeats an inner value, and y'' is constant.
                ASSERT_NEAR(ypp.at(i, j, d), expected[d], 1e-5) << i << "," << j << " dir " << d;
                if (i == 0 || j == 0 || i == 32 || j == 32) continue;
                // Equation 1 with the exact slope (central differences are exact for a quadric).
                double x = i * h - 32.0, z = j * h - 32.0, ux, uz, len;
                directionOf(d, h, ux, uz, len);
                double slope = (a * x + c * z) * ux + (b * z + c * x) * uz;
                double kappa = std::fabs(expected[d]) / std::pow(1 + slope * slope, 1.5);
                ASSERT_NEAR(k.at(i, j, d), kappa, 1e-5 + 1e-4 * kappa)
                    << i << "," << j << " dir " << d;
            }
}

TEST(AnalysisCurvature, QuadricEdgeNormalsGiveExactNormalMethodSecondDerivatives) {
    // Edge normals are central differences, exact gradients on a quadric, so
    // the two- and three-normal y'' are exact too (tolerance 1e-5). Triangle
    // and quad normals average unit normals, so on this gentle quadric (slopes
    // below 1) their y'' is within 10% of the exact value.
    const double a = 0.03, b = -0.02, c = 0.01, h = 2.0;
    auto f = sampleSurface(
        33, 33, h, 0.5, [&](double x, double z) { return (a * x * x + b * z * z) / 2 + c * x * z; },
        -32.0, -32.0);
    const double expected[4] = {a, b, (a + b) / 2 + c, (a + b) / 2 - c};
    for (CurvatureMethod m : {CurvatureMethod::TwoNormal, CurvatureMethod::ThreeNormal})
        for (NormalMethod n : kAllNormals) {
            auto ypp = curvature(f, m, n, CurvatureOutput::SecondDerivative);
            double tol = n == NormalMethod::Edge ? 1e-5 : 0.1;
            for (int j = 2; j < 31; ++j)
                for (int i = 2; i < 31; ++i)
                    for (int d = 0; d < 4; ++d) {
                        double err = std::fabs(ypp.at(i, j, d) - expected[d]);
                        ASSERT_LE(err, n == NormalMethod::Edge
                                           ? tol
                                           : tol * std::fabs(expected[d]) + 1e-5)
                            << curvatureMethodName(m) << "/" << normalMethodName(n) << " at " << i
                            << "," << j << " dir " << d;
                    }
        }
}

TEST(AnalysisCurvature, CylinderHasCurvatureOneOverRadiusAcrossItsAxis) {
    // y = sqrt(R^2 - z^2), axis along x, R = 40, spacing 1, |z| <= 20.
    // Along x: 0 for every method (1e-5). Along z and the diagonals: the exact
    // curvature of the vertical section, |y''| / (1 + y'^2)^1.5 with y' =
    // f'(z) dz/dt, y'' = f''(z) (dz/dt)^2, dz/dt = 1 or 1/sqrt(2); 1/R along z.
    // Three-vertex is second-order (1%); three-normal averages slopes of
    // averaged normals (3%); two-normal is a one-sided difference (y'' at the
    // midpoint, y' at the vertex: 8%). Edge angle: 1 + cos of the angle between
    // the chords, from the exact heights (1e-4 relative).
    const double R = 40.0;
    auto f = sampleSurface(
        21, 41, 1.0, 1.0, [&](double, double z) { return std::sqrt(R * R - z * z); }, 0.0, -20.0);
    for (CurvatureMethod m : kAllMethods) {
        auto k = curvature(f, m);
        double tol = m == CurvatureMethod::ThreeVertex   ? 0.01
                     : m == CurvatureMethod::ThreeNormal ? 0.03
                                                         : 0.08;
        // Two samples in from the border, where no stencil uses a one-sided normal.
        for (int j = 2; j < 39; ++j)
            for (int i = 2; i < 19; ++i) {
                double z = j - 20.0;
                ASSERT_NEAR(k.at(i, j, 0), 0.0, 1e-5) << curvatureMethodName(m);
                for (int d = 1; d < 4; ++d) {
                    double dzdt = d == 1 ? 1.0 : (d == 2 ? 1.0 : -1.0) / std::sqrt(2.0);
                    double fz = std::sqrt(R * R - z * z);
                    double yp = -z / fz * dzdt, ypp = -R * R / (fz * fz * fz) * dzdt * dzdt;
                    double kappa = std::fabs(ypp) / std::pow(1 + yp * yp, 1.5);
                    if (d == 1) {
                        ASSERT_NEAR(kappa, 1.0 / R,
                                    1e-12);  // the section across the axis is the circle
                    }
                    if (m == CurvatureMethod::EdgeAngle) {
                        double L = d == 1 ? 1.0 : std::sqrt(2.0);
                        double zp = z - dzdt * L, zn = z + dzdt * L;
                        double e1x = -L, e1y = std::sqrt(R * R - zp * zp) - fz;
                        double e2x = L, e2y = std::sqrt(R * R - zn * zn) - fz;
                        double cosT =
                            (e1x * e2x + e1y * e2y) / (std::hypot(e1x, e1y) * std::hypot(e2x, e2y));
                        ASSERT_NEAR(k.at(i, j, d), 1 + cosT, 1e-4 * (1 + cosT) + 1e-6)
                            << i << "," << j << " d" << d;
                    } else {
                        ASSERT_NEAR(k.at(i, j, d), kappa, tol * kappa)
                            << curvatureMethodName(m) << " at " << i << "," << j << " dir " << d;
                    }
                }
            }
    }
}

TEST(AnalysisCurvature, SineRidgeThreeVertexSecondDerivativeIsExact) {
    // A sin(k x): three-vertex y'' = -A sin(kx) 4 sin^2(kh/2) / h^2 along x,
    // the same over 2 (step h sqrt 2, same x change) on the diagonals, 0 along
    // z. Interior vertices (the border repeats its neighbour). Tolerance 1e-5
    // absolute (peak |y''| ~ 0.3).
    const double A = 5.0, k = 2 * std::numbers::pi / 16.0, h = 1.0;
    auto f = sampleSurface(65, 17, h, 1.0, [&](double x, double) { return A * std::sin(k * x); });
    auto ypp = curvature(f, CurvatureMethod::ThreeVertex, NormalMethod::Quad,
                         CurvatureOutput::SecondDerivative);
    for (int j = 1; j < 16; ++j)
        for (int i = 1; i < 64; ++i) {
            double exact =
                -A * std::sin(k * i * h) * 4 * std::pow(std::sin(k * h / 2), 2) / (h * h);
            ASSERT_NEAR(ypp.at(i, j, 0), exact, 1e-5) << i;
            ASSERT_NEAR(ypp.at(i, j, 1), 0.0, 1e-5) << i;
            ASSERT_NEAR(ypp.at(i, j, 2), exact / 2, 1e-5) << i;
            ASSERT_NEAR(ypp.at(i, j, 3), exact / 2, 1e-5) << i;
        }
}

TEST(AnalysisCurvature, SineRidgeNormalMethodsAndEdgeAngle) {
    // With edge normals the slope is A cos(kx) sin(kh)/h (a central
    // difference), so three-normal y'' = -A sin(kx) sin^2(kh)/h^2 and
    // two-normal y'' = A sin(kh)/h (cos(k(x+h)) - cos(kx))/h, exactly (1e-5).
    // Every method is 0 along z (1e-5) and peaks on the crests and troughs.
    const double A = 5.0, k = 2 * std::numbers::pi / 16.0;
    auto f = sampleSurface(65, 17, 1.0, 1.0, [&](double x, double) { return A * std::sin(k * x); });
    auto three = curvature(f, CurvatureMethod::ThreeNormal, NormalMethod::Edge,
                           CurvatureOutput::SecondDerivative);
    auto two = curvature(f, CurvatureMethod::TwoNormal, NormalMethod::Edge,
                         CurvatureOutput::SecondDerivative);
    for (int i = 2; i < 63; ++i) {
        double x = i;
        ASSERT_NEAR(three.at(i, 8, 0), -A * std::sin(k * x) * std::pow(std::sin(k), 2), 1e-5) << i;
        ASSERT_NEAR(two.at(i, 8, 0), A * std::sin(k) * (std::cos(k * (x + 1)) - std::cos(k * x)),
                    1e-5)
            << i;
    }
    for (CurvatureMethod m : kAllMethods) {
        auto c = curvature(f, m);
        for (int i = 0; i < 65; ++i)
            ASSERT_NEAR(c.at(i, 8, 1), 0.0, 1e-5) << curvatureMethodName(m);
        // Crest at i = 4 (x = 4, sin = 1), trough at i = 12: the x value there
        // beats its neighbours two columns away (two-normal is one-sided, so
        // compare with the neighbour before and two after).
        for (int peak : {4, 12, 20}) {
            EXPECT_GT(c.at(peak, 8, 0), c.at(peak - 2, 8, 0))
                << curvatureMethodName(m) << " peak " << peak;
            EXPECT_GT(c.at(peak, 8, 0), c.at(peak + 3, 8, 0))
                << curvatureMethodName(m) << " peak " << peak;
        }
    }
}

TEST(AnalysisCurvature, GaussianBumpHasZeroRadialSecondDerivativeAtSigma) {
    // y = A exp(-r^2 / (2 sigma^2)): the radial y'' vanishes on r = sigma.
    // Radial directions on the grid: x and z at (+-sigma, 0) and (0, +-sigma)
    // with sigma = 10 h; the diagonals at (+-8, +-8) with sigma = 8 sqrt(2) h.
    // Tolerance: |y''(sigma)| below 2% of the peak |y''| = A / sigma^2 for the
    // centred stencils (the h^2/12 y'''' error is ~0.1%), 10% for two-normal's
    // one-sided difference (its h/2 y''' error is ~5%). Edge angle (no y''):
    // below 2% of its value at the centre.
    for (int diagonal = 0; diagonal < 2; ++diagonal) {
        const double sigma = diagonal ? 8.0 * std::sqrt(2.0) : 10.0, A = 20.0;
        auto f = sampleSurface(
            61, 61, 1.0, 1.0,
            [&](double x, double z) {
                return A * std::exp(-(x * x + z * z) / (2 * sigma * sigma));
            },
            -30.0, -30.0);
        const double peak = A / (sigma * sigma);
        struct Probe {
            int di, dj, dir;
        };
        std::vector<Probe> probes =
            diagonal ? std::vector<Probe>{{8, 8, 2}, {-8, -8, 2}, {8, -8, 3}, {-8, 8, 3}}
                     : std::vector<Probe>{{10, 0, 0}, {-10, 0, 0}, {0, 10, 1}, {0, -10, 1}};
        for (CurvatureMethod m : kAllMethods) {
            bool edge = m == CurvatureMethod::EdgeAngle;
            auto c =
                curvature(f, m, NormalMethod::Quad,
                          edge ? CurvatureOutput::Curvature : CurvatureOutput::SecondDerivative);
            double ref = edge ? c.at(30, 30, probes[0].dir) : peak;
            double tol = m == CurvatureMethod::TwoNormal ? 0.1 : 0.02;
            for (auto p : probes)
                EXPECT_LT(std::fabs(c.at(30 + p.di, 30 + p.dj, p.dir)), tol * ref)
                    << curvatureMethodName(m) << " at offset " << p.di << "," << p.dj;
            // Sanity: not trivially zero: at the centre |y''| is near the peak.
            EXPECT_GT(std::fabs(c.at(30, 30, probes[0].dir)), edge ? 0.0 : 0.5 * peak)
                << curvatureMethodName(m);
        }
    }
}

TEST(AnalysisCurvature, ReinforcementPushesValuesAwayFromOne) {
    // Parabolas y = a x^2 / 2 sampled finely (h = 0.05): near the apex every
    // measure is about a, at distance 2 as well, so the reinforced value is
    // about a^2: below 1 it drops, above 1 it grows. Edge angle lies in [0, 1]
    // and can only drop.
    for (double a : {0.5, 2.0}) {
        auto f = sampleSurface(
            41, 9, 0.05, 1.0, [&](double x, double) { return a * x * x / 2; }, -1.0, 0.0);
        for (CurvatureMethod m : {CurvatureMethod::ThreeNormal, CurvatureMethod::ThreeVertex,
                                  CurvatureMethod::EdgeAngle}) {
            auto one = curvature(f, m, NormalMethod::Quad, CurvatureOutput::Curvature, 1);
            auto two = curvature(f, m, NormalMethod::Quad, CurvatureOutput::Curvature, 2);
            for (int i = 16; i <= 24; ++i) {
                float v1 = one.at(i, 4, 0), v2 = two.at(i, 4, 0);
                ASSERT_GT(v1, 0.0f);
                if (m == CurvatureMethod::EdgeAngle || a < 1) {
                    EXPECT_LT(v2, v1) << curvatureMethodName(m) << " a=" << a << " i=" << i;
                } else {
                    EXPECT_GT(v2, v1) << curvatureMethodName(m) << " a=" << a << " i=" << i;
                }
            }
        }
    }
}

TEST(AnalysisCurvature, ReinforcementIsTheProductWithTheMeasureAtDistance) {
    // Three-vertex and edge angle at distance 2 on grid G equal the near value
    // times the near value of G subsampled by 2 (spacing doubled), at the same
    // point: the far stencil is the subsampled grid's near stencil. 1e-5 relative.
    auto g = terrain::generateDiamondSquare({.size = 65, .seed = 7});
    terrain::Heightfield sub(33, 33);
    sub.setSpacing(2.0f, 2.0f);
    for (int j = 0; j < 33; ++j)
        for (int i = 0; i < 33; ++i) sub.at(i, j) = g.at(2 * i, 2 * j);
    for (CurvatureMethod m : {CurvatureMethod::ThreeVertex, CurvatureMethod::EdgeAngle}) {
        auto nearG = curvature(g, m);
        auto reinforced = curvature(g, m, NormalMethod::Quad, CurvatureOutput::Curvature, 2);
        auto nearSub = curvature(sub, m);
        for (int j = 1; j < 32; ++j)
            for (int i = 1; i < 32; ++i)
                for (int d = 0; d < 4; ++d) {
                    double expect = double(nearG.at(2 * i, 2 * j, d)) * nearSub.at(i, j, d);
                    ASSERT_NEAR(reinforced.at(2 * i, 2 * j, d), expect,
                                1e-5 * std::fabs(expect) + 1e-9)
                        << curvatureMethodName(m) << " " << i << "," << j << " d" << d;
                }
    }
}

TEST(AnalysisCurvature, NoDataGivesNanThatDoesNotSpread) {
    // One no-data sample at p: it is NaN in all directions; a vertex is NaN in
    // a direction only when its stencil holds p (Chebyshev distance <= reach
    // from p); vertices farther than reach + 1 (the normals of p's neighbours
    // change too) equal the unmasked result bit for bit.
    auto g = terrain::generateDiamondSquare({.size = 65, .seed = 3});
    auto masked = g;
    std::vector<uint8_t> mask(size_t(g.sampleCount()), 1);
    const int pi = 30, pj = 21;
    mask[size_t(pj) * 65 + pi] = 0;
    masked.setMask(mask);
    for (CurvatureMethod m : kAllMethods)
        for (int distance : {1, 2}) {
            if (m == CurvatureMethod::TwoNormal && distance > 1) continue;
            auto plain = curvature(g, m, NormalMethod::Quad, CurvatureOutput::Curvature, distance);
            auto holed =
                curvature(masked, m, NormalMethod::Quad, CurvatureOutput::Curvature, distance);
            bool normals = m == CurvatureMethod::TwoNormal || m == CurvatureMethod::ThreeNormal;
            for (int d = 0; d < 4; ++d) EXPECT_TRUE(std::isnan(holed.at(pi, pj, d)));
            int nanCount = 0;
            for (int j = 0; j < 65; ++j)
                for (int i = 0; i < 65; ++i)
                    for (int d = 0; d < 4; ++d) {
                        int cheb = std::max(std::abs(i - pi), std::abs(j - pj));
                        float v = holed.at(i, j, d);
                        if (std::isnan(v)) {
                            ++nanCount;
                            // On the line through p along d, within reach.
                            int di = kDirectionSteps[size_t(d)][0],
                                dj = kDirectionSteps[size_t(d)][1];
                            bool onLine = (i - pi) * dj == (j - pj) * di;
                            ASSERT_TRUE(onLine && cheb <= distance)
                                << curvatureMethodName(m) << " NaN at " << i << "," << j << " d"
                                << d;
                        } else if (cheb > distance + (normals ? 1 : 0)) {
                            ASSERT_EQ(
                                std::memcmp(&v, &plain.values[(size_t(j) * 65 + i) * 4 + d], 4), 0)
                                << curvatureMethodName(m) << " changed at " << i << "," << j << " d"
                                << d;
                        }
                    }
            EXPECT_GE(nanCount, 4);
        }
}

TEST(AnalysisCurvature, MultithreadedEqualsSingleThreadedExactly) {
    // 257^2 is above kParallelMinSamples, so several threads really run.
    auto g = terrain::generateDiamondSquare({.size = 257, .seed = 5});
    g.setSpacing(2.0f, 1.5f);
    g.setVerticalScale(3.0f);
    std::vector<uint8_t> mask(size_t(g.sampleCount()), 1);
    for (int k = 0; k < 2000; ++k) mask[size_t(k * 97) % mask.size()] = 0;
    auto masked = g;
    masked.setMask(mask);
    for (const auto* field : {&g, &masked})
        for (CurvatureMethod m : kAllMethods)
            for (NormalMethod n : kAllNormals) {
                CurvatureOptions o{.method = m,
                                   .normals = n,
                                   .distance = m == CurvatureMethod::TwoNormal ? 1 : 2,
                                   .scale = 3.0f,
                                   .signedValues = true};
                o.threads = 1;
                auto serial = computeCurvature(*field, o);
                o.threads = 4;
                auto parallel = computeCurvature(*field, o);
                ASSERT_EQ(serial.values.size(), parallel.values.size());
                ASSERT_EQ(std::memcmp(serial.values.data(), parallel.values.data(),
                                      serial.values.size() * 4),
                          0)
                    << curvatureMethodName(m) << "/" << normalMethodName(n);
            }
}

TEST(AnalysisCurvature, ScaleLevelsAndSign) {
    const double A = 5.0, k = 2 * std::numbers::pi / 16.0;
    auto f = sampleSurface(65, 9, 1.0, 1.0, [&](double x, double) { return A * std::sin(k * x); });
    auto base = computeCurvature(f, {.method = CurvatureMethod::ThreeVertex});
    auto scaled = computeCurvature(f, {.method = CurvatureMethod::ThreeVertex, .scale = 4.0f});
    auto signedField =
        computeCurvature(f, {.method = CurvatureMethod::ThreeVertex, .signedValues = true});
    Levels lv{.enabled = true, .black = 0.1f, .white = 0.5f, .gamma = 2.0f};
    auto levelled = computeCurvature(f, {.method = CurvatureMethod::ThreeVertex, .levels = lv});
    for (int i = 0; i < 65; ++i) {
        float v = base.at(i, 4, 0);
        EXPECT_FLOAT_EQ(scaled.at(i, 4, 0), 4.0f * v);
        // Crests (sin > 0) are convex: negative; troughs concave: positive.
        double s = std::sin(k * std::clamp(i, 1, 63));
        if (std::fabs(s) > 0.1) {
            EXPECT_EQ(signedField.at(i, 4, 0) < 0, s > 0) << i;
        }
        EXPECT_FLOAT_EQ(std::fabs(signedField.at(i, 4, 0)), v);
        float expect = std::pow(std::clamp((v - 0.1f) / 0.4f, 0.0f, 1.0f), 0.5f);
        EXPECT_NEAR(levelled.at(i, 4, 0), expect, 1e-6f);
    }
}

TEST(AnalysisCurvature, BadParametersGiveClearErrors) {
    auto f = terrain::generateDiamondSquare({.size = 17});
    auto expectError = [&](CurvatureOptions o, const std::string& words) {
        try {
            computeCurvature(f, o);
            ADD_FAILURE() << "no error for " << words;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
        }
    };
    expectError({.distance = 0}, "distance must be an integer >= 1");
    expectError({.scale = -1.0f}, "scale must be finite and >= 0");
    expectError({.method = CurvatureMethod::TwoNormal, .distance = 2},
                "two-normal has no reinforcement");
    expectError({.levels = {.enabled = true, .black = 0.5f, .white = 0.5f}}, "white point");
    expectError({.levels = {.enabled = true, .gamma = 0.0f}}, "gamma");
    expectError({.distance = 9}, "too small for reinforcement distance 9");
    expectError({.method = CurvatureMethod::EdgeAngle, .output = CurvatureOutput::SecondDerivative},
                "edge-angle has no second derivative");
    EXPECT_THROW(parseCurvatureMethod("four-normal"), Error);
    try {
        parseCurvatureMethod("four-normal");
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("unknown curvature method 'four-normal'"),
                  std::string::npos);
    }
    for (CurvatureMethod m : kAllMethods)
        EXPECT_EQ(parseCurvatureMethod(curvatureMethodName(m)), m);
    EXPECT_THROW(computeCurvature(terrain::Heightfield{}, {}), Error);
}
