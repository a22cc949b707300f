// Hatch strokes on cylinders run along or across the axis as asked.
#include <sierra/analysis/Hatch.h>
#include <sierra/core/Error.h>

#include "analysis_test_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

using namespace sierra;
using namespace sierra::analysis;
using sierra::analysis::test::sampleSurface;

namespace {

float dot(const Vec3& a, const Vec3& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

}  // namespace

TEST(AnalysisHatch, CylinderStrokesRunAcrossOrAlongItsAxis) {
    // Cylinders of radius 30 with the axis along x, along z and along the
    // x+z diagonal, |distance to axis| <= 15. "Along" strokes follow the
    // greatest curvature, i.e. cross the axis; "across" strokes lie along the
    // axis. Tolerance: |cos| of the angle to the expected horizontal axis
    // > 0.999 (2.5 degrees), strokes on the tangent plane within 1e-5.
    const double R = 30.0;
    const double inv = 1.0 / std::sqrt(2.0);
    struct Case {
        double ax, az;  // horizontal axis of the cylinder
    };
    for (Case cs : {Case{1, 0}, Case{0, 1}, Case{inv, inv}}) {
        auto f = sampleSurface(
            31, 31, 1.0, 1.0,
            [&](double x, double z) {
                double across = -x * cs.az + z * cs.ax;  // distance to the axis line
                return std::sqrt(R * R - across * across);
            },
            -15.0, -15.0);
        auto c = computeCurvature(f, {.method = CurvatureMethod::ThreeVertex});
        auto normals = computeNormals(f);
        for (HatchDirection dir : {HatchDirection::Along, HatchDirection::Across}) {
            auto h = computeHatchField(f, c, {.direction = dir});
            for (int j = 2; j < 29; ++j)
                for (int i = 2; i < 29; ++i) {
                    size_t k = h.index(i, j);
                    const Vec3& s = h.direction[k];
                    ASSERT_NEAR(std::sqrt(dot(s, s)), 1.0f, 1e-5f);
                    ASSERT_NEAR(dot(s, normals.normals[k]), 0.0f, 1e-5f) << "on the tangent plane";
                    // Horizontal part of the stroke against the axis.
                    float hl = std::hypot(s.x, s.z);
                    float cosAxis = float(std::fabs(s.x * cs.ax + s.z * cs.az)) / hl;
                    if (dir == HatchDirection::Across) {
                        ASSERT_GT(cosAxis, 0.999f) << i << "," << j;
                    } else {
                        ASSERT_LT(cosAxis, 0.045f) << i << "," << j;
                    }
                    ASSERT_NEAR(h.opacity[k], std::min(1.0f, c.maxMagnitude(i, j)), 1e-7f);
                }
        }
    }
}

TEST(AnalysisHatch, BlendedAxisWeighsTheFourDirections) {
    float ux = 0, uz = 0;
    const float alongZ[4] = {0.0f, 1.0f, 0.5f, 0.5f};
    ASSERT_TRUE(blendedCurvatureAxis(alongZ, 1.0f, 1.0f, ux, uz));
    EXPECT_NEAR(std::fabs(uz), 1.0f, 1e-6f);
    const float diagonal[4] = {0.5f, 0.5f, 1.0f, 0.0f};
    ASSERT_TRUE(blendedCurvatureAxis(diagonal, 1.0f, 1.0f, ux, uz));
    EXPECT_NEAR(ux, uz, 1e-6f);
    // Signed values weigh by magnitude.
    const float negative[4] = {-2.0f, 0.0f, -1.0f, -1.0f};
    ASSERT_TRUE(blendedCurvatureAxis(negative, 1.0f, 1.0f, ux, uz));
    EXPECT_NEAR(std::fabs(ux), 1.0f, 1e-6f);
    // Round summit: as much everywhere, the largest single direction wins.
    const float round[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    ASSERT_TRUE(blendedCurvatureAxis(round, 1.0f, 1.0f, ux, uz));
    EXPECT_NEAR(ux, 1.0f, 1e-6f);
    const float none[4] = {0.0f, NAN, 0.0f, 0.0f};
    EXPECT_FALSE(blendedCurvatureAxis(none, 1.0f, 1.0f, ux, uz));
}

TEST(AnalysisHatch, MismatchedFieldsAndNoData) {
    auto f = sampleSurface(9, 9, 1.0, 1.0, [](double x, double z) { return 0.1 * x * z; });
    auto c = computeCurvature(f, {});
    auto small = sampleSurface(8, 9, 1.0, 1.0, [](double, double) { return 0.0; });
    EXPECT_THROW(computeHatchField(small, c), Error);
    std::vector<uint8_t> mask(81, 1);
    mask[40] = 0;
    f.setMask(mask);
    auto h = computeHatchField(f, computeCurvature(f, {}));
    EXPECT_TRUE(std::isnan(h.direction[40].x));
    EXPECT_TRUE(std::isnan(h.opacity[40]));
    EXPECT_FALSE(std::isnan(h.direction[0].x));
    EXPECT_THROW(parseHatchDirection("with"), Error);
}

TEST(AnalysisHatch, ThreadCountDoesNotChangeTheField) {
    auto f = sampleSurface(257, 257, 1.0, 1.0, [](double x, double z) {
        return 3.0 * std::sin(0.1 * x) * std::cos(0.07 * z);
    });
    auto c = computeCurvature(f, {.method = CurvatureMethod::ThreeNormal, .distance = 2});
    for (HatchDirection dir : {HatchDirection::Along, HatchDirection::Across}) {
        auto a = computeHatchField(f, c, {.direction = dir, .threads = 1});
        auto b = computeHatchField(f, c, {.direction = dir, .threads = 3});
        ASSERT_EQ(
            std::memcmp(a.direction.data(), b.direction.data(), a.direction.size() * sizeof(Vec3)),
            0);
        ASSERT_EQ(std::memcmp(a.opacity.data(), b.opacity.data(), a.opacity.size() * sizeof(float)),
                  0);
    }
}
