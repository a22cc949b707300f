// The tile file against the grid in memory: the records it stores and
// recomputes are computeVertexErrors' bit for bit, refining it gives
// Refiner's triangles, partial loads conform, padding and no-data are kept,
// and a damaged file is refused or read unchanged, never misread.
#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/sbt/Refiner.h>
#include <sierra/sbt/TileFile.h>
#include <sierra/sbt/TiledRefiner.h>
#include <sierra/sbt/VertexErrors.h>
#include <sierra/terrain/DiamondSquare.h>
#include <sierra/terrain/GridReader.h>
#include <sierra/terrain/Padding.h>

#include "sbt_mesh_checks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace sierra::test {
namespace {

terrain::Heightfield roughField(int width, int height, uint32_t seed) {
    const int side = std::max(width, height);
    terrain::Heightfield square = terrain::generateDiamondSquare(
        {.size = terrain::paddedSide(side), .seed = seed, .roughness = 0.9f});
    terrain::Heightfield field(width, height);
    for (int j = 0; j < height; ++j)
        for (int i = 0; i < width; ++i) field.at(i, j) = square.at(i, j);
    field.setSpacing(1.5f, 0.75f);
    field.setVerticalScale(0.3f * float(side));
    return field;
}

std::string buildFile(const terrain::Heightfield& field, int k, sbt::TileHeights heights,
                      const std::string& name) {
    const std::string path = testing::TempDir() + "/" + name + ".sierra";
    const auto reader = terrain::memoryGridReader(field);
    sbt::buildTileFile(
        *reader, path,
        {.k = k, .heights = heights, .verticalScale = field.verticalScale(), .threads = 2});
    return path;
}

// The (2^n+1)^2 field of the heights the file stores, read back through FileTiles.
terrain::Heightfield storedField(const sbt::FileTiles& tiles, const sbt::TileFileInfo& info) {
    const int side = int(info.gridSide());
    terrain::Heightfield out(side, side);
    out.setSpacing(info.spacingX, info.spacingZ);
    out.setVerticalScale(info.verticalScale);
    for (int j = 0; j < side; ++j)
        for (int i = 0; i < side; ++i) out.at(i, j) = tiles.vertex(uint32_t(i), uint32_t(j)).height;
    return out;
}

TEST(TileFile, RecordsAreTheWholeGridsErrorsBitForBit) {
    for (int side : {33, 129, 257}) {
        const terrain::Heightfield field = roughField(side, side, uint32_t(side));
        const int n = terrain::paddedSide(side) == side ? std::countr_zero(unsigned(side - 1)) : 0;
        for (int k : {1, 3, n})
            for (sbt::TileHeights heights : {sbt::TileHeights::Float32, sbt::TileHeights::Int16}) {
                SCOPED_TRACE(testing::Message()
                             << side << "^2, k " << k
                             << (heights == sbt::TileHeights::Int16 ? ", int16" : ", float"));
                const std::string path = buildFile(field, k, heights, "records");
                const sbt::TileFile file(path);
                ASSERT_EQ(file.info().n, n);
                ASSERT_EQ(file.info().k, k);
                sbt::FileTiles tiles(file);
                tiles.loadAll(2 * k);
                const terrain::Heightfield stored = storedField(tiles, file.info());
                const double step =
                    heights == sbt::TileHeights::Int16 ? file.info().heightScale : 0.0;
                for (int j = 0; j < side; ++j)
                    for (int i = 0; i < side; ++i)
                        ASSERT_LE(
                            std::abs(double(stored.at(i, j)) - double(field.at(i, j))),
                            0.5 * step * 1.0001 + 4.0 * FLT_EPSILON * std::abs(field.at(i, j)))
                            << "sample " << i << ", " << j;
                // Errors and radii of the whole grid of those heights, stored
                // or recomputed on load: the same floats.
                const sbt::VertexErrors want = sbt::computeVertexErrors(stored, 1);
                for (int j = 0; j < side; ++j)
                    for (int i = 0; i < side; ++i) {
                        const sbt::VertexRecord r = tiles.vertex(uint32_t(i), uint32_t(j));
                        const size_t m = size_t(j) * size_t(side) + size_t(i);
                        ASSERT_EQ(r.error, want.error[m]) << "error at " << i << ", " << j;
                        ASSERT_EQ(r.radius, want.radius[m]) << "radius at " << i << ", " << j;
                    }
                std::remove(path.c_str());
            }
    }
}

TEST(TileFile, RefiningTheFileGivesTheInMemoryTriangles) {
    std::mt19937 random(11);
    const int side = 257;
    const terrain::Heightfield field = roughField(side, side, 4);
    const sbt::VertexErrors errors = sbt::computeVertexErrors(field, 1);
    sbt::Refiner refiner(field, errors, {.threads = 1});
    for (int k : {2, 5}) {
        const std::string path = buildFile(field, k, sbt::TileHeights::Float32, "triangles");
        const sbt::TileFile file(path);
        sbt::FileTiles tiles(file);
        tiles.loadAll(2 * k);
        sbt::TiledRefiner tiled(tiles);
        for (float tau : {1.0f, 4.0f})
            for (bool cull : {true, false}) {
                const sbt::ViewParams view = randomView(random, side, tau, cull);
                sbt::StripMesh reference;
                refiner.refineViewReference(view, reference);
                sbt::TiledMesh mesh;
                tiled.refineView(view, mesh);
                SCOPED_TRACE(testing::Message() << "k " << k << ", tau " << tau);
                EXPECT_EQ(mesh.triangleCount, reference.triangleCount);
                EXPECT_EQ(mesh.coarseTiles, 0);
                EXPECT_EQ(canonical(sbt::decodeTiledStrip(mesh.strip, side)),
                          canonical(sbt::decodeStrip(reference.indices)));
            }
        std::remove(path.c_str());
    }
}

TEST(TileFile, PartlyReadTilesLeaveAConformingMesh) {
    std::mt19937 random(2);
    const int side = 257;
    const terrain::Heightfield field = roughField(side, side, 6);
    const std::string path = buildFile(field, 4, sbt::TileHeights::Int16, "partial");
    const sbt::TileFile file(path);
    const int P = file.info().tilesPerSide();
    std::uniform_int_distribution<int> chunks(0, file.chunkCount());
    for (int round = 0; round < 4; ++round) {
        sbt::FileTiles tiles(file);
        for (int ty = 0; ty < P; ++ty)
            for (int tx = 0; tx < P; ++tx) {
                const int c = chunks(random);
                if (c > 0) tiles.load(tx, ty, file.levelsAfterChunks(c));
                EXPECT_EQ(tiles.residentLevels(tx, ty), file.levelsAfterChunks(c));
            }
        sbt::TiledRefiner tiled(tiles);
        sbt::TiledMesh mesh;
        tiled.refineView(randomView(random, side, 1.0f, false), mesh);
        SCOPED_TRACE(testing::Message() << "round " << round);
        expectConforming(sbt::decodeTiledStrip(mesh.strip, side), side, true);
        EXPECT_GT(mesh.coarseTiles, 0);
        // A partial read is a prefix of the whole tile.
        sbt::TileData part, whole;
        file.readTile(1, 2, 2, part);
        file.readTile(1, 2, file.chunkCount(), whole);
        EXPECT_EQ(part.levels, 2);
        EXPECT_LT(file.tileBytes(1, 2, 2), file.tileBytes(1, 2, file.chunkCount()));
        int same = 0, set = 0;
        for (size_t m = 0; m < part.height.size(); ++m)
            if (part.error[m] != 0.0f || part.height[m] != 0.0f) {
                ++set;
                same += part.height[m] == whole.height[m] && part.error[m] == whole.error[m] &&
                        part.radius[m] == whole.radius[m];
            }
        EXPECT_GT(set, 4);
        EXPECT_EQ(same, set);
    }
    std::remove(path.c_str());
}

TEST(TileFile, PaddingIsNotStoredAndNoDataIsMasked) {
    // 150 x 70 samples with a hole: a 257^2 grid, tiles of 32 cells.
    terrain::Heightfield field = roughField(150, 70, 9);
    std::vector<uint8_t> mask(size_t(150) * 70, 1);
    for (int j = 20; j < 30; ++j)
        for (int i = 40; i < 60; ++i) mask[size_t(j) * 150 + size_t(i)] = 0;
    field.setMask(mask);
    const std::string path = buildFile(field, 5, sbt::TileHeights::Float32, "padded");
    const sbt::TileFile file(path);
    EXPECT_EQ(file.info().width, 150);
    EXPECT_EQ(file.info().height, 70);
    EXPECT_TRUE(file.info().hasNoData);
    const int P = file.info().tilesPerSide();
    ASSERT_EQ(P, 8);
    for (int ty = 0; ty < P; ++ty)
        for (int tx = 0; tx < P; ++tx)
            EXPECT_EQ(file.stored(tx, ty), tx * 32 < 149 && ty * 32 < 69) << tx << ", " << ty;

    // The in-memory grid the file stands for: the hole filled with the lowest
    // real height, padded by edge clamping.
    terrain::Heightfield filled = field;
    const float low = field.range().first;
    for (int j = 0; j < 70; ++j)
        for (int i = 0; i < 150; ++i)
            if (!field.valid(i, j)) filled.at(i, j) = low;
    filled.setMask({});
    const terrain::Heightfield padded = terrain::padToPowerOfTwoPlusOne(filled);
    const sbt::VertexErrors want = sbt::computeVertexErrors(padded, 1);
    sbt::FileTiles tiles(file);
    tiles.loadAll(10);
    for (int j = 0; j <= 3 * 32; ++j)
        for (int i = 0; i <= 5 * 32; ++i) {
            if (i % 32 == 0 && j % 32 == 0) continue;  // corners: the coarse section's
            const sbt::VertexRecord r = tiles.vertex(uint32_t(i), uint32_t(j));
            const size_t m = size_t(j) * 257 + size_t(i);
            ASSERT_EQ(r.height, padded.samples()[m]) << i << ", " << j;
            ASSERT_EQ(r.error, want.error[m]) << i << ", " << j;
            ASSERT_EQ(r.radius, want.radius[m]) << i << ", " << j;
        }
    // Masks: the hole and the padding are not real data.
    for (int ty = 0; ty < 3; ++ty)
        for (int tx = 0; tx < 5; ++tx) {
            sbt::TileData d;
            file.readTile(tx, ty, file.chunkCount(), d);
            const bool inside =
                (tx + 1) * 32 < 150 && (ty + 1) * 32 < 70 &&
                !(tx * 32 <= 60 && (tx + 1) * 32 >= 40 && ty * 32 <= 30 && (ty + 1) * 32 >= 20);
            if (inside) {
                EXPECT_TRUE(d.mask.empty()) << tx << ", " << ty;
                continue;
            }
            ASSERT_EQ(d.mask.size(), size_t(33 * 33));
            for (int y = 0; y <= 32; ++y)
                for (int x = 0; x <= 32; ++x) {
                    const int i = tx * 32 + x, j = ty * 32 + y;
                    const bool real = i < 150 && j < 70 && field.valid(i, j);
                    ASSERT_EQ(d.mask[size_t(y) * 33 + size_t(x)], real ? 1 : 0) << i << ", " << j;
                }
        }
    std::remove(path.c_str());
}

TEST(TileFile, RawInt16IsStoredExactly) {
    const int w = 70, h = 65;
    std::vector<uint8_t> bytes(size_t(w) * h * 2);
    std::mt19937 random(3);
    std::vector<int> values(size_t(w) * h);
    for (size_t s = 0; s < values.size(); ++s) {
        values[s] = int(random() % 65536);
        bytes[2 * s] = uint8_t(values[s] & 0xff);
        bytes[2 * s + 1] = uint8_t(values[s] >> 8);
    }
    const std::string raw = testing::TempDir() + "/exact.r16";
    writeFileAtomic(raw, bytes);
    const std::string path = testing::TempDir() + "/exact.sierra";
    const std::vector<std::string> inputs{raw};
    const auto reader = terrain::openGridReader(inputs, {.rawWidth = w, .rawHeight = h});
    sbt::buildTileFile(*reader, path, {.k = 3});
    const sbt::TileFile file(path);
    sbt::FileTiles tiles(file);
    tiles.loadAll(6);
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i)
            ASSERT_EQ(tiles.vertex(uint32_t(i), uint32_t(j)).height,
                      float(values[size_t(j) * w + size_t(i)]))
                << i << ", " << j;
    // A wrong raw size is refused with the sizes in the message.
    try {
        terrain::openGridReader(inputs, {.rawWidth = 71, .rawHeight = 65});
        ADD_FAILURE() << "a wrong raw size was taken";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("71x65"), std::string::npos) << e.what();
    }
    std::remove(raw.c_str());
    std::remove(path.c_str());
}

