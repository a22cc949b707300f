// Zone borderlines as the TIN's constrained edges: every vectorised segment is
// a chain of mesh edges, the triangles' zones agree with the zone map (checked
// by this file's own point location, not the library's zoneAgreement), bands
// survive snapping to the grid, and the OBJ's materials name tiles that exist.
#include "zones_test_maps.h"

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/terrain/DiamondSquare.h>
#include <sierra/tin/Export.h>
#include <sierra/tin/Tin.h>
#include <sierra/tin/ZoneTin.h>
#include <sierra/zones/Tiles.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>

namespace {

using namespace sierra;
using tin::GridPoint;

// Three zones on a 65x65 map: a disc (1) inside zone 0, and zone 2 below a
// sloping line that meets the disc's zone nowhere and the frame twice.
zones::ZoneMap threeZones(int size) {
    const double s = double(size) / 65.0;
    return zones::test::makeMap(size, size, [&](int x, int y) {
        const double dx = (x + 0.5) / s - 30, dy = (y + 0.5) / s - 26;
        if (dx * dx + dy * dy < 14.2 * 14.2) return 1;
        return (y + 0.5) / s > 48 + ((x + 0.5) / s) / 5 ? 2 : 0;
    });
}

int64_t orient(GridPoint a, GridPoint b, GridPoint c) {
    return int64_t(b.x - a.x) * (c.y - a.y) - int64_t(b.y - a.y) * (c.x - a.x);
}

// The sample the TIN snaps a constraint vertex to.
GridPoint snapped(const tin::Constraints::Vertex& v, const tin::TinMesh& m) {
    return {std::clamp(int32_t(std::floor(v.x + 0.5)), 0, m.gridWidth - 1),
            std::clamp(int32_t(std::floor(v.y + 0.5)), 0, m.gridHeight - 1)};
}

// Every segment a-b is the union of the constrained mesh edges along it: the
// mesh vertices on the segment, in order, are joined by constrained edges.
void expectSegmentsAreMeshEdges(const tin::Constraints& c, const tin::TinMesh& m) {
    std::set<std::pair<int, int>> constrained;
    for (size_t t = 0; t < m.triangles.size(); ++t)
        for (int k = 0; k < 3; ++k)
            if (m.constrainedEdges[t] & (1u << k)) {
                const int u = m.triangles[t][size_t(k)], w = m.triangles[t][size_t((k + 1) % 3)];
                constrained.insert({std::min(u, w), std::max(u, w)});
            }
    int checked = 0;
    for (const auto& s : c.segments) {
        const GridPoint a = snapped(c.vertices[size_t(s.a)], m),
                        b = snapped(c.vertices[size_t(s.b)], m);
        if (a == b) continue;
        std::vector<std::pair<int64_t, int>> on;  // (position along a-b, vertex)
        for (size_t v = 0; v < m.vertices.size(); ++v) {
            const GridPoint p = m.vertices[v];
            if (orient(a, b, p) != 0) continue;
            const int64_t t = int64_t(p.x - a.x) * (b.x - a.x) + int64_t(p.y - a.y) * (b.y - a.y);
            const int64_t len = int64_t(b.x - a.x) * (b.x - a.x) + int64_t(b.y - a.y) * (b.y - a.y);
            if (t >= 0 && t <= len) on.push_back({t, int(v)});
        }
        std::sort(on.begin(), on.end());
        ASSERT_GE(on.size(), 2u) << "segment (" << a.x << "," << a.y << ")-(" << b.x << "," << b.y
                                 << ") has no vertices";
        EXPECT_EQ(on.front().first, 0);
        for (size_t k = 0; k + 1 < on.size(); ++k) {
            const int u = on[k].second, w = on[k + 1].second;
            EXPECT_TRUE(constrained.count({std::min(u, w), std::max(u, w)}))
                << "segment (" << a.x << "," << a.y << ")-(" << b.x << "," << b.y
                << "): no constrained edge (" << m.vertices[size_t(u)].x << ","
                << m.vertices[size_t(u)].y << ")-(" << m.vertices[size_t(w)].x << ","
                << m.vertices[size_t(w)].y << ")";
        }
        ++checked;
    }
    EXPECT_GT(checked, 20);
}

// This file's own agreement: each map pixel centre, nudged off every edge by
// an offset no grid line passes through, located by a brute-force search.
double independentAgreement(const tin::TinMesh& m, const zones::ZoneMap& map) {
    const double sx = double(m.gridWidth - 1) / double(map.width - 1);
    const double sy = double(m.gridHeight - 1) / double(map.height - 1);
    int64_t agree = 0, pixels = 0;
    for (int j = 0; j < map.height; ++j)
        for (int i = 0; i < map.width; ++i) {
            const int zone = map.at(i, j);
            if (zone < 0) continue;
            double px = i * sx + 1.3e-4, py = j * sy + 0.7e-4;
            if (px > m.gridWidth - 1) px -= 2.6e-4;
            if (py > m.gridHeight - 1) py -= 1.4e-4;
            int found = -1;
            for (size_t t = 0; t < m.triangles.size() && found < 0; ++t) {
                bool inside = true;
                for (int k = 0; k < 3 && inside; ++k) {
                    const GridPoint a = m.vertices[size_t(m.triangles[t][size_t(k)])];
                    const GridPoint b = m.vertices[size_t(m.triangles[t][size_t((k + 1) % 3)])];
                    inside = (b.x - a.x) * (py - a.y) - (b.y - a.y) * (px - a.x) > 0.0;
                }
                if (inside) found = int(t);
            }
            EXPECT_GE(found, 0) << "pixel " << i << "," << j << " in no triangle";
            if (found < 0) continue;
            ++pixels;
            agree += (m.surfaces[size_t(found)][0] == zone || m.surfaces[size_t(found)][1] == zone)
                         ? 1
                         : 0;
        }
    return pixels ? double(agree) / double(pixels) : 0.0;
}

terrain::Heightfield fractal(int size) {
    return terrain::generateDiamondSquare({.size = size, .seed = 7, .threads = 1});
}

TEST(TinZones, BorderlineSegmentsAreMeshEdges) {
    // Touching and Figure 1 layouts, map as fine as the grid and half as fine.
    for (bool figure1 : {false, true})
        for (int gridSize : {65, 129}) {
            SCOPED_TRACE(testing::Message()
                         << (figure1 ? "Figure 1" : "touching") << ", grid " << gridSize);
            zones::ZoneMap map = threeZones(65);
            if (figure1) map = zones::drawBorderlines(map);
            const zones::Palette palette = zones::test::testPalette(3);
            const zones::Borderlines lines =
                tin::gridBorderlines(map, palette, {.epsilon = 0.5}, gridSize, gridSize);
            const tin::Constraints c = tin::constraintsFromBorderlines(lines, gridSize, gridSize);
            const terrain::Heightfield field = fractal(gridSize);
            // snapDistance 0: no bending, so each segment must be exactly a chain of edges.
            const tin::TinResult r =
                tin::buildTin(field, c, {.maxErrorRel = 0.01, .snapDistance = 0.0});
            expectSegmentsAreMeshEdges(c, r.mesh);
            EXPECT_EQ(r.stats.zoneConflicts, 0);
        }
}

TEST(TinZones, TriangleZonesAgreeWithTheMap) {
    const zones::Palette palette = zones::test::testPalette(3);
    const terrain::Heightfield field = fractal(65);
    for (bool figure1 : {false, true})
        for (double band : {0.0, 3.0}) {
            SCOPED_TRACE(testing::Message()
                         << (figure1 ? "Figure 1" : "touching") << ", band " << band);
            zones::ZoneMap map = threeZones(65);
            if (figure1) map = zones::drawBorderlines(map);
            const zones::Borderlines lines =
                tin::gridBorderlines(map, palette, {.epsilon = 0.5, .bandWidth = band}, 65, 65);
            const tin::Constraints c = tin::constraintsFromBorderlines(lines, 65, 65);
            EXPECT_EQ(c.bands.empty(), band == 0.0);
            // The app's setting: the snap rule on (default snap distance).
            const tin::TinResult r = tin::buildTin(field, c, {.maxErrorRel = 0.005});
            const double mine = independentAgreement(r.mesh, map);
            EXPECT_GE(mine, 0.995);
            const tin::ZoneAgreement lib = tin::zoneAgreement(r.mesh, map);
            EXPECT_GE(lib.fraction(), 0.995);
            EXPECT_NEAR(lib.fraction(), mine, 0.002);
            int64_t expectedPixels = 0;
            for (int16_t id : map.ids) expectedPixels += id >= 0;
            EXPECT_EQ(lib.pixels, expectedPixels);
            if (band > 0.0) {
                size_t bandTriangles = 0;
                for (const auto& s : r.mesh.surfaces) bandTriangles += s[0] != s[1];
                EXPECT_GT(bandTriangles, 10u);
            }
        }
}

// Every triangle has one zone (or one band pair): no triangle is claimed by two
// zones, and every constrained edge carries its triangle's zone on the
// triangle's side. Islands of 3 to 7 pixels ringed by borderline pixels (Figure
// 1 layout, shapes from the sample zone map) with a 3-pixel band: the inner
// copy of a loop smaller than the band turned inside out after snapping (its
// zones on the wrong sides, 140-191 triangles of the sample map claimed twice);
// such a loop's band is now narrowed, then left single.
TEST(TinZones, EveryTriangleHasOneZone) {
    const zones::Palette palette = zones::test::testPalette(3);
    // '#' borderline pixel, '1' island, '.' the zone around it.
    const std::vector<std::vector<std::string>> islands = {
        {"...#....", "...####.", "..###1#.", "..#######"},
        {"....#....", "...###...", "....#####", "....#111##", "....##111#", ".....####."},
        {"...##.", "..#1#.", ".#11#.", "##11#.", ".###.."},
        {"...#...", "..###..", ".#11#..", "#111#..", "#11#...", "###...."}};
    zones::ZoneMap map = zones::test::makeMap(65, 65, [&](int x, int y) {
        for (size_t k = 0; k < islands.size(); ++k)
            for (int dy : {0, 28}) {
                const int x0 = 4 + 15 * int(k), y0 = 6 + dy;
                const auto& rows = islands[k];
                if (y >= y0 && y < y0 + int(rows.size()) && x >= x0 &&
                    x < x0 + int(rows[size_t(y - y0)].size())) {
                    const char c = rows[size_t(y - y0)][size_t(x - x0)];
                    if (c == '#') return int(zones::kBorderlinePixel);
                    if (c == '1') return 1;
                    return dy == 0 ? 0 : 2;
                }
            }
        if (y == 24) return int(zones::kBorderlinePixel);
        return y > 24 ? 2 : 0;
    });
    map.layout = zones::ZoneLayout::Borderlines;
    // Touching layout: strips of one pixel along the frame, so that their
    // borderlines snap onto the grid's border, where the frame edge carries the
    // outermost pixels' zone and the triangle inside belongs to the next one.
    const zones::ZoneMap frame = zones::test::makeMap(65, 65, [](int x, int y) {
        if (x == 64 && y >= 10 && y < 14) return 1;  // zone 1 strip on zone 0's edge
        if (y == 0 && x >= 20 && x < 26) return 2;
        if (x == 0 && y >= 40 && y < 47) return 0;   // zone 0 strip on zone 2's edge
        if (x >= 40 && y >= 12 && y < 20) return 1;  // a region meeting the frame beside it
        return y >= 30 ? 2 : 0;
    });
    for (const zones::ZoneMap* m : std::array<const zones::ZoneMap*, 2>{&map, &frame}) {
        for (int grid : {65, 129}) {
            SCOPED_TRACE(testing::Message()
                         << (m == &map ? "islands" : "frame") << ", grid " << grid);
            const zones::Borderlines lines =
                tin::gridBorderlines(*m, palette, {.epsilon = 0.5, .bandWidth = 3.0}, grid, grid);
            const tin::Constraints c = tin::constraintsFromBorderlines(lines, grid, grid);
            EXPECT_FALSE(c.bands.empty());
            const tin::TinResult r = tin::buildTin(fractal(grid), c, {.maxErrorRel = 0.005});
            EXPECT_EQ(r.stats.zoneConflicts, 0);
            std::map<int32_t, std::array<int32_t, 2>> bands;
            for (const auto& b : c.bands) bands[b.zone] = {b.first, b.second};
            for (size_t t = 0; t < r.mesh.triangles.size(); ++t) {
                for (int k = 0; k < 3; ++k) {
                    if (r.mesh.constrainedEdges[t] & (1u << k)) {
                        EXPECT_EQ(r.mesh.edgeZones[t][size_t(k)], r.mesh.zone[t])
                            << "triangle " << t;
                    }
                }
                auto it = bands.find(r.mesh.zone[t]);
                const std::array<int32_t, 2> expected =
                    it != bands.end() ? it->second
                                      : std::array<int32_t, 2>{r.mesh.zone[t], r.mesh.zone[t]};
                EXPECT_EQ(r.mesh.surfaces[t], expected);
            }
            EXPECT_GE(tin::zoneAgreement(r.mesh, *m).fraction(), 0.99);
        }
    }
}

TEST(TinZones, AgreementFailsWithoutBorderlines) {
    // The same check on a mesh that ignores the zones (everything zone 0) must fail.
    const zones::ZoneMap map = threeZones(65);
    const tin::TinResult r = tin::buildTin(fractal(65), {}, {.maxErrorRel = 0.005});
    EXPECT_LT(independentAgreement(r.mesh, map), 0.9);
    EXPECT_LT(tin::zoneAgreement(r.mesh, map).fraction(), 0.9);
}

TEST(TinZones, MapToGridPutsPixelCentresOnSamples) {
    const tin::Constraints::Vertex a = tin::mapToGrid(0.5, 0.5, 65, 33, 129, 65);
    EXPECT_DOUBLE_EQ(a.x, 0.0);
    EXPECT_DOUBLE_EQ(a.y, 0.0);
    const tin::Constraints::Vertex b = tin::mapToGrid(64.5, 32.5, 65, 33, 129, 65);
    EXPECT_DOUBLE_EQ(b.x, 128.0);
    EXPECT_DOUBLE_EQ(b.y, 64.0);
    zones::Borderlines tiny;
    tiny.mapWidth = 1;
    tiny.mapHeight = 5;
    EXPECT_THROW(tin::constraintsFromBorderlines(tiny, 65, 65), Error);
}

// The OBJ's UVs are the renderer's zone tiles: a triangle of surface s at grid
// (x, y) has u = (x (mapW - 1) / (gridW - 1) + 0.5) / tileSize(s) (the terrain
// shader's zone-map position over the tile's size), each material its own
// period; a band the mean of its two surfaces' periods.
TEST(TinZones, ObjUvsRepeatWithEachTilesPeriod) {
    const std::string dir = ::testing::TempDir() + "/tin_zones_uvs";
    std::filesystem::create_directories(dir);
    zones::Palette palette = zones::test::testPalette(3);
    const float sizes[3] = {8.0f, 12.0f, 20.0f};
    for (int k = 0; k < 3; ++k) palette.surfaces[size_t(k)].tileSize = sizes[k];
    // A map of 33 x 33 pixels on a 65 x 65 grid: two samples per pixel.
    const zones::ZoneMap map = threeZones(33);
    terrain::Heightfield field = fractal(65);
    field.setSpacing(3.0f, 3.0f);
    const zones::Borderlines lines =
        tin::gridBorderlines(map, palette, {.epsilon = 0.5, .bandWidth = 2.0}, 65, 65);
    const tin::TinResult r =
        tin::buildTin(field, tin::constraintsFromBorderlines(lines, 65, 65), {.maxErrorRel = 0.01});
    const std::string obj = dir + "/mesh.obj";
    tin::writeObj(obj, r.mesh, tin::zoneMaterials(obj, r.mesh, palette, 33, 33));
    const tin::ObjFile back = tin::readObj(obj);
    ASSERT_EQ(back.faces.size(), r.mesh.triangles.size());
    std::map<std::string, int> faces;
    std::set<std::pair<int32_t, int32_t>> uvsOfVertex;  // (vertex, vt) pairs
    for (size_t f = 0; f < back.faces.size(); ++f) {
        const std::string& name = back.faceMaterials[f];
        ++faces[name];
        // zone_<s> or band_<a>_<b>: the tile size of the material.
        double size = 0.0;
        int a = -1, b = -1;
        if (std::sscanf(name.c_str(), "band_%d_%d", &a, &b) == 2)
            size = 0.5 * (sizes[a] + sizes[b]);
        else if (std::sscanf(name.c_str(), "zone_%d", &a) == 1)
            size = sizes[a];
        ASSERT_GT(size, 0.0) << name;
        for (int k = 0; k < 3; ++k) {
            const int32_t v = back.faces[f][size_t(k)], t = back.faceUvs[f][size_t(k)];
            ASSERT_GE(t, 0);
            uvsOfVertex.insert({v, t});
            const double x = back.positions[size_t(v)][0] / 3.0,
                         y = back.positions[size_t(v)][2] / 3.0;
            const double u = (x * 32.0 / 64.0 + 0.5) / size, w = (y * 32.0 / 64.0 + 0.5) / size;
            EXPECT_NEAR(back.uvs[size_t(t)][0], u, 1e-5 * std::max(1.0, u)) << name;
            EXPECT_NEAR(back.uvs[size_t(t)][1], w, 1e-5 * std::max(1.0, w)) << name;
        }
    }
    // Every surface and at least one band has triangles, so three or more periods
    // were checked, and vertices on borderlines carry one UV per period around them.
    EXPECT_GE(faces.size(), 4u);
    EXPECT_GT(uvsOfVertex.size(), r.mesh.vertices.size());
    EXPECT_GT(back.uvs.size(), r.mesh.vertices.size());
}

TEST(TinZones, BlendedTilesAndMaterials) {
    const std::string dir = ::testing::TempDir() + "/tin_zones_materials";
    std::filesystem::create_directories(dir + "/tiles");
    // Two flat tiles: the blend with no height blending is their mean.
    zones::TileImage red{.size = 16, .rgba = {}}, blue{.size = 16, .rgba = {}};
    for (int k = 0; k < 16 * 16; ++k) {
        red.rgba.insert(red.rgba.end(), {200, 0, 0, 100});
        blue.rgba.insert(blue.rgba.end(), {0, 0, 100, 200});
    }
    writeFileAtomic(dir + "/tiles/red.png", zones::encodeTilePng(red));
    writeFileAtomic(dir + "/tiles/blue.png", zones::encodeTilePng(blue));
    const zones::TileImage readBack = zones::loadTile(dir + "/tiles/red.png");
    EXPECT_EQ(readBack.size, 16);
    EXPECT_EQ(readBack.rgba, red.rgba);
    const zones::TileImage mean = zones::blendTiles(red, blue, 0.0f);
    EXPECT_EQ(mean.rgba[0], 100);
    EXPECT_EQ(mean.rgba[2], 50);
    EXPECT_EQ(mean.rgba[3], 150);
    // Height blending moves the blend towards the higher tile (blue).
    const zones::TileImage shifted = zones::blendTiles(red, blue, 1.0f);
    EXPECT_LT(shifted.rgba[0], 100);
    EXPECT_GT(shifted.rgba[2], 50);
    EXPECT_THROW(
        zones::blendTiles(red, zones::TileImage{.size = 8, .rgba = std::vector<uint8_t>(8 * 8 * 4)},
                          0.0f),
        Error);
    EXPECT_THROW(zones::loadTile(dir + "/tiles/none.png"), Error);

    zones::Palette palette = zones::test::testPalette(3);
    palette.surfaces[0].tile = dir + "/tiles/red.png";
    palette.surfaces[1].tile = dir + "/tiles/blue.png";
    palette.surfaces[2].tile = dir + "/tiles/red.png";
    const zones::Borderlines lines =
        tin::gridBorderlines(threeZones(65), palette, {.bandWidth = 2.0}, 65, 65);
    const tin::TinResult r = tin::buildTin(
        fractal(65), tin::constraintsFromBorderlines(lines, 65, 65), {.maxErrorRel = 0.01});
    const std::string obj = dir + "/out/mesh.obj";
    std::filesystem::create_directories(dir + "/out");
    tin::writeObj(obj, r.mesh, tin::zoneMaterials(obj, r.mesh, palette, 65, 65));
    const tin::ObjFile parsed = tin::readObj(obj);
    EXPECT_EQ(parsed.faces.size(), r.mesh.triangles.size());
    const auto textures = tin::readMtlTextures(dir + "/out/" + parsed.mtllib);
    std::set<std::string> materials(parsed.faceMaterials.begin(), parsed.faceMaterials.end());
    int bands = 0;
    for (const std::string& name : materials) {
        ASSERT_TRUE(textures.count(name)) << name;
        const std::string image = textures.at(name);
        ASSERT_FALSE(image.empty()) << name;
        // Relative to the MTL's folder, and there.
        EXPECT_TRUE(std::filesystem::path(image).is_relative()) << image;
        EXPECT_TRUE(std::filesystem::exists(dir + "/out/" + image)) << image;
        if (name.rfind("band_", 0) == 0) {
            ++bands;
            EXPECT_EQ(zones::loadTile(dir + "/out/" + image).size, 16);
        }
    }
    EXPECT_GE(bands, 2);
}

}  // namespace
