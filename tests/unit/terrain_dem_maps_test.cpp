// DEM fields from the 3x3 window: slope and aspect conventions on planes,
// hillshade styles, gdaldem's edge and no-data rules, and the curvatures of
// surfaces whose curvature is known in closed form.

#include <sierra/terrain/DemMaps.h>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

namespace sierra::terrain {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A w x h field of world heights f(x east, y north) sampled at spacing h;
// row 0 is north (y = (rows - 1 - j) * h), column 0 west (x = i * h). The
// stored heights are world heights / verticalScale.
Heightfield sampled(int w, int h, double spacing, double verticalScale,
                    const std::function<double(double, double)>& f) {
    Heightfield field(w, h);
    field.setSpacing(float(spacing), float(spacing));
    field.setVerticalScale(float(verticalScale));
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i)
            field.at(i, j) = float(f(i * spacing, (h - 1 - j) * spacing) / verticalScale);
    return field;
}

float at(const std::vector<float>& v, const Heightfield& f, int i, int j) {
    return v[size_t(j) * size_t(f.width()) + size_t(i)];
}

TEST(DemMaps, SlopeOfPlanesInWorldUnits) {
    // Rising 1 per 1 eastwards, stored at vertical scale 0.5 and spacing 4.
    Heightfield f = sampled(9, 7, 4.0, 0.5, [](double x, double) { return x; });
    for (Stencil s : {Stencil::Horn, Stencil::ZevenbergenThorne, Stencil::EvansYoung}) {
        std::vector<float> deg = demField(f, {.field = DemField::Slope, .stencil = s});
        std::vector<float> pct = demField(
            f, {.field = DemField::Slope, .stencil = s, .slopeUnits = SlopeUnits::Percent});
        EXPECT_NEAR(at(deg, f, 4, 3), 45.0f, 1e-4f);
        EXPECT_NEAR(at(pct, f, 4, 3), 100.0f, 1e-3f);
    }
}

TEST(DemMaps, AspectIsTheCompassBearingDownhill) {
    struct Case {
        double dx, dy;  // world gradient east, north
        float compass, trigonometric;
    };
    // Falling to the east faces east: 90 on the compass, 0 counter-clockwise from east.
    for (const Case& c : {Case{-1, 0, 90, 0}, Case{0, -1, 0, 90}, Case{1, 0, 270, 180},
                          Case{0, 1, 180, 270}, Case{-1, -1, 45, 45}, Case{1, -1, 315, 135}}) {
        Heightfield f =
            sampled(5, 5, 1.0, 1.0, [&](double x, double y) { return c.dx * x + c.dy * y; });
        std::vector<float> a = demField(f, {.field = DemField::Aspect});
        std::vector<float> t = demField(f, {.field = DemField::Aspect, .trigonometric = true});
        EXPECT_NEAR(at(a, f, 2, 2), c.compass, 1e-4f) << c.dx << "," << c.dy;
        EXPECT_NEAR(at(t, f, 2, 2), c.trigonometric, 1e-4f) << c.dx << "," << c.dy;
    }
    // Flat ground has no aspect (NaN), or 0 with zeroForFlat.
    Heightfield flat(5, 5, 3.0f);
    EXPECT_TRUE(std::isnan(at(demField(flat, {.field = DemField::Aspect}), flat, 2, 2)));
    EXPECT_EQ(at(demField(flat, {.field = DemField::Aspect, .zeroForFlat = true}), flat, 2, 2),
              0.0f);
}

