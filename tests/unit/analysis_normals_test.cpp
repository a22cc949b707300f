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

// Scattered no data (single samples, a block, a whole column, samples on the
// border): a sample whose 3x3 neighbourhood is complete has the unmasked
// field's normal bit for bit (the rows' stretches between no data take the
// interior sums); one beside no data averages the quads (quad normals) whose
// 4 corners have data, each the normalised sum of its two triangles' unit
// normals, recomputed here in double precision.
TEST(AnalysisNormals, ScatteredNoDataLeavesCompleteNeighbourhoodsAlone) {
    const int n = 65;
    auto plain = terrain::generateDiamondSquare({.size = n, .seed = 4});
    plain.setSpacing(1.5f, 0.75f);
    plain.setVerticalScale(3.0f);
    auto masked = plain;
    std::vector<uint8_t> mask(size_t(n) * n, 1);
    uint32_t state = 12345;
    for (auto& m : mask) {
        state = state * 1664525u + 1013904223u;
        if ((state >> 8) % 100 < 3) m = 0;
    }
    for (int j = 20; j < 26; ++j)
        for (int i = 40; i < 47; ++i) mask[size_t(j) * n + i] = 0;
    for (int j = 0; j < n; ++j) mask[size_t(j) * n + 11] = 0;
    mask[5] = mask[size_t(n - 1) * n + 30] = 0;
    masked.setMask(mask);
    auto ok = [&](int i, int j) {
        return i >= 0 && j >= 0 && i < n && j < n && mask[size_t(j) * n + i] != 0;
    };
    const auto a = computeNormals(plain, NormalMethod::Quad);
    const auto b = computeNormals(masked, NormalMethod::Quad);
    const int ring[8][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}};
    int complete = 0, beside = 0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const Vec3& v = b.at(i, j);
            if (!ok(i, j)) {
                ASSERT_TRUE(std::isnan(v.x)) << i << "," << j;
                continue;
            }
            bool full = true;
            for (auto [di, dj] : ring) full = full && ok(i + di, j + dj);
            if (full) {
                ++complete;
                ASSERT_EQ(std::memcmp(&v, &a.at(i, j), sizeof(Vec3)), 0) << i << "," << j;
                continue;
            }
            ++beside;
            double e[8][3];
            const double yc = double(plain.at(i, j)) * 3.0;
            for (int k = 0; k < 8; ++k) {
                const int ni = i + ring[k][0], nj = j + ring[k][1];
                e[k][0] = ring[k][0] * 1.5;
                e[k][1] = ok(ni, nj) ? double(plain.at(ni, nj)) * 3.0 - yc : 0.0;
                e[k][2] = ring[k][1] * 0.75;
            }
            auto unit = [](double x, double y, double z, double* o) {
                const double l = std::sqrt(x * x + y * y + z * z);
                o[0] = x / l, o[1] = y / l, o[2] = z / l;
            };
            // upward unit normal of (centre, centre + p, centre + q), q after p
            auto tri = [&](const double* p, const double* q, double* o) {
                unit(q[1] * p[2] - q[2] * p[1], q[2] * p[0] - q[0] * p[2],
                     q[0] * p[1] - q[1] * p[0], o);
            };
            double sum[3] = {0, 0, 0};
            for (int q = 0; q < 4; ++q) {
                const int p0 = 2 * q, c = 2 * q + 1, p1 = (2 * q + 2) & 7;
                if (!ok(i + ring[p0][0], j + ring[p0][1]) || !ok(i + ring[c][0], j + ring[c][1]) ||
                    !ok(i + ring[p1][0], j + ring[p1][1]))
                    continue;
                double t0[3], t1[3], u[3];
                tri(e[p0], e[c], t0);
                tri(e[c], e[p1], t1);
                unit(t0[0] + t1[0], t0[1] + t1[1], t0[2] + t1[2], u);
                for (int k = 0; k < 3; ++k) sum[k] += u[k];
            }
            double expect[3] = {0, 1, 0};
            if (sum[1] > 0.0) unit(sum[0], sum[1], sum[2], expect);
            ASSERT_NEAR(v.x, expect[0], 1e-5) << i << "," << j;
            ASSERT_NEAR(v.y, expect[1], 1e-5) << i << "," << j;
            ASSERT_NEAR(v.z, expect[2], 1e-5) << i << "," << j;
        }
    EXPECT_GT(complete, n * n / 2);
    EXPECT_GT(beside, 300);
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