// The default tile size is the one whose file is smallest: a small grid's
// partly padded edge tiles make the largest tiles cost bytes.
TEST(TileFile, TheDefaultTileSizeMakesTheSmallestFile) {
    const terrain::Heightfield field = roughField(403, 344, 17);
    const auto reader = terrain::memoryGridReader(field);
    const std::string path = testing::TempDir() + "/auto.sierra";
    uint64_t least = ~uint64_t(0), chosen = 0;
    for (int k = 4; k <= 8; ++k) {
        const sbt::TileBuildReport r = sbt::buildTileFile(*reader, path, {.k = k});
        least = std::min(least, r.fileBytes);
    }
    const sbt::TileBuildReport r = sbt::buildTileFile(*reader, path, {});
    chosen = r.fileBytes;
    EXPECT_EQ(r.info.k, sbt::autoTileLevels(403, 344, sbt::TileHeights::Int16, false));
    EXPECT_LE(double(chosen), 1.05 * double(least)) << "k " << r.info.k;
    EXPECT_LE(r.bytesPerSample, 6.0);
    EXPECT_EQ(sbt::autoTileLevels(65537, 65537, sbt::TileHeights::Int16, false), 8);
    EXPECT_EQ(sbt::autoTileLevels(20, 20, sbt::TileHeights::Float32, true), 5) << "one tile";
    std::remove(path.c_str());
}

