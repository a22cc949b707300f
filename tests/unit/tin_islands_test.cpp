// Rule 3 for islands (tin::removeThinIslands): a closed borderline without a
// junction whose vertices all lie within epsilon of its longest chord is
// removed; fat islands, borderlines with junctions and an island with a kept
// borderline inside stay; a TIN of the result is still conforming to its
// borderlines and its zones agree with the map.
#include "zones_test_maps.h"

#include <sierra/terrain/DiamondSquare.h>
#include <sierra/tin/Tin.h>
#include <sierra/tin/ZoneTin.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <tuple>
#include <utility>

namespace {

using namespace sierra;

// Zone 0 with, in zone 1: a horizontal strip 1 pixel high and 24 long, a
// diagonal staircase 2 pixels wide (its bounding box is 16 x 17 pixels, its
// width across the diagonal under 2), a single pixel, and a 10 x 10 square;
// zone 2 below y = 48 (a borderline meeting the frame: junctions, never an island).
zones::ZoneMap islandMap() {
    return zones::test::makeMap(64, 64, [](int x, int y) {
        if (y >= 48) return 2;
        if (y == 6 && x >= 4 && x < 28) return 1;                        // thin strip
        if (y >= 14 && y < 31 && x - y >= -10 && x - y <= -9) return 1;  // diagonal staircase
        if (x == 40 && y == 8) return 1;                                 // one pixel
        if (x >= 36 && x < 46 && y >= 24 && y < 34) return 1;            // fat square
        return 0;
    });
}

// Connected components of a borderline set's edges: (edges, vertices) per component.
std::vector<std::pair<size_t, std::set<uint32_t>>> components(const zones::Borderlines& lines) {
    std::vector<uint32_t> parent(lines.vertices.size());
    for (uint32_t v = 0; v < parent.size(); ++v) parent[v] = v;
    auto root = [&](uint32_t v) {
        while (parent[v] != v) v = parent[v];
        return v;
    };
    for (const auto& e : lines.edges) parent[root(e.from)] = root(e.to);
    std::map<uint32_t, std::pair<size_t, std::set<uint32_t>>> byRoot;
    for (const auto& e : lines.edges) {
        auto& c = byRoot[root(e.from)];
        ++c.first;
        c.second.insert(e.from);
        c.second.insert(e.to);
    }
    std::vector<std::pair<size_t, std::set<uint32_t>>> out;
    for (auto& [r, c] : byRoot) out.push_back(c);
    return out;
}

// Does any vertex of `lines` lie inside the pixel box [x0, x1] x [y0, y1]?
bool anyVertexIn(const zones::Borderlines& lines, double x0, double y0, double x1, double y1) {
    for (const auto& v : lines.vertices)
        if (v.x >= x0 && v.x <= x1 && v.y >= y0 && v.y <= y1) return true;
    return false;
}

TEST(TinIslands, ThinIslandsGoFatOnesStay) {
    const zones::Palette palette = zones::test::testPalette(3);
    const zones::ZoneMap map = islandMap();
    zones::Borderlines before = zones::vectorise(map, palette);
    zones::removeCollinearVertices(before);
    const size_t componentsBefore = components(before).size();

    // At 0.5 pixels no island lies within epsilon of its chord (a single
    // pixel's corners are 0.71 from its diagonal): nothing changes.
    zones::Borderlines same = before;
    EXPECT_EQ(tin::removeThinIslands(same, 0.5), 0u);
    EXPECT_EQ(same.vertices.size(), before.vertices.size());
    EXPECT_EQ(same.edges.size(), before.edges.size());
    EXPECT_EQ(tin::removeThinIslands(same, 0.0), 0u);

    // At 2 pixels the strip, the staircase and the pixel go, the square (its
    // corners 7.1 from its diagonal) and the zone-2 line stay.
    zones::Borderlines lines = before;
    EXPECT_EQ(tin::removeThinIslands(lines, 2.0), 3u);
    EXPECT_EQ(components(lines).size(), componentsBefore - 3);
    EXPECT_FALSE(anyVertexIn(lines, 3, 5, 29, 8));    // the strip's
    EXPECT_FALSE(anyVertexIn(lines, 3, 13, 22, 32));  // the staircase's
    EXPECT_FALSE(anyVertexIn(lines, 39, 7, 42, 10));  // the pixel's
    EXPECT_TRUE(anyVertexIn(lines, 36, 24, 36, 24));  // the square's corner
    EXPECT_TRUE(anyVertexIn(lines, 0, 48, 0, 48));    // the zone-2 line at the frame
    // Every edge kept is an edge of before, with its zones; every vertex has an edge.
    std::set<std::tuple<double, double, double, double, int32_t, int32_t>> old;
    for (const auto& e : before.edges) {
        const auto& a = before.vertices[e.from];
        const auto& b = before.vertices[e.to];
        old.insert({a.x, a.y, b.x, b.y, e.left, e.right});
    }
    std::vector<int> degree(lines.vertices.size(), 0);
    for (const auto& e : lines.edges) {
        const auto& a = lines.vertices[e.from];
        const auto& b = lines.vertices[e.to];
        EXPECT_TRUE(old.count({a.x, a.y, b.x, b.y, e.left, e.right}));
        ++degree[e.from];
        ++degree[e.to];
    }
    for (int d : degree) EXPECT_GT(d, 0);
}

// A loop of the given corners, zone `inside` on its left as drawn (y down:
// corners listed clockwise on screen) and `outside` on its right.
void addLoop(zones::Borderlines& lines, const std::vector<zones::Vertex>& corners, int32_t inside,
             int32_t outside) {
    const uint32_t first = uint32_t(lines.vertices.size());
    for (const auto& c : corners) lines.vertices.push_back(c);
    for (uint32_t k = 0; k < corners.size(); ++k)
        lines.edges.push_back(
            {first + k, first + (k + 1) % uint32_t(corners.size()), inside, outside});
}

TEST(TinIslands, AnIslandAroundAKeptBorderlineStays) {
    zones::Borderlines lines;
    lines.mapWidth = lines.mapHeight = 64;
    lines.frameX1 = lines.frameY1 = 64;
    // A thin island of zone 1 (40 x 3 pixels, corners 3.0 from its diagonal)
    // holding two triangles of zones 2 and 3 that meet at one vertex, a
    // junction: the island must stay, or zone 1 would be left inside zone 0.
    addLoop(lines, {{10, 10}, {50, 10}, {50, 13}, {10, 13}}, 1, 0);
    addLoop(lines, {{20, 11}, {22, 11}, {21, 12}}, 2, 1);
    addLoop(lines, {{22, 11}, {24, 11}, {23, 12}}, 3, 1);
    // removeDuplicateVertices joins the two triangles at (22, 11).
    zones::removeDuplicateVertices(lines);
    ASSERT_EQ(lines.vertices.size(), 9u);
    zones::Borderlines kept = lines;
    EXPECT_EQ(tin::removeThinIslands(kept, 3.5), 0u);
    EXPECT_EQ(kept.edges.size(), lines.edges.size());

    // With a small square island of zone 2 inside instead, both go.
    zones::Borderlines nested;
    nested.mapWidth = nested.mapHeight = 64;
    nested.frameX1 = nested.frameY1 = 64;
    addLoop(nested, {{10, 10}, {50, 10}, {50, 13}, {10, 13}}, 1, 0);
    addLoop(nested, {{20, 11}, {21, 11}, {21, 12}, {20, 12}}, 2, 1);
    // And a fat island elsewhere stays.
    addLoop(nested, {{10, 30}, {30, 30}, {30, 50}, {10, 50}}, 1, 0);
    EXPECT_EQ(tin::removeThinIslands(nested, 3.5), 2u);
    EXPECT_EQ(nested.edges.size(), 4u);
    EXPECT_EQ(nested.vertices.size(), 4u);
    for (const auto& e : nested.edges) {
        EXPECT_EQ(e.left, 1);
        EXPECT_EQ(e.right, 0);
        EXPECT_GE(nested.vertices[e.from].y, 30.0);
    }
}

// The TIN of the simplified borderlines: each constraint segment is a chain
// of constrained mesh edges, no triangle is claimed by two zones, and the
// zones agree with the map except on the removed islands' pixels.
TEST(TinIslands, TinOfTheRemainingBorderlines) {
    const zones::Palette palette = zones::test::testPalette(3);
    const zones::ZoneMap map = islandMap();
    const terrain::Heightfield field =
        terrain::generateDiamondSquare({.size = 65, .seed = 7, .threads = 1});
    int64_t islandPixels = 0;  // the strip, the staircase and the pixel
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 30; ++x) islandPixels += map.at(x, y) == 1;
    islandPixels += map.at(40, 8) == 1;
    ASSERT_EQ(islandPixels, 24 + 2 * 17 + 1);
    for (double band : {0.0, 3.0}) {
        SCOPED_TRACE(testing::Message() << "band " << band);
        size_t removed = 0;
        const zones::Borderlines lines = tin::gridBorderlines(
            map, palette, {.epsilon = 2.0, .bandWidth = band}, 65, 65, &removed);
        EXPECT_EQ(removed, 3u);
        const tin::Constraints c = tin::constraintsFromBorderlines(lines, 65, 65);
        const tin::TinResult r =
            tin::buildTin(field, c, {.maxErrorRel = 0.005, .snapDistance = 0.0});
        EXPECT_EQ(r.stats.zoneConflicts, 0);
        // Each segment's two snapped ends are joined by constrained edges along it.
        std::set<std::pair<int, int>> constrained;
        for (size_t t = 0; t < r.mesh.triangles.size(); ++t)
            for (int k = 0; k < 3; ++k)
                if (r.mesh.constrainedEdges[t] & (1u << k)) {
                    const int u = r.mesh.triangles[t][size_t(k)];
                    const int w = r.mesh.triangles[t][size_t((k + 1) % 3)];
                    constrained.insert({std::min(u, w), std::max(u, w)});
                }
        std::map<std::pair<int, int>, int> vertexAt;
        for (size_t v = 0; v < r.mesh.vertices.size(); ++v)
            vertexAt[{r.mesh.vertices[v].x, r.mesh.vertices[v].y}] = int(v);
        for (const auto& s : c.segments) {
            const auto& a = c.vertices[size_t(s.a)];
            const auto& b = c.vertices[size_t(s.b)];
            const std::pair<int, int> pa{int(std::floor(a.x + 0.5)), int(std::floor(a.y + 0.5))};
            const std::pair<int, int> pb{int(std::floor(b.x + 0.5)), int(std::floor(b.y + 0.5))};
            if (pa == pb) continue;
            ASSERT_TRUE(vertexAt.count(pa) && vertexAt.count(pb));
            // Walk the mesh vertices on a-b in order.
            std::vector<std::pair<int64_t, int>> on;
            for (size_t v = 0; v < r.mesh.vertices.size(); ++v) {
                const auto p = r.mesh.vertices[v];
                const int64_t cross = int64_t(pb.first - pa.first) * (p.y - pa.second) -
                                      int64_t(pb.second - pa.second) * (p.x - pa.first);
                const int64_t t = int64_t(p.x - pa.first) * (pb.first - pa.first) +
                                  int64_t(p.y - pa.second) * (pb.second - pa.second);
                const int64_t len = int64_t(pb.first - pa.first) * (pb.first - pa.first) +
                                    int64_t(pb.second - pa.second) * (pb.second - pa.second);
                if (cross == 0 && t >= 0 && t <= len) on.push_back({t, int(v)});
            }
            std::sort(on.begin(), on.end());
            for (size_t k = 0; k + 1 < on.size(); ++k)
                EXPECT_TRUE(constrained.count({std::min(on[k].second, on[k + 1].second),
                                               std::max(on[k].second, on[k + 1].second)}));
        }
        const tin::ZoneAgreement agreement = tin::zoneAgreement(r.mesh, map);
        // The removed islands' pixels disagree (a few others might, where the
        // map's 64 pixels are stretched over 65 samples); the fat square's agree.
        EXPECT_GE(agreement.pixels - agreement.agree, islandPixels);
        EXPECT_LE(agreement.pixels - agreement.agree, islandPixels + 8);
    }
}

}  // namespace
