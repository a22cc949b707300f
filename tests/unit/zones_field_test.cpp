// The distance-to-border field: zones from the vector polygons, distances to
// the vectorised borderlines, exact on straight borders, within half a texel
// of brute force everywhere.
#include <sierra/zones/BorderField.h>

#include "zones_test_maps.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace sierra::zones {
namespace {

using test::testPalette;

double bruteDistance(const Borderlines& lines, double px, double py) {
    double best = 1e30;
    for (const Edge& e : lines.edges) {
        if (e.left < 0 || e.right < 0) continue;
        const Vertex& a = lines.vertices[e.from];
        const Vertex& b = lines.vertices[e.to];
        double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
        double t = std::clamp(((px - a.x) * dx + (py - a.y) * dy) / len2, 0.0, 1.0);
        best = std::min(best, std::hypot(a.x + t * dx - px, a.y + t * dy - py));
    }
    return best;
}

TEST(ZonesField, StraightBorderGrowsOneTexelPerTexel) {
    ZoneMap map = test::makeMap(40, 16, [](int x, int) { return x < 20 ? 0 : 1; });
    Borderlines lines = buildBorderlines(map, testPalette(2));
    for (int s : {1, 2, 4}) {
        BorderField f = buildBorderField(lines, {.texelsPerPixel = s});
        ASSERT_EQ(f.width, 40 * s);
        ASSERT_EQ(f.height, 16 * s);
        for (int j = 0; j < f.height; ++j)
            for (int i = 0; i < f.width; ++i) {
                size_t p = size_t(j) * size_t(f.width) + size_t(i);
                double expected = i + 0.5 - 20.0 * s;  // texels, < 0 on zone 0's side
                EXPECT_NEAR(f.signedDistance[p], expected, 1e-4);
                EXPECT_EQ(f.zone[p], expected < 0 ? 0 : 1);
                EXPECT_EQ(f.lowZone[p], 0);
                EXPECT_EQ(f.highZone[p], 1);
            }
    }
}

TEST(ZonesField, ZeroOnFigure1BorderlinesAndExactZones) {
    ZoneMap map = drawBorderlines(test::discMap());
    Borderlines lines = buildBorderlines(map, testPalette(2));
    BorderField f = buildBorderField(lines);
    for (int y = 0; y < map.height; ++y)
        for (int x = 0; x < map.width; ++x) {
            size_t p = size_t(y) * size_t(map.width) + size_t(x);
            if (map.at(x, y) == kBorderlinePixel) {
                EXPECT_NEAR(f.signedDistance[p], 0.0f, 1e-5f)
                    << x << "," << y;  // float rounding only
            } else {
                EXPECT_EQ(f.zone[p], map.at(x, y)) << x << "," << y;
            }
        }
}

TEST(ZonesField, MatchesBruteForceWithinHalfATexel) {
    for (auto [name, map, zones] :
         {std::tuple{"disc", test::discMap(), 2}, std::tuple{"junction", test::junctionMap(), 3},
          std::tuple{"checker", test::checkerMap(), 2}}) {
        for (double eps : {0.0, 1.0}) {
            for (int s : {1, 3}) {
                SCOPED_TRACE(std::string(name) + " eps " + std::to_string(eps) + " s " +
                             std::to_string(s));
                Borderlines lines = buildBorderlines(map, testPalette(zones), {.epsilon = eps});
                BorderField f = buildBorderField(lines, {.texelsPerPixel = s});
                double worst = 0;
                int wrongZone = 0;
                for (int j = 0; j < f.height; ++j)
                    for (int i = 0; i < f.width; ++i) {
                        size_t p = size_t(j) * size_t(f.width) + size_t(i);
                        double px = (i + 0.5) / s, py = (j + 0.5) / s;
                        double exact = bruteDistance(lines, px, py) * s;
                        worst = std::max(worst, std::abs(std::abs(f.signedDistance[p]) - exact));
                        if (eps == 0.0) wrongZone += f.zone[p] != map.at(int(px), int(py));
                        // The sign says on which side of its pair the texel lies
                        // (either side is right for a texel on the line).
                        if (f.lowZone[p] != f.highZone[p] &&
                            std::abs(f.signedDistance[p]) > 1e-4f) {
                            EXPECT_EQ(f.zone[p],
                                      f.signedDistance[p] < 0 ? f.lowZone[p] : f.highZone[p]);
                        }
                    }
                EXPECT_LE(worst, 0.5);
                EXPECT_EQ(wrongZone, 0);
            }
        }
    }
}

TEST(ZonesField, OneZoneHasNoBorder) {
    ZoneMap map = test::makeMap(8, 8, [](int, int) { return 1; });
    BorderField f = buildBorderField(buildBorderlines(map, testPalette(2)));
    for (size_t p = 0; p < f.zone.size(); ++p) {
        EXPECT_EQ(f.zone[p], 1);
        EXPECT_EQ(f.lowZone[p], 1);
        EXPECT_GE(f.signedDistance[p], 1e8f);
    }
}

TEST(ZonesField, RejectsDoubledLines) {
    Borderlines lines = buildBorderlines(test::squareMap(), testPalette(2), {.bandWidth = 2});
    EXPECT_THROW(buildBorderField(lines), Error);
    EXPECT_THROW(buildBorderField(buildBorderlines(test::squareMap(), testPalette(2)),
                                  {.texelsPerPixel = 0}),
                 Error);
}

}  // namespace
}  // namespace sierra::zones