TEST(TileFile, ADamagedFileIsRefusedOrReadUnchanged) {
    const terrain::Heightfield field = roughField(65, 65, 1);
    const std::string good = buildFile(field, 3, sbt::TileHeights::Int16, "good");
    const std::vector<uint8_t> bytes = readFileBytes(good);
    // Everything the good file reads: every stored tile, whole.
    auto readAll = [](const sbt::TileFile& f) {
        std::vector<float> all;
        for (int ty = 0; ty < f.info().tilesPerSide(); ++ty)
            for (int tx = 0; tx < f.info().tilesPerSide(); ++tx) {
                sbt::TileData d;
                f.readTile(tx, ty, f.chunkCount(), d);
                all.insert(all.end(), d.height.begin(), d.height.end());
                all.insert(all.end(), d.error.begin(), d.error.end());
                all.insert(all.end(), d.radius.begin(), d.radius.end());
            }
        return all;
    };
    const std::vector<float> want = readAll(sbt::TileFile(good));
    const std::string bad = testing::TempDir() + "/bad.sierra";
    // Truncated anywhere: refused at open, naming the file.
    for (size_t size : {size_t(0), size_t(7), size_t(100), bytes.size() / 3, bytes.size() / 2,
                        bytes.size() - 1}) {
        writeFileAtomic(bad, std::span(bytes.data(), size));
        try {
            sbt::TileFile f(bad);
            ADD_FAILURE() << "a file cut to " << size << " of " << bytes.size() << " bytes opened";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
        }
    }
    // One byte changed anywhere: refused at open or on reading the tile, or
    // (in the alignment gaps) read exactly as before.
    std::mt19937 random(8);
    int refused = 0;
    for (int trial = 0; trial < 300; ++trial) {
        std::vector<uint8_t> damaged = bytes;
        const size_t at = random() % damaged.size();
        damaged[at] ^= uint8_t(1 + random() % 255);
        writeFileAtomic(bad, damaged);
        try {
            const sbt::TileFile f(bad);
            EXPECT_EQ(readAll(f), want) << "byte " << at << " changed what is read";
        } catch (const Error& e) {
            ++refused;
            EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
        }
    }
    EXPECT_GT(refused, 250);
    std::remove(good.c_str());
    std::remove(bad.c_str());
}

}  // namespace
}  // namespace sierra::test

