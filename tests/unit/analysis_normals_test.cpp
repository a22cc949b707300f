// Vertex normals: exact on planes for every method, in world units, one-sided
// at borders and beside no data, the same for any thread count.
#include <sierra/analysis/Normals.h>
#include <sierra/core/Error.h>
#include <sierra/terrain/DiamondSquare.h>

#include "analysis_test_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

using namespace sierra;
using namespace sierra::analysis;
using sierra::analysis::test::sampleSurface;

namespace {
constexpr NormalMethod kAll[] = {NormalMethod::Edge, NormalMethod::Triangle, NormalMethod::Quad};
}

TEST(AnalysisNormals, PlaneNormalIsExactEverywhere) {
    // World plane y = 0.5 x - 0.25 z with spacing 2 and vertical scale 4: the
    // stored heights differ, the world normal is normalize(-0.5, 1, 0.25).
    // Tolerance 1e-6, borders included.
    auto f = sampleSurface(9, 7, 2.0, 4.0, [](double x, double z) { return 0.5 * x - 0.25 * z; });
    const double len = std::sqrt(0.25 + 1 + 0.0625);
    for (NormalMethod m : kAll) {
        auto n = computeNormals(f, m);
        for (int j = 0; j < 7; ++j)
            for (int i = 0; i < 9; ++i) {
                ASSERT_NEAR(n.at(i, j).x, -0.5 / len, 1e-6) << normalMethodName(m);
                ASSERT_NEAR(n.at(i, j).y, 1.0 / len, 1e-6) << normalMethodName(m);
                ASSERT_NEAR(n.at(i, j).z, 0.25 / len, 1e-6) << normalMethodName(m);
            }
    }
}

TEST(AnalysisNormals, MethodsDifferAsDefinedOnACurvedSurface) {
    // y = 0.05 x^2 z (a saddle-like cubic): the edge normal is the central
    // difference gradient exactly; triangle and quad normals average unit
    // face normals and differ from it (and from each other) by a little.
    auto f = sampleSurface(
        11, 11, 1.0, 1.0, [](double x, double z) { return 0.05 * x * x * z; }, -5.0, -5.0);
    auto edge = computeNormals(f, NormalMethod::Edge);
    auto tri = computeNormals(f, NormalMethod::Triangle);
    auto quad = computeNormals(f, NormalMethod::Quad);
    double maxTri = 0, maxQuad = 0, maxTriQuad = 0;
    for (int j = 1; j < 10; ++j)
        for (int i = 1; i < 10; ++i) {
            double x = i - 5.0, z = j - 5.0;
            double gx = 0.05 * (((x + 1) * (x + 1)) - ((x - 1) * (x - 1))) * z / 2;
            double gz = 0.05 * x * x;  // exact: linear in z
            double l = std::sqrt(gx * gx + 1 + gz * gz);
            ASSERT_NEAR(edge.at(i, j).x, -gx / l, 1e-6);
            ASSERT_NEAR(edge.at(i, j).z, -gz / l, 1e-6);
            maxTri = std::max(maxTri, double(std::fabs(tri.at(i, j).x - edge.at(i, j).x)));
            maxQuad = std::max(maxQuad, double(std::fabs(quad.at(i, j).x - edge.at(i, j).x)));
            maxTriQuad = std::max(maxTriQuad, double(std::fabs(quad.at(i, j).x - tri.at(i, j).x)));
            ASSERT_NEAR(tri.at(i, j).x, edge.at(i, j).x, 0.05);
            ASSERT_NEAR(quad.at(i, j).x, edge.at(i, j).x, 0.05);
        }
    EXPECT_GT(maxTri, 1e-4);
    EXPECT_GT(maxQuad, 1e-4);
    EXPECT_GT(maxTriQuad, 1e-4);
}

TEST(AnalysisNormals, NoDataIsNanAndNeighboursStayFinite) {
    auto f = terrain::generateDiamondSquare({.size = 17, .seed = 2});
    std::vector<uint8_t> mask(17 * 17, 1);
    mask[8 * 17 + 8] = 0;
    mask[0] = 0;
    f.setMask(mask);
    for (NormalMethod m : kAll) {
        auto n = computeNormals(f, m);
        EXPECT_TRUE(std::isnan(n.at(8, 8).x));
        EXPECT_TRUE(std::isnan(n.at(0, 0).y));
        for (int j = 0; j < 17; ++j)
            for (int i = 0; i < 17; ++i) {
                if ((i == 8 && j == 8) || (i == 0 && j == 0)) continue;
                const Vec3& v = n.at(i, j);
                ASSERT_TRUE(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z))
                    << i << "," << j;
                ASSERT_NEAR(v.x * v.x + v.y * v.y + v.z * v.z, 1.0f, 1e-5f);
                ASSERT_GT(v.y, 0.0f);
            }
    }
}

TEST(AnalysisNormals, ThreadCountDoesNotChangeTheResult) {
    auto f = terrain::generateDiamondSquare({.size = 257, .seed = 9});
    for (NormalMethod m : kAll) {
        auto a = computeNormals(f, m, 1);
        auto b = computeNormals(f, m, 3);
        ASSERT_EQ(std::memcmp(a.normals.data(), b.normals.data(), a.normals.size() * sizeof(Vec3)),
                  0);
    }
    EXPECT_THROW(computeNormals(terrain::Heightfield{}), Error);
    EXPECT_THROW(parseNormalMethod("vertex"), Error);
    for (NormalMethod m : kAll) EXPECT_EQ(parseNormalMethod(normalMethodName(m)), m);
}