TEST(DemMaps, HillshadeStyles) {
    Heightfield flat(5, 5, 0.0f);
    auto shadeAt = [](const Heightfield& f, DemFieldDesc d) {
        d.field = DemField::Hillshade;
        return at(demField(f, d), f, 2, 2);
    };
    // Flat ground: sin(altitude) on gdaldem's 1..255 scale, for one light or four.
    const float flatShade = float(1.0 + 254.0 * std::sin(30.0 * kPi / 180.0));
    EXPECT_NEAR(shadeAt(flat, {.altitude = 30.0f}), flatShade, 1e-3f);
    EXPECT_NEAR(shadeAt(flat, {.altitude = 30.0f, .shade = ShadeStyle::Multidirectional}),
                flatShade, 1e-3f);
    EXPECT_NEAR(shadeAt(flat, {.shade = ShadeStyle::Combined}), 255.0f, 1e-3f);
    EXPECT_NEAR(shadeAt(flat, {.shade = ShadeStyle::Igor}), 255.0f, 1e-3f);
    // A slope of 45 degrees facing the sun (from the north-west, 45 up) is lit
    // head-on: 255; facing away it is lit at grazing angle: 1.
    const double g = std::sqrt(0.5);
    Heightfield towards = sampled(5, 5, 1.0, 1.0, [&](double x, double y) { return g * (x - y); });
    Heightfield away = sampled(5, 5, 1.0, 1.0, [&](double x, double y) { return g * (y - x); });
    EXPECT_NEAR(shadeAt(towards, {}), 255.0f, 1e-3f);
    EXPECT_NEAR(shadeAt(away, {}), 1.0f, 1e-3f);
    // Igor darkens a slope facing away by its steepness: 255 (1 - 45/90).
    EXPECT_NEAR(shadeAt(away, {.shade = ShadeStyle::Igor}), 127.5f, 1e-3f);
    EXPECT_NEAR(shadeAt(towards, {.shade = ShadeStyle::Igor}), 255.0f, 1e-3f);
    // The z factor steepens: a gentle slope facing away (east) darkens.
    Heightfield gentle = sampled(5, 5, 1.0, 1.0, [&](double x, double) { return -0.1 * x; });
    EXPECT_LT(shadeAt(gentle, {.zFactor = 5.0f}), shadeAt(gentle, {}) - 20.0f);
    EXPECT_THROW(shadeAt(gentle, {.zFactor = 0.0f}), Error);
    EXPECT_THROW(shadeAt(gentle, {.altitude = 91.0f}), Error);
}

TEST(DemMaps, EdgesAndNoDataAsGdaldem) {
    Heightfield f = sampled(6, 5, 1.0, 1.0, [](double x, double y) { return 2.0 * x + y; });
    const DemFieldDesc slope{.field = DemField::Slope};
    std::vector<float> plain = demField(f, slope);
    const float expected = float(std::atan(std::sqrt(5.0)) * 180.0 / kPi);
    for (int j = 0; j < f.height(); ++j)
        for (int i = 0; i < f.width(); ++i) {
            const bool border = i == 0 || j == 0 || i == f.width() - 1 || j == f.height() - 1;
            if (border)
                EXPECT_TRUE(std::isnan(at(plain, f, i, j))) << i << "," << j;
            else
                EXPECT_NEAR(at(plain, f, i, j), expected, 1e-4f) << i << "," << j;
        }
    // With computeEdges the missing row or column is extrapolated linearly: a
    // plane stays a plane on the first and last columns, and on the first
    // and last rows away from the corners (where the columns clamp).
    DemFieldDesc edges = slope;
    edges.computeEdges = true;
    std::vector<float> e = demField(f, edges);
    EXPECT_NEAR(at(e, f, 0, 2), expected, 1e-4f);
    EXPECT_NEAR(at(e, f, 5, 2), expected, 1e-4f);
    EXPECT_NEAR(at(e, f, 2, 0), expected, 1e-4f);
    EXPECT_NEAR(at(e, f, 3, 4), expected, 1e-4f);
    EXPECT_FALSE(std::isnan(at(e, f, 0, 0)));
    // A no-data sample: NaN itself; its neighbours NaN too unless computeEdges,
    // which gives the missing sample the centre's height.
    std::vector<uint8_t> mask(size_t(f.sampleCount()), 1);
    mask[size_t(2) * 6 + 2] = 0;
    f.setMask(mask);
    plain = demField(f, slope);
    e = demField(f, edges);
    EXPECT_TRUE(std::isnan(at(plain, f, 2, 2)));
    EXPECT_TRUE(std::isnan(at(e, f, 2, 2)));
    EXPECT_TRUE(std::isnan(at(plain, f, 3, 3)));
    EXPECT_FALSE(std::isnan(at(e, f, 3, 3)));
    EXPECT_NEAR(at(plain, f, 4, 3), expected, 1e-4f);  // its window misses the hole
}

