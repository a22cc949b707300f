// Vectorising zone maps (002_b56d55d1c6f1d101.txt, section 4): both layouts,
// rules 1-3, exact areas, no gaps or overlaps, transition bands.
#include <sierra/zones/Borderlines.h>

#include "zones_test_maps.h"

#include <sierra/terrain/DiamondSquare.h>
#include <sierra/zones/Tiles.h>

#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>

namespace sierra::zones {
namespace {

using test::checkerMap;
using test::discMap;
using test::junctionMap;
using test::squareMap;
using test::testPalette;

struct Case {
    const char* name;
    ZoneMap map;
    int zones;
};

std::vector<Case> cases() {
    return {{"square", squareMap(), 2},
            {"disc", discMap(), 2},
            {"checker", checkerMap(), 2},
            {"junction", junctionMap(), 3}};
}

std::vector<int64_t> pixelCounts(const ZoneMap& map, int zones) {
    std::vector<int64_t> count(size_t(zones), 0);
    for (int16_t id : map.ids)
        if (id >= 0) ++count[size_t(id)];
    return count;
}

double segmentDistance(const Vertex& p, const Vertex& a, const Vertex& b) {
    double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
    double t = len2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / len2, 0.0, 1.0) : 0.0;
    return std::hypot(a.x + t * dx - p.x, a.y + t * dy - p.y);
}

// Around every vertex, in angular order, the zone right of one edge is the
// zone left of the next: no sector is claimed by two zones or by none. With
// no crossing edges this means the zones tile the frame with no gap or overlap.
void expectConsistentFaces(const Borderlines& lines) {
    std::vector<std::vector<std::pair<double, std::pair<int32_t, int32_t>>>> around(
        lines.vertices.size());
    for (const Edge& e : lines.edges) {
        const Vertex& a = lines.vertices[e.from];
        const Vertex& b = lines.vertices[e.to];
        ASSERT_NE(e.left, e.right) << "an edge between one zone";
        around[e.from].push_back({std::atan2(b.y - a.y, b.x - a.x), {e.left, e.right}});
        around[e.to].push_back({std::atan2(a.y - b.y, a.x - b.x), {e.right, e.left}});
    }
    for (size_t v = 0; v < around.size(); ++v) {
        auto& list = around[v];
        ASSERT_GE(list.size(), 2u) << "dangling vertex " << v << " at " << lines.vertices[v].x
                                   << "," << lines.vertices[v].y;
        std::sort(list.begin(), list.end());
        for (size_t k = 0; k < list.size(); ++k) {
            const auto& cur = list[k];
            const auto& next = list[(k + 1) % list.size()];
            ASSERT_NE(cur.first, next.first)
                << "two edges leave vertex " << v << " in the same direction";
            ASSERT_EQ(cur.second.second, next.second.first)
                << "zones disagree around vertex " << v << " (" << lines.vertices[v].x << ", "
                << lines.vertices[v].y << ")";
        }
    }
}

bool properlyCross(const Vertex& a, const Vertex& b, const Vertex& c, const Vertex& d) {
    auto orient = [](const Vertex& p, const Vertex& q, const Vertex& r) {
        double v = (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x);
        return v > 1e-12 ? 1 : v < -1e-12 ? -1 : 0;
    };
    int o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
    return o1 * o2 < 0 && o3 * o4 < 0;
}

// Every pair of edges whose bounding boxes overlap is tested: a sweep over the
// edges sorted by their smallest x, so that maps of thousands of edges stay fast
// (under the sanitizers too).
void expectNoCrossings(const Borderlines& lines) {
    const auto& v = lines.vertices;
    const auto& edges = lines.edges;
    auto lowX = [&](const Edge& e) { return std::min(v[e.from].x, v[e.to].x); };
    std::vector<size_t> order(edges.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::sort(order.begin(), order.end(),
              [&](size_t a, size_t b) { return lowX(edges[a]) < lowX(edges[b]); });
    for (size_t k = 0; k < order.size(); ++k) {
        const Edge& e = edges[order[k]];
        const double highX = std::max(v[e.from].x, v[e.to].x);
        const double lowY = std::min(v[e.from].y, v[e.to].y),
                     highY = std::max(v[e.from].y, v[e.to].y);
        for (size_t m = k + 1; m < order.size() && lowX(edges[order[m]]) <= highX; ++m) {
            const Edge& f = edges[order[m]];
            if (std::max(v[f.from].y, v[f.to].y) < lowY || std::min(v[f.from].y, v[f.to].y) > highY)
                continue;
            if (properlyCross(v[e.from], v[e.to], v[f.from], v[f.to])) {
                ADD_FAILURE() << "edges " << order[k] << " and " << order[m] << " cross";
                return;
            }
        }
    }
}

TEST(ZonesVectorise, CrossingCheckFindsCrossings) {
    // A long edge first in x order, a short one far along it that crosses it,
    // and a third that overlaps both boxes without crossing.
    Borderlines lines;
    lines.vertices = {{0, 0}, {10, 10}, {8, 9}, {9, 8}, {0, 5}, {1, 9}};
    lines.edges = {{.from = 0, .to = 1}, {.from = 4, .to = 5}};
    expectNoCrossings(lines);
    lines.edges.push_back({.from = 2, .to = 3});
    EXPECT_NONFATAL_FAILURE(expectNoCrossings(lines), "edges 0 and 2 cross");
}

TEST(ZonesVectorise, TouchingAreasEqualPixelCountsAtEpsilonZero) {
    for (auto& c : cases()) {
        SCOPED_TRACE(c.name);
        Borderlines lines = buildBorderlines(c.map, testPalette(c.zones));
        auto areas = zoneAreas(lines);
        auto counts = pixelCounts(c.map, c.zones);
        for (int z = 0; z < c.zones; ++z)
            EXPECT_EQ(areas[size_t(z)], double(counts[size_t(z)])) << "zone " << z;
        expectConsistentFaces(lines);
        expectNoCrossings(lines);
    }
}

// Figure 1 layout: vertices sit on pixel centres, so each zone is a lattice
// polygon and Pick's theorem gives its exact area: A = I + B/2 - chi, with I
// the zone's pixels strictly inside the frame, B the pixel centres on its
// boundary (borderline pixels and the zone's own pixels on the frame, counted
// once per visit of the boundary cycles: the unit lattice steps of its edges),
// chi = components - holes.
TEST(ZonesVectorise, Figure1AreasFollowPicksTheorem) {
    struct Topology {
        ZoneMap map;
        int zones;
        std::vector<int> holes;
    };
    std::vector<std::pair<const char*, Topology>> maps{
        {"square", {drawBorderlines(squareMap()), 2, {1, 0}}},
        {"disc", {drawBorderlines(discMap()), 2, {1, 0}}},
        {"checker", {drawBorderlines(checkerMap()), 2, {0, 0}}},
        {"junction", {drawBorderlines(junctionMap()), 3, {0, 0, 0}}}};
    for (auto& [name, t] : maps) {
        SCOPED_TRACE(name);
        const ZoneMap& m = t.map;
        Borderlines lines = buildBorderlines(m, testPalette(t.zones));
        auto areas = zoneAreas(lines);
        for (int z = 0; z < t.zones; ++z) {
            // I and the components of the zone's pixels (4-connected).
            int64_t inside = 0;
            int components = 0;
            std::vector<int> seen(m.ids.size(), 0);
            for (int y = 0; y < m.height; ++y)
                for (int x = 0; x < m.width; ++x) {
                    if (m.at(x, y) != z) continue;
                    bool ring = x == 0 || y == 0 || x == m.width - 1 || y == m.height - 1;
                    inside += !ring;
                    if (seen[size_t(y * m.width + x)]) continue;
                    ++components;
                    std::vector<std::pair<int, int>> stack{{x, y}};
                    seen[size_t(y * m.width + x)] = 1;
                    while (!stack.empty()) {
                        auto [px, py] = stack.back();
                        stack.pop_back();
                        for (auto [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
                            int qx = px + dx, qy = py + dy;
                            if (qx < 0 || qy < 0 || qx >= m.width || qy >= m.height ||
                                m.at(qx, qy) != z || seen[size_t(qy * m.width + qx)])
                                continue;
                            seen[size_t(qy * m.width + qx)] = 1;
                            stack.push_back({qx, qy});
                        }
                    }
                }
            // B: lattice points (pixel centres) along the zone's boundary cycles.
            int64_t boundary = 0;
            for (const Edge& e : lines.edges) {
                if (e.left != z && e.right != z) continue;
                const Vertex& a = lines.vertices[e.from];
                const Vertex& b = lines.vertices[e.to];
                boundary += std::gcd(std::abs(int(b.x - a.x)), std::abs(int(b.y - a.y)));
            }
            double expected =
                double(inside) + double(boundary) / 2 - (components - t.holes[size_t(z)]);
            EXPECT_EQ(areas[size_t(z)], expected) << "zone " << z;
        }
        double total = std::accumulate(areas.begin(), areas.end(), 0.0);
        EXPECT_EQ(total, double(m.width - 1) * double(m.height - 1));
        expectConsistentFaces(lines);
        expectNoCrossings(lines);
    }
}

TEST(ZonesVectorise, Figure1VerticesAreBorderlinePixelCentres) {
    ZoneMap m = drawBorderlines(discMap());
    Borderlines lines = vectorise(m, testPalette(2));
    for (const Vertex& v : lines.vertices) {
        int x = int(v.x - 0.5), y = int(v.y - 0.5);
        ASSERT_EQ(v.x, x + 0.5);
        ASSERT_EQ(v.y, y + 0.5);
        bool ring = x == 0 || y == 0 || x == m.width - 1 || y == m.height - 1;
        EXPECT_TRUE(ring || m.at(x, y) == kBorderlinePixel) << x << "," << y;
    }
}

TEST(ZonesVectorise, RuleOneMergesDuplicateVertices) {
    // The paper's raw form: two fresh vertices per pair of neighbouring pixels.
    Borderlines lines;
    lines.zones = {{0, "a", 0, {-1, -1}}, {1, "b", 1, {-1, -1}}};
    for (int k = 0; k < 4; ++k) {
        lines.vertices.push_back({double(k), 2.0});
        lines.vertices.push_back({double(k + 1), 2.0});
        lines.edges.push_back({uint32_t(2 * k), uint32_t(2 * k + 1), 0, 1});
    }
    lines.edges.push_back({1, 0, 1, 0});  // the same edge again, reversed
    removeDuplicateVertices(lines);
    EXPECT_EQ(lines.vertices.size(), 5u);
    EXPECT_EQ(lines.edges.size(), 4u);
    std::set<std::pair<double, double>> unique;
    for (const Vertex& v : lines.vertices) unique.insert({v.x, v.y});
    EXPECT_EQ(unique.size(), lines.vertices.size());
    // vectorise already holds rule 1: running it again changes nothing.
    Borderlines raw = vectorise(discMap(), testPalette(2));
    size_t before = raw.vertices.size();
    removeDuplicateVertices(raw);
    EXPECT_EQ(raw.vertices.size(), before);
}

TEST(ZonesVectorise, RuleTwoLeavesOnlyCorners) {
    Borderlines lines = vectorise(squareMap(), testPalette(2));
    EXPECT_GT(lines.vertices.size(), 100u);
    auto areasBefore = zoneAreas(lines);
    removeCollinearVertices(lines);
    // The frame's 4 corners and the square's 4 corners.
    EXPECT_EQ(lines.vertices.size(), 8u);
    EXPECT_EQ(lines.edges.size(), 8u);
    EXPECT_EQ(zoneAreas(lines), areasBefore);
    // No unpinned vertex is left between two collinear edges, on any map.
    for (auto& c : cases()) {
        Borderlines l = vectorise(c.map, testPalette(c.zones));
        removeCollinearVertices(l);
        auto pinned = junctions(l);
        std::vector<std::vector<uint32_t>> nb(l.vertices.size());
        for (const Edge& e : l.edges) {
            nb[e.from].push_back(e.to);
            nb[e.to].push_back(e.from);
        }
        for (size_t v = 0; v < l.vertices.size(); ++v) {
            if (pinned[v]) continue;
            ASSERT_EQ(nb[v].size(), 2u);
            const Vertex &a = l.vertices[nb[v][0]], &p = l.vertices[v], &b = l.vertices[nb[v][1]];
            double cross = (p.x - a.x) * (b.y - a.y) - (p.y - a.y) * (b.x - a.x);
            EXPECT_NE(cross, 0.0) << c.name << ": collinear vertex kept";
        }
    }
}

TEST(ZonesVectorise, RuleThreeRemovesVerticesWithinEpsilon) {
    // A staircase boundary one pixel per step: its corners lie within
    // sqrt(2)/4 ~ 0.354 of the diagonal through the stair ends.
    ZoneMap stair = test::makeMap(20, 20, [](int x, int y) { return x > y ? 0 : 1; });
    Borderlines fine = buildBorderlines(stair, testPalette(2), {.epsilon = 0.3});
    Borderlines coarse = buildBorderlines(stair, testPalette(2), {.epsilon = 0.8});
    Borderlines exact = buildBorderlines(stair, testPalette(2));
    EXPECT_EQ(fine.vertices.size(), exact.vertices.size());  // 0.354 > 0.3: nothing removed
    // At 0.8 the stair is one diagonal segment (two frame junctions) plus the frame.
    size_t borderEdges = 0;
    for (const Edge& e : coarse.edges) borderEdges += e.left >= 0 && e.right >= 0;
    EXPECT_EQ(borderEdges, 1u);
    auto areas = zoneAreas(coarse);
    // The stair runs from (1, 0) to (20, 19): zone 0 keeps its 190 pixels minus
    // the half of each of the 19 steps the diagonal cuts off.
    EXPECT_NEAR(areas[0], 190.0 - 9.5, 1e-9);
}

TEST(ZonesVectorise, SimplifiedArcsStayWithinEpsilonAndTheAreaBound) {
    for (double eps : {0.5, 1.0, 2.5}) {
        for (bool figure1 : {false, true}) {
            for (auto& c : cases()) {
                SCOPED_TRACE(std::string(c.name) + (figure1 ? " figure1" : " touching") + " eps " +
                             std::to_string(eps));
                ZoneMap map = figure1 ? drawBorderlines(c.map) : c.map;
                Borderlines exact = buildBorderlines(map, testPalette(c.zones));
                Borderlines simple = buildBorderlines(map, testPalette(c.zones), {.epsilon = eps});
                EXPECT_LE(simple.vertices.size(), exact.vertices.size());
                // Every vertex of the exact lines lies within eps of an edge of
                // the simplified lines between the same two zones.
                for (const Edge& e : exact.edges)
                    for (uint32_t v : {e.from, e.to}) {
                        double best = 1e30;
                        for (const Edge& f : simple.edges)
                            if (std::minmax(f.left, f.right) == std::minmax(e.left, e.right))
                                best = std::min(best, segmentDistance(exact.vertices[v],
                                                                      simple.vertices[f.from],
                                                                      simple.vertices[f.to]));
                        ASSERT_LE(best, eps + 1e-9);
                    }
                // Each simplified segment replaced a chain inside its eps-capsule,
                // so a zone's area moves by at most the sum of its segments'
                // capsule areas (2 eps L + pi eps^2).
                auto a0 = zoneAreas(exact), a1 = zoneAreas(simple);
                for (int z = 0; z < c.zones; ++z) {
                    double bound = 0;
                    for (const Edge& f : simple.edges)
                        if ((f.left == z || f.right == z) && f.left >= 0 && f.right >= 0) {
                            const Vertex &a = simple.vertices[f.from], &b = simple.vertices[f.to];
                            bound += 2 * eps * std::hypot(b.x - a.x, b.y - a.y) + M_PI * eps * eps;
                        }
                    EXPECT_LE(std::abs(a1[size_t(z)] - a0[size_t(z)]), bound + 1e-9)
                        << "zone " << z;
                }
                double total = 0;
                for (double a : a1) total += a;
                EXPECT_NEAR(total,
                            (simple.frameX1 - simple.frameX0) * (simple.frameY1 - simple.frameY0),
                            1e-9);
                expectConsistentFaces(simple);
                expectNoCrossings(simple);
            }
        }
    }
}

TEST(ZonesVectorise, JunctionsArePinned) {
    Borderlines exact = buildBorderlines(junctionMap(), testPalette(3));
    Borderlines simple = buildBorderlines(junctionMap(), testPalette(3), {.epsilon = 3.0});
    auto pinnedExact = junctions(exact);
    std::set<std::pair<double, double>> kept;
    for (const Vertex& v : simple.vertices) kept.insert({v.x, v.y});
    int threeZoneJunctions = 0;
    for (size_t v = 0; v < exact.vertices.size(); ++v) {
        if (!pinnedExact[v]) continue;
        EXPECT_TRUE(kept.count({exact.vertices[v].x, exact.vertices[v].y})) << "junction removed";
        std::set<int32_t> zonesAround;
        for (const Edge& e : exact.edges)
            if (e.from == v || e.to == v) zonesAround.insert({e.left, e.right});
        threeZoneJunctions += zonesAround.size() == 3 && !zonesAround.count(kOutside);
    }
    EXPECT_EQ(threeZoneJunctions, 1);
}

TEST(ZonesVectorise, BandOfTheAskedWidth) {
    const double width = 2.0;
    Borderlines lines = buildBorderlines(squareMap(), testPalette(2), {.bandWidth = width});
    ASSERT_EQ(lines.zones.size(), 3u);
    const Zone& band = lines.zones[2];
    EXPECT_EQ(band.name, "z0|z1");
    EXPECT_EQ(band.bandOf[0], 0);
    EXPECT_EQ(band.bandOf[1], 1);
    auto areas = zoneAreas(lines);
    // The 12x14 square offset by +-1 along mitred normals: (14 x 16) - (10 x 12).
    EXPECT_NEAR(areas[2], 14.0 * 16.0 - 10.0 * 12.0, 1e-9);
    EXPECT_NEAR(areas[1], 10.0 * 12.0, 1e-9);
    EXPECT_NEAR(areas[0] + areas[1] + areas[2], 32.0 * 32.0, 1e-9);
    // Every band edge runs at width/2 from the original boundary (measured at
    // its midpoint; its mitred ends are width/2 from both lines of a corner).
    Borderlines base = buildBorderlines(squareMap(), testPalette(2));
    for (const Edge& e : lines.edges) {
        if (e.left != 2 && e.right != 2) continue;
        Vertex mid{(lines.vertices[e.from].x + lines.vertices[e.to].x) / 2,
                   (lines.vertices[e.from].y + lines.vertices[e.to].y) / 2};
        double best = 1e30;
        for (const Edge& f : base.edges)
            if (f.left >= 0 && f.right >= 0)
                best = std::min(best,
                                segmentDistance(mid, base.vertices[f.from], base.vertices[f.to]));
        EXPECT_NEAR(best, width / 2, 1e-9);
    }
    expectConsistentFaces(lines);
    expectNoCrossings(lines);
}

TEST(ZonesVectorise, BandsNarrowToJunctionsAndKeepTheWidthBetween) {
    for (auto& c : cases()) {
        SCOPED_TRACE(c.name);
        Borderlines lines = buildBorderlines(drawBorderlines(c.map), testPalette(c.zones),
                                             {.epsilon = 0.5, .bandWidth = 1.0});
        expectConsistentFaces(lines);
        expectNoCrossings(lines);
        double total = 0;
        for (double a : zoneAreas(lines)) total += a;
        EXPECT_NEAR(total, (lines.frameX1 - lines.frameX0) * (lines.frameY1 - lines.frameY0), 1e-6);
    }
    // A straight border across the map: full width in the middle, 0 at the frame.
    ZoneMap half = test::makeMap(40, 20, [](int x, int) { return x < 20 ? 0 : 1; });
    Borderlines lines = buildBorderlines(half, testPalette(2), {.bandWidth = 3.0});
    double minX = 1e9, maxX = -1e9;
    for (const Edge& e : lines.edges)
        if (e.left == 2 || e.right == 2)
            for (uint32_t v : {e.from, e.to})
                if (lines.vertices[v].y >= 6 && lines.vertices[v].y <= 14) {
                    minX = std::min(minX, lines.vertices[v].x);
                    maxX = std::max(maxX, lines.vertices[v].x);
                }
    EXPECT_DOUBLE_EQ(minX, 18.5);
    EXPECT_DOUBLE_EQ(maxX, 21.5);
    // A hexagon: full width over y = 6..14, tapering over 2 W = 6 at each end.
    EXPECT_NEAR(zoneAreas(lines)[2], 3.0 * (20 - 6.0), 1e-9);
}

// A real map: the auto-zoning of a fractal terrain (specks, thin strips, many
// junctions), in both layouts, exact and simplified.
TEST(ZonesVectorise, AutoZonedTerrainTilesTheFrame) {
    Palette p;
    for (const std::string& name : tileNames())
        p.surfaces.push_back({name, Colour(p.surfaces.size() + 1), "", 16, 0.5});
    for (uint64_t seed : {3, 4, 5}) {
        auto field = terrain::generateDiamondSquare({.size = 129, .seed = seed});
        auto [lo, hi] = field.range();
        field.setVerticalScale(0.2f * 128 / (hi - lo));
        ZoneMap touching = autoZones(field, p, {.rockSlope = 20.0f, .smoothPasses = 0});
        for (bool figure1 : {false, true}) {
            ZoneMap map = figure1 ? drawBorderlines(touching) : touching;
            for (double eps : {0.0, 0.7, 1.5, 4.0}) {
                SCOPED_TRACE(std::string(figure1 ? "figure1" : "touching") + " eps " +
                             std::to_string(eps) + " seed " + std::to_string(seed));
                Borderlines lines = buildBorderlines(map, p, {.epsilon = eps});
                auto areas = zoneAreas(lines);
                double total = 0;
                for (double a : areas) {
                    EXPECT_GE(a, 0.0);
                    total += a;
                }
                EXPECT_NEAR(
                    total, (lines.frameX1 - lines.frameX0) * (lines.frameY1 - lines.frameY0), 1e-6);
                if (!figure1 && eps == 0.0) {
                    auto counts = pixelCounts(map, int(p.surfaces.size()));
                    for (size_t z = 0; z < counts.size(); ++z)
                        EXPECT_EQ(areas[z], double(counts[z]));
                }
                expectConsistentFaces(lines);
                expectNoCrossings(lines);
            }
            // Bands wider than many strips and bends: narrowed where they do not fit.
            for (double width : {2.0, 5.0}) {
                SCOPED_TRACE(std::string(figure1 ? "figure1" : "touching") + " band " +
                             std::to_string(width) + " seed " + std::to_string(seed));
                Borderlines lines = buildBorderlines(map, p, {.epsilon = 0.7, .bandWidth = width});
                double total = 0;
                for (double a : zoneAreas(lines)) {
                    EXPECT_GE(a, 0.0);
                    total += a;
                }
                EXPECT_NEAR(
                    total, (lines.frameX1 - lines.frameX0) * (lines.frameY1 - lines.frameY0), 1e-6);
                expectConsistentFaces(lines);
                expectNoCrossings(lines);
            }
        }
    }
}

}  // namespace
}  // namespace sierra::zones