namespace sierra::test {
namespace {

TEST(TileFile, TheOverviewIsEveryStrideThSampleOfTheWorldHeights) {
    const terrain::Heightfield field = roughField(200, 150, 12);  // a 257^2 grid, padded
    const std::string path = buildFile(field, 4, sbt::TileHeights::Float32, "overview");
    const sbt::TileFile file(path);
    for (int maxSide : {300, 120, 60, 13}) {
        int stride = 0;
        const terrain::Heightfield o = sbt::readOverview(file, maxSide, 2, &stride);
        SCOPED_TRACE(testing::Message() << "max side " << maxSide << ", stride " << stride);
        EXPECT_LE(std::max(o.width(), o.height()), maxSide);
        EXPECT_EQ(o.width(), 199 / stride + 1);
        EXPECT_EQ(o.height(), 149 / stride + 1);
        EXPECT_FLOAT_EQ(o.spacingX(), field.spacingX() * float(stride));
        for (int j = 0; j < o.height(); ++j)
            for (int i = 0; i < o.width(); ++i)
                ASSERT_EQ(o.at(i, j), field.at(i * stride, j * stride) * field.verticalScale())
                    << i << ", " << j;
    }
    EXPECT_THROW(sbt::readOverview(file, 8), Error) << "the 17^2 tile corners do not fit in 8";
    std::remove(path.c_str());
}

TEST(TileFile, AWindowIsTheGridsSamplesWithItsNoData) {
    // 150 x 70 samples, a hole across a tile border, tiles of 16 cells.
    terrain::Heightfield field = roughField(150, 70, 14);
    std::vector<uint8_t> mask(size_t(150) * 70, 1);
    for (int j = 20; j < 36; ++j)
        for (int i = 40; i < 52; ++i) mask[size_t(j) * 150 + size_t(i)] = 0;
    field.setMask(mask);
    field.setGeoreference(
        terrain::Heightfield::Georeference{{500.0, 2.0, 0.0, 900.0, 0.0, -3.0}, "LOCAL"});
    const std::string path = buildFile(field, 4, sbt::TileHeights::Float32, "window");
    const sbt::TileFile file(path);
    struct Case {
        int64_t i0, j0;
        int width, height;
    };
    // Inside one tile, across borders and the hole, on tile borders, the whole.
    for (const Case c : {Case{3, 5, 9, 7}, Case{30, 10, 40, 33}, Case{16, 32, 17, 17},
                         Case{0, 0, 150, 70}, Case{133, 53, 17, 17}}) {
        SCOPED_TRACE(testing::Message()
                     << c.i0 << ", " << c.j0 << ", " << c.width << "x" << c.height);
        const terrain::Heightfield w = sbt::readWindow(file, c.i0, c.j0, c.width, c.height, 2);
        ASSERT_EQ(w.width(), c.width);
        ASSERT_EQ(w.height(), c.height);
        EXPECT_FLOAT_EQ(w.spacingX(), field.spacingX());
        EXPECT_FLOAT_EQ(w.verticalScale(), 1.0f) << "world heights";
        bool hole = false;
        for (int j = 0; j < c.height; ++j)
            for (int i = 0; i < c.width; ++i) {
                const int gi = int(c.i0) + i, gj = int(c.j0) + j;
                ASSERT_EQ(w.valid(i, j), field.valid(gi, gj)) << gi << ", " << gj;
                hole |= !field.valid(gi, gj);
                if (!field.valid(gi, gj)) continue;
                ASSERT_EQ(w.at(i, j), field.at(gi, gj) * field.verticalScale()) << gi << ", " << gj;
            }
        EXPECT_EQ(w.hasMask(), hole) << "a mask only where the window holds no-data";
        // Sample centres keep their place: sample (0, 0) is the file's (i0, j0).
        ASSERT_TRUE(w.georeference());
        EXPECT_DOUBLE_EQ(w.georeference()->geoTransform[0], 500.0 + 2.0 * double(c.i0));
        EXPECT_DOUBLE_EQ(w.georeference()->geoTransform[3], 900.0 - 3.0 * double(c.j0));
    }
    EXPECT_THROW(sbt::readWindow(file, 140, 0, 20, 10), Error) << "past the real samples";
    EXPECT_THROW(sbt::readWindow(file, -1, 0, 5, 5), Error);
    EXPECT_THROW(sbt::readWindow(file, 0, 0, 0, 5), Error);
    std::remove(path.c_str());
}

}  // namespace
}  // namespace sierra::test