TEST(DemMaps, TriTpiRoughness) {
    // One peak of height 8 among zeros: the 3x3 measures at the peak.
    Heightfield f(5, 5, 0.0f);
    f.at(2, 2) = 8.0f;
    auto centre = [&](DemFieldDesc d) { return at(demField(f, d), f, 2, 2); };
    EXPECT_NEAR(centre({.field = DemField::Tri}), std::sqrt(8.0 * 64.0), 1e-4);
    EXPECT_NEAR(centre({.field = DemField::Tri, .tri = TriFormula::Wilson}), 8.0, 1e-5);
    EXPECT_NEAR(centre({.field = DemField::Tpi}), 8.0, 1e-5);
    EXPECT_NEAR(centre({.field = DemField::Roughness}), 8.0, 1e-5);
    // Beside the peak: lower than its neighbours' mean.
    EXPECT_NEAR(at(demField(f, {.field = DemField::Tpi}), f, 1, 2), -1.0, 1e-5);
}

// The paraboloid dome z = -(x^2 + y^2) / (2R) about (cx, cy): at distance rho
// from the top, along the fall line z(rho) = -rho^2 / (2R) curves by
// (1/R) / (1 + (rho/R)^2)^1.5, its contours are circles of radius rho, the
// slope's sine is (rho/R) / sqrt(1 + (rho/R)^2), and K = (1/R^2) / (1 + (rho/R)^2)^2.
// A quadratic: both stencils fit it exactly, so the values hold to rounding.
TEST(DemMaps, CurvaturesOfAParaboloidDome) {
    const double R = 50.0, h = 2.0, c = 20.0 * h;
    Heightfield dome = sampled(41, 41, h, 0.5, [&](double x, double y) {
        return 100.0 - ((x - c) * (x - c) + (y - c) * (y - c)) / (2 * R);
    });
    for (Stencil s : {Stencil::EvansYoung, Stencil::ZevenbergenThorne}) {
        auto field = [&](DemField kind) { return demField(dome, {.field = kind, .stencil = s}); };
        const std::vector<float> profile = field(DemField::CurvatureProfile),
                                 plan = field(DemField::CurvaturePlan),
                                 tangential = field(DemField::CurvatureTangential),
                                 mean = field(DemField::CurvatureMean),
                                 gauss = field(DemField::CurvatureGaussian),
                                 kmin = field(DemField::CurvatureMinimal),
                                 kmax = field(DemField::CurvatureMaximal);
        // The top (i = j = 20): an umbilic point, both principal curvatures 1/R.
        EXPECT_NEAR(at(mean, dome, 20, 20), 1.0 / R, 1e-3 / R);
        EXPECT_NEAR(at(gauss, dome, 20, 20), 1.0 / (R * R), 1e-3 / (R * R));
        EXPECT_NEAR(at(kmin, dome, 20, 20), 1.0 / R, 1e-4);
        EXPECT_NEAR(at(kmax, dome, 20, 20), 1.0 / R, 1e-4);
        EXPECT_EQ(at(profile, dome, 20, 20), 0.0f);  // no fall line on the top
        // 12 samples east and 5 north of the top (row 15): rho = 13 h.
        const double rho = 13.0 * h, u = rho / R, w = 1.0 + u * u;
        const int i = 32, j = 15;
        // Within 1e-3 relative: the stored float32 heights round the second
        // differences.
        auto near = [](double value, double expected) {
            EXPECT_NEAR(value, expected, 1e-3 * std::abs(expected));
        };
        near(at(profile, dome, i, j), (1.0 / R) / std::pow(w, 1.5));
        near(at(plan, dome, i, j), 1.0 / rho);
        near(at(tangential, dome, i, j), (1.0 / rho) * u / std::sqrt(w));
        near(at(gauss, dome, i, j), 1.0 / (R * R) / (w * w));
        EXPECT_GT(at(mean, dome, i, j), 0.0f);  // convex: positive
        EXPECT_LE(at(kmin, dome, i, j), at(kmax, dome, i, j));
        EXPECT_NEAR(double(at(kmin, dome, i, j)) * at(kmax, dome, i, j), at(gauss, dome, i, j),
                    1e-3 * at(gauss, dome, i, j));
    }
    // The bowl (the dome upside down) is concave: every curvature but the
    // Gaussian changes sign.
    Heightfield bowl = dome;
    for (float& v : bowl.samples()) v = -v;
    for (DemField kind : {DemField::CurvatureProfile, DemField::CurvaturePlan,
                          DemField::CurvatureTangential, DemField::CurvatureMean}) {
        const std::vector<float> up =
            demField(dome, {.field = kind, .stencil = Stencil::EvansYoung});
        const std::vector<float> down =
            demField(bowl, {.field = kind, .stencil = Stencil::EvansYoung});
        EXPECT_GT(at(up, dome, 32, 15), 0.0f);
        EXPECT_NEAR(at(down, bowl, 32, 15), -at(up, dome, 32, 15), 1e-7);
    }
    const std::vector<float> kDown =
        demField(bowl, {.field = DemField::CurvatureGaussian, .stencil = Stencil::EvansYoung});
    EXPECT_GT(at(kDown, bowl, 32, 15), 0.0f);
    EXPECT_THROW(demField(dome, {.field = DemField::CurvatureMean, .stencil = Stencil::Horn}),
                 Error);
}

