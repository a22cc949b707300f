// The zoned TIN's epsilon policy (tin::buildZonedTin): the automatic epsilon
// of a budget, the loop that halves it while the zone agreement is too low,
// and a given epsilon used once.
#include "zones_test_maps.h"

#include <sierra/core/Error.h>
#include <sierra/terrain/DiamondSquare.h>
#include <sierra/tin/ZoneTin.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace {

using namespace sierra;

terrain::Heightfield fractal(int size) {
    return terrain::generateDiamondSquare({.size = size, .seed = 7, .threads = 1});
}

// Many thin diagonal stripes: borderlines that a coarse epsilon flattens, so
// that the zone agreement at the budget's epsilon falls short.
zones::ZoneMap stripes(int size) {
    return zones::test::makeMap(
        size, size, [](int x, int y) { return ((x + 2 * y) / 9 + (x * x + y) / 170) % 2; });
}

TEST(TinEpsilon, BudgetEpsilonFollowsTheMeanTriangle) {
    const zones::ZoneMap map = zones::test::makeMap(1025, 1025, [](int, int) { return 0; });
    // 0.45 sqrt(1024^2 / 100000) samples, one map pixel per sample.
    EXPECT_NEAR(tin::budgetEpsilon(100000, 1025, 1025, map, 0.5),
                0.45 * std::sqrt(1024.0 * 1024.0 / 100000.0), 1e-12);
    // A map of half the resolution: half the pixels per sample.
    const zones::ZoneMap half = zones::test::makeMap(513, 513, [](int, int) { return 0; });
    EXPECT_NEAR(tin::budgetEpsilon(100000, 1025, 1025, half, 0.1),
                0.5 * 0.45 * std::sqrt(1024.0 * 1024.0 / 100000.0), 1e-12);
    // A budget finer than the least epsilon: the least.
    EXPECT_EQ(tin::budgetEpsilon(100000000, 1025, 1025, map, 0.5), 0.5);
}

TEST(TinEpsilon, BudgetTrianglesTakesTheTighterLimit) {
    EXPECT_EQ(tin::budgetTriangles({}), 0);
    EXPECT_EQ(tin::budgetTriangles({.maxTriangles = 5000}), 5000);
    EXPECT_EQ(tin::budgetTriangles({.maxPoints = 2000}), 4000);
    EXPECT_EQ(tin::budgetTriangles({.maxTriangles = 5000, .maxPoints = 2000}), 4000);
    EXPECT_EQ(tin::budgetTriangles({.maxTriangles = 3000, .maxPoints = 2000}), 3000);
}

TEST(TinEpsilon, AutomaticEpsilonHalvesUntilTheZonesAgree) {
    const terrain::Heightfield field = fractal(129);
    const zones::ZoneMap map = stripes(129);
    const zones::Palette palette = zones::test::testPalette(2);
    const tin::TinDesc desc{.maxTriangles = 600};
    const double start = tin::budgetEpsilon(600, 129, 129, map, 0.5);
    ASSERT_GT(start, 2.0);
    std::vector<double> tried;
    tin::ZonedTinDesc zd{.epsilon = 0.5, .autoEpsilon = true};
    zd.retry = [&](double agreement, double epsilon, double next) {
        EXPECT_LT(agreement, zd.leastAgreement);
        EXPECT_DOUBLE_EQ(next, std::max(0.5, epsilon / 2));
        tried.push_back(epsilon);
    };
    const tin::ZonedTin z = tin::buildZonedTin(field, map, palette, desc, zd);
    EXPECT_TRUE(z.autoEpsilon);
    ASSERT_GE(z.builds, 2) << "the stripes must need a finer epsilon than the budget's";
    EXPECT_EQ(tried.size(), size_t(z.builds - 1));
    EXPECT_DOUBLE_EQ(tried.front(), start);
    // It stopped because the zones agree, or at the least epsilon.
    EXPECT_TRUE(z.agreement.fraction() >= zd.leastAgreement || z.epsilon == 0.5)
        << "agreement " << z.agreement.fraction() << " at epsilon " << z.epsilon;
    EXPECT_DOUBLE_EQ(z.epsilon, std::max(0.5, start / std::pow(2.0, z.builds - 1)));
    // The agreement is the mesh's, as zoneAgreement gives it.
    EXPECT_EQ(z.agreement.agree, tin::zoneAgreement(z.result.mesh, map).agree);
}

TEST(TinEpsilon, ErrorTargetOrGivenEpsilonBuildsOnce) {
    const terrain::Heightfield field = fractal(65);
    const zones::ZoneMap map = stripes(65);
    const zones::Palette palette = zones::test::testPalette(2);
    int retries = 0;
    auto count = [&](double, double, double) { ++retries; };
    // An error target beside the budget: the epsilon given, once.
    tin::ZonedTin z =
        tin::buildZonedTin(field, map, palette, {.maxErrorRel = 0.01, .maxTriangles = 300},
                           {.epsilon = 0.75, .autoEpsilon = true, .retry = count});
    EXPECT_FALSE(z.autoEpsilon);
    EXPECT_EQ(z.epsilon, 0.75);
    EXPECT_EQ(z.builds, 1);
    // No automatic epsilon asked for: once, whatever the agreement.
    z = tin::buildZonedTin(field, map, palette, {.maxTriangles = 300},
                           {.epsilon = 3.0, .autoEpsilon = false, .retry = count});
    EXPECT_EQ(z.epsilon, 3.0);
    EXPECT_EQ(z.builds, 1);
    EXPECT_EQ(retries, 0);
    EXPECT_THROW(tin::buildZonedTin(field, map, palette, {}, {.epsilon = -1.0}), Error);
}

}  // namespace
