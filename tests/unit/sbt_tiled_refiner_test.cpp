// The tiled refinement against the in-memory one: with every tile resident
// the same triangles in the same order; with tiles missing or partly loaded
// a conforming mesh, drawn coarser where the data stops.
#include <sierra/sbt/Refiner.h>
#include <sierra/sbt/TiledRefiner.h>
#include <sierra/sbt/VertexErrors.h>
#include <sierra/terrain/DiamondSquare.h>

#include "sbt_mesh_checks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <vector>

namespace sierra::test {
namespace {

struct Grid {
    terrain::Heightfield field;
    sbt::VertexErrors errors;
};

Grid makeGrid(int side, uint32_t seed) {
    Grid g{terrain::generateDiamondSquare({.size = side, .seed = seed, .roughness = 0.9f}), {}};
    g.field.setVerticalScale(0.3f * float(side));
    g.errors = sbt::computeVertexErrors(g.field, 1);
    return g;
}

TEST(TiledRefiner, EveryTileResidentGivesTheInMemoryTriangles) {
    std::mt19937 random(5);
    for (int side : {33, 129, 257}) {
        const Grid g = makeGrid(side, uint32_t(side));
        sbt::Refiner refiner(g.field, g.errors, {.threads = 1});
        const int n = g.errors.n;
        for (int k : {1, 3, n}) {
            if (k > n) continue;
            sbt::InMemoryTiles tiles(g.field, g.errors, k);
            sbt::TiledRefiner tiled(tiles);
            for (float tau : {1.0f, 4.0f, 8.0f})
                for (bool cull : {true, false}) {
                    const sbt::ViewParams view = randomView(random, side, tau, cull);
                    sbt::StripMesh reference;
                    refiner.refineViewReference(view, reference);
                    sbt::TiledMesh mesh;
                    tiled.refineView(view, mesh);
                    SCOPED_TRACE(testing::Message() << side << "^2, k " << k << ", tau " << tau
                                                    << (cull ? ", culled" : ""));
                    EXPECT_EQ(mesh.triangleCount, reference.triangleCount);
                    EXPECT_EQ(mesh.culledSubtrees, reference.culledSubtrees);
                    EXPECT_EQ(mesh.coarseTiles, 0);
                    EXPECT_EQ(canonical(sbt::decodeTiledStrip(mesh.strip, side)),
                              canonical(sbt::decodeStrip(reference.indices)))
                        << "the same triangles in the same order";
                }
        }
    }
}

TEST(TiledRefiner, MissingTilesLeaveAConformingMesh) {
    std::mt19937 random(9);
    const int side = 257;
    const Grid g = makeGrid(side, 3);
    for (int k : {2, 4, 6}) {
        sbt::InMemoryTiles tiles(g.field, g.errors, k);
        sbt::TiledRefiner tiled(tiles);
        const int t = tiles.tilesPerSide();
        std::uniform_int_distribution<int> depth(0, 2 * k);
        for (int round = 0; round < 6; ++round) {
            for (int ty = 0; ty < t; ++ty)
                for (int tx = 0; tx < t; ++tx) tiles.setResident(tx, ty, depth(random));
            const sbt::ViewParams view = randomView(random, side, 1.0f, false);
            sbt::TiledMesh mesh;
            tiled.refineView(view, mesh);
            SCOPED_TRACE(testing::Message() << "k " << k << ", round " << round);
            // Without culling the mesh covers the square: every interior edge
            // shared by two triangles, no T-junction, however little is loaded.
            expectConforming(sbt::decodeTiledStrip(mesh.strip, side), side, true);
            EXPECT_GT(mesh.coarseTiles, 0) << "random depths leave a tile short";
            // The usable levels: never above what is resident, and edge
            // neighbours at most one level apart.
            const std::vector<int>& usable = tiled.usableLevels();
            for (int ty = 0; ty < t; ++ty)
                for (int tx = 0; tx < t; ++tx) {
                    const int d = usable[size_t(ty * t + tx)];
                    EXPECT_LE(d, tiles.residentLevels(tx, ty));
                    if (tx + 1 < t) {
                        EXPECT_LE(std::abs(d - usable[size_t(ty * t + tx + 1)]), 1);
                    }
                    if (ty + 1 < t) {
                        EXPECT_LE(std::abs(d - usable[size_t((ty + 1) * t + tx)]), 1);
                    }
                }
        }
    }
}

// The walk takes its tests in float and falls back to double inside a guard
// band: eyes placed a few float steps from where a vertex's reach equals its
// distance, where the float test and the double one disagree, must still
// give the reference's triangles.
TEST(TiledRefiner, TiesOnTheFloatGuardBandAreDecidedAsTheReference) {
    const int side = 257;
    const Grid g = makeGrid(side, 21);
    sbt::Refiner refiner(g.field, g.errors, {.threads = 1});
    sbt::InMemoryTiles tiles(g.field, g.errors, 4);
    sbt::TiledRefiner tiled(tiles);
    std::mt19937 random(9);
    std::uniform_int_distribution<int> pick(1, side - 2);
    auto viewFrom = [&](const std::array<float, 3>& eye, const std::array<float, 3>& target,
                        bool cull) {
        return sbt::lookAtView(eye, target, 0.9f, 16.0f / 9.0f, 720.0f, 0.1f, 10.0f * side, 0.5f,
                               cull);
    };
    const sbt::ViewParams probe = viewFrom({0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, false);
    const double kE = double(probe.lambda) / double(probe.tau);
    const float vs = g.field.verticalScale();
    int ties = 0;
    for (int trial = 0; trial < 400 && ties < 24; ++trial) {
        const int i = pick(random), j = pick(random);
        const size_t at = size_t(j) * side + size_t(i);
        const float e = g.errors.error[at], r = g.errors.radius[at], h = g.field.samples()[at];
        const double reach = kE * double(e) + double(r);
        if (reach <= 0.0 || reach > 4.0 * side) continue;
        // The eye off the vertex along (1, 1, 1) at about its reach, x stepped
        // float by float, until the float test and the double one disagree
        // (the roundings of three squared differences add up).
        const float y = h * vs, off = float(reach / std::sqrt(3.0));
        const float ey = y + off, ez = float(j) + off;
        float ex = float(i) + off;
        for (int step = 0; step < 64; ++step) ex = std::nextafter(ex, 0.0f);
        bool found = false;
        for (int step = 0; step < 128; ++step) {
            const float dxf = float(i) - ex, dyf = y - ey, dzf = float(j) - ez;
            const float reachf = float(kE) * e + r;
            const float r2 = reachf * reachf, d2 = dxf * dxf + dyf * dyf + dzf * dzf;
            const double dx = double(i) - double(ex), dy = double(h) * double(vs) - double(ey),
                         dz = double(j) - double(ez);
            found = r2 != d2 && (r2 > d2) != (reach * reach > dx * dx + dy * dy + dz * dz);
            if (found) break;
            ex = std::nextafter(ex, 1e9f);
        }
        if (!found) continue;
        const std::array<float, 3> eye{ex, ey, ez}, target{float(i), y, float(j)};
        const sbt::ViewParams view = viewFrom(eye, target, ties % 2 == 0);
        sbt::StripMesh reference;
        refiner.refineViewReference(view, reference);
        sbt::TiledMesh mesh;
        tiled.refineView(view, mesh);
        SCOPED_TRACE(testing::Message() << "vertex " << i << ", " << j);
        EXPECT_EQ(canonical(sbt::decodeTiledStrip(mesh.strip, side)),
                  canonical(sbt::decodeStrip(reference.indices)));
        ++ties;
    }
    EXPECT_GE(ties, 24) << "eyes where float and double disagree";
}

TEST(TiledRefiner, NoTileLoadedDrawsEachTileAsItsTwoTriangles) {
    const int side = 129;
    const Grid g = makeGrid(side, 8);
    sbt::InMemoryTiles tiles(g.field, g.errors, 4);  // 8 x 8 tiles of 16 cells
    tiles.setAllResident(0);
    sbt::TiledRefiner tiled(tiles);
    // So close and so fine that the in-memory path splits everywhere it can.
    const sbt::ViewParams view = sbt::lookAtView({64.0f, 30.0f, 64.0f}, {64.0f, 0.0f, 70.0f}, 1.2f,
                                                 1.0f, 4000.0f, 0.5f, 2000.0f, 0.01f, false);
    sbt::TiledMesh mesh;
    tiled.refineView(view, mesh);
    EXPECT_EQ(mesh.triangleCount, 2 * 8 * 8) << "the tile corners alone are readable";
    EXPECT_EQ(mesh.coarseTiles, 8 * 8);
    expectConforming(sbt::decodeTiledStrip(mesh.strip, side), side, true);
    // One tile fully loaded in the middle: it refines, its neighbours step down to it.
    tiles.setResident(3, 3, 8);
    tiled.refineView(view, mesh);
    EXPECT_GT(mesh.triangleCount, 2 * 8 * 8);
    EXPECT_EQ(tiled.usableLevels()[3 * 8 + 3], 1) << "one level above its unloaded neighbours";
    expectConforming(sbt::decodeTiledStrip(mesh.strip, side), side, true);
}

}  // namespace
}  // namespace sierra::test
