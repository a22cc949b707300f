// Tiles streamed from a tile file while the camera moves: every frame
// conforms whatever has arrived, the stream converges to the in-memory
// triangles when the camera stops, the budget holds while the camera crosses
// the terrain (bytes held, and the process's resident memory), and a corrupt
// tile is an error, not a crash.
#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/sbt/Refiner.h>
#include <sierra/sbt/TileCache.h>
#include <sierra/sbt/TileFile.h>
#include <sierra/sbt/TiledRefiner.h>
#include <sierra/sbt/VertexErrors.h>
#include <sierra/terrain/DiamondSquare.h>
#include <sierra/terrain/GridReader.h>

#include "sbt_mesh_checks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>

namespace sierra::test {
namespace {

terrain::Heightfield rough(int side, uint32_t seed) {
    terrain::Heightfield f =
        terrain::generateDiamondSquare({.size = side, .seed = seed, .roughness = 0.85f});
    f.setVerticalScale(0.2f * float(side));
    return f;
}

std::string build(const terrain::Heightfield& field, int k, const std::string& name) {
    const std::string path = testing::TempDir() + "/" + name + ".sierra";
    sbt::buildTileFile(
        *terrain::memoryGridReader(field), path,
        {.k = k, .heights = sbt::TileHeights::Float32, .verticalScale = field.verticalScale()});
    return path;
}

sbt::ViewParams view(float x, float y, float z, float tx, float tz, float tau, float far) {
    return sbt::lookAtView({x, y, z}, {tx, 0.0f, tz}, 0.9f, 16.0f / 9.0f, 1080.0f, 0.5f, far, tau,
                           true);
}

std::vector<Tri> sortedTriangles(std::vector<Tri> tris) {
    for (Tri& t : tris) std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    std::sort(tris.begin(), tris.end());
    return tris;
}

// The process's resident memory now, bytes (VmRSS).
uint64_t residentBytes() {
    std::ifstream in("/proc/self/status");
    std::string key;
    while (in >> key) {
        if (key == "VmRSS:") {
            uint64_t kb = 0;
            in >> kb;
            return kb * 1024;
        }
        in.ignore(1 << 12, '\n');
    }
    return 0;
}

TEST(TileCache, StreamsToTheInMemoryTrianglesAndConformsMeanwhile) {
    const int side = 257;
    const terrain::Heightfield field = rough(side, 3);
    const std::string path = build(field, 4, "stream");
    const sbt::TileFile file(path);
    sbt::TileCache cache(file, {.budgetBytes = 64u << 20, .loaderThreads = 2});
    sbt::TiledRefiner tiled(cache);
    const sbt::ViewParams v = view(40.0f, 30.0f, 20.0f, 150.0f, 180.0f, 1.0f, 2000.0f);
    sbt::TiledMesh mesh;
    int coarseFrames = 0;
    for (int frame = 0; frame < 200; ++frame) {
        cache.beginFrame();
        tiled.refineView(v, mesh);
        expectConforming(sbt::decodeTiledStrip(mesh.strip, side), side, false);
        if (mesh.coarseTiles == 0) break;
        ++coarseFrames;
        cache.wantForView(tiled, v.eye, v.eye);
        if (frame % 4 == 3) cache.waitIdle();  // let the loaders catch up now and then
    }
    EXPECT_GT(coarseFrames, 0) << "the first frame has only the coarse section";
    EXPECT_EQ(mesh.coarseTiles, 0) << "the wants converge";
    const sbt::VertexErrors errors = sbt::computeVertexErrors(field, 1);
    sbt::Refiner refiner(field, errors, {.threads = 1});
    sbt::StripMesh reference;
    refiner.refineViewReference(v, reference);
    EXPECT_EQ(sortedTriangles(sbt::decodeTiledStrip(mesh.strip, side)),
              sortedTriangles(sbt::decodeStrip(reference.indices)));
    EXPECT_GT(cache.stats().tilesRead, 0);
    std::remove(path.c_str());
}

TEST(TileCache, TheBudgetHoldsWhileTheCameraCrossesTheTerrain) {
    // 4097^2 samples in the default tiles of 256 cells, under 64 MiB (about
    // 80 whole tiles of the 256): low over the ground from one corner to the
    // other. The loaders catch up after every frame (as on a machine where
    // they keep up), which holds the most at once.
    const int side = 4097;
    const std::string path = build(rough(side, 5), 8, "cross");
    const sbt::TileFile file(path);
    const uint64_t budget = uint64_t(64) << 20;
    const uint64_t before = residentBytes();
    uint64_t highest = before;
    {
        sbt::TileCache cache(file, {.budgetBytes = budget, .loaderThreads = 2});
        sbt::TiledRefiner tiled(cache);
        sbt::TiledMesh mesh;
        const int frames = 150;
        for (int f = 0; f < frames; ++f) {
            const float s = float(f) / float(frames - 1), x = 100.0f + s * 3900.0f;
            const float eyeY = 0.2f * float(side) * 0.6f + 40.0f;
            const sbt::ViewParams v = view(x, eyeY, x, x + 300.0f, x + 300.0f, 1.0f, 6000.0f);
            cache.beginFrame();
            tiled.refineView(v, mesh);
            const std::array<float, 3> ahead{x + 100.0f, eyeY, x + 100.0f};
            cache.wantForView(tiled, v.eye, ahead);
            cache.waitIdle();
            const sbt::TileCacheStats st = cache.stats();
            ASSERT_LE(st.residentBytes, budget) << "frame " << f;
            ASSERT_LE(st.peakBytes, budget) << "frame " << f;
            highest = std::max(highest, residentBytes());
        }
        const sbt::TileCacheStats st = cache.stats();
        EXPECT_GT(st.evicted, 0) << "crossing the terrain does not fit: tiles behind are dropped";
        EXPECT_GT(st.tilesRead, 100);
        std::printf(
            "tile cache: %lld tiles read, %lld evicted, peak %.1f MiB of %.0f MiB; process "
            "memory +%.1f MiB\n",
            (long long)st.tilesRead, (long long)st.evicted, double(st.peakBytes) / 1048576.0,
            double(budget) / 1048576.0, double(highest - before) / 1048576.0);
    }
#if !defined(__SANITIZE_ADDRESS__)
    // The cache's bytes, the frame's mesh and the allocator's slack: within
    // the budget and 32 MiB.
    EXPECT_LE(highest - before, budget + (uint64_t(32) << 20));
#endif
    std::remove(path.c_str());
}

TEST(TileCache, ACorruptTileIsAnErrorOnTheRenderThread) {
    const int side = 129;
    const std::string path = build(rough(side, 7), 4, "corrupt");
    std::vector<uint8_t> bytes = readFileBytes(path);
    for (size_t at = bytes.size() - 4096; at < bytes.size(); at += 7) bytes[at] ^= 0x5a;
    writeFileAtomic(path, bytes);
    const sbt::TileFile file(path);  // the header, index and coarse section are whole
    sbt::TileCache cache(file, {.budgetBytes = 16u << 20, .loaderThreads = 1});
    for (int ty = 0; ty < file.info().tilesPerSide(); ++ty)
        for (int tx = 0; tx < file.info().tilesPerSide(); ++tx) cache.want(tx, ty, 8);
    try {
        cache.waitIdle();
        ADD_FAILURE() << "the damaged tiles were taken";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("corrupt"), std::string::npos) << e.what();
    }
    std::remove(path.c_str());
}

}  // namespace
}  // namespace sierra::test