TEST(DemMaps, CurvaturesOfASphereCapAndASaddle) {
    // A sphere of radius R seen from above: every normal section curves by
    // 1/R, convex. The 3x3 fits are exact only for quadratics: within 1%.
    const double R = 200.0, h = 1.0, c = 30.0;
    Heightfield cap = sampled(61, 61, h, 1.0, [&](double x, double y) {
        return std::sqrt(R * R - (x - c) * (x - c) - (y - c) * (y - c));
    });
    auto value = [&](const Heightfield& f, DemField kind, int i, int j) {
        return double(at(demField(f, {.field = kind, .stencil = Stencil::EvansYoung}), f, i, j));
    };
    for (DemField kind :
         {DemField::CurvatureMean, DemField::CurvatureMinimal, DemField::CurvatureMaximal,
          DemField::CurvatureProfile, DemField::CurvatureTangential})
        EXPECT_NEAR(value(cap, kind, 45, 20), 1.0 / R, 0.01 / R) << int(kind);
    EXPECT_NEAR(value(cap, DemField::CurvatureGaussian, 45, 20), 1.0 / (R * R), 0.02 / (R * R));
    // The contour through (45, 20) is a circle about the centre.
    const double rho = std::hypot(45.0 - c, (60.0 - 20.0) - c);
    EXPECT_NEAR(value(cap, DemField::CurvaturePlan, 45, 20), 1.0 / rho, 0.01 / rho);
    // A saddle z = (x^2 - y^2) / (2a): Gaussian -1/a^2 and mean 0 at its centre.
    const double a = 40.0;
    Heightfield saddle = sampled(21, 21, h, 1.0, [&](double x, double y) {
        return ((x - 10) * (x - 10) - (y - 10) * (y - 10)) / (2 * a);
    });
    EXPECT_NEAR(value(saddle, DemField::CurvatureGaussian, 10, 10), -1.0 / (a * a), 1e-7);
    EXPECT_NEAR(value(saddle, DemField::CurvatureMean, 10, 10), 0.0, 1e-7);
    EXPECT_NEAR(value(saddle, DemField::CurvatureMaximal, 10, 10), 1.0 / a, 1e-5);
    EXPECT_NEAR(value(saddle, DemField::CurvatureMinimal, 10, 10), -1.0 / a, 1e-5);
}

TEST(DemMaps, Names) {
    DemField f;
    EXPECT_TRUE(parseDemField("curvature-tangential", &f));
    EXPECT_EQ(f, DemField::CurvatureTangential);
    EXPECT_FALSE(parseDemField("curvature", &f));
    EXPECT_TRUE(isCurvature(DemField::CurvatureMaximal));
    EXPECT_FALSE(isCurvature(DemField::Roughness));
}

}  // namespace
}  // namespace sierra::terrain
