// Heightfield loaders and writers on good files (values checked) and on bad
// files (each refused with one clear sierra::Error, never a crash). Every file
// is written by the test into a fresh temporary directory.

#include "temp_dir_test_util.h"

#include <sierra/terrain/FileIO.h>
#include <sierra/terrain/HeightfieldIO.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <stb/stb_image_write.h>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

namespace sierra::terrain {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using Bytes = std::vector<uint8_t>;

class TerrainLoaders : public test::TempDirTest {
  protected:
    // The message of the sierra::Error that loading `file` throws ("" if none).
    static std::string loadError(const std::string& file, const LoadOptions& options = {}) {
        try {
            loadHeightfield(file, options);
        } catch (const Error& e) {
            return e.what();
        }
        return "";
    }
};

void putLe16(Bytes& b, uint16_t v) {
    b.push_back(uint8_t(v));
    b.push_back(uint8_t(v >> 8));
}
void putBe16(Bytes& b, uint16_t v) {
    b.push_back(uint8_t(v >> 8));
    b.push_back(uint8_t(v));
}
void putLe32(Bytes& b, uint32_t v) {
    for (int k = 0; k < 4; ++k) b.push_back(uint8_t(v >> (8 * k)));
}
void putLe64(Bytes& b, uint64_t v) {
    for (int k = 0; k < 8; ++k) b.push_back(uint8_t(v >> (8 * k)));
}

// A hand-written .npy file: magic, version, header length, dictionary, data.
Bytes npy(const std::string& descr, const std::string& shape, const Bytes& data,
          bool fortran = false, int major = 1) {
    std::string header = "{'descr': '" + descr +
                         "', 'fortran_order': " + (fortran ? "True" : "False") +
                         ", 'shape': " + shape + ", }";
    const size_t prefix = major == 1 ? 10 : 12;
    header.append((64 - (prefix + header.size() + 1) % 64) % 64, ' ');
    header.push_back('\n');
    Bytes b = {0x93, 'N', 'U', 'M', 'P', 'Y', uint8_t(major), 0};
    if (major == 1)
        putLe16(b, uint16_t(header.size()));
    else
        putLe32(b, uint32_t(header.size()));
    b.insert(b.end(), header.begin(), header.end());
    b.insert(b.end(), data.begin(), data.end());
    return b;
}

Bytes floats32(const std::vector<float>& v) {
    Bytes b;
    for (float f : v) putLe32(b, std::bit_cast<uint32_t>(f));
    return b;
}

// ------------------------------------------------------------------ good files

TEST_F(TerrainLoaders, Png8GreyAndChosenChannelOfRgb) {
    const int w = 5, h = 3;
    std::vector<uint8_t> grey(w * h), rgb(w * h * 3);
    for (int k = 0; k < w * h; ++k) {
        grey[k] = uint8_t(k * 17);
        rgb[3 * k] = uint8_t(255 - k), rgb[3 * k + 1] = 7, rgb[3 * k + 2] = 9;
    }
    ASSERT_TRUE(stbi_write_png(path("grey.png").c_str(), w, h, 1, grey.data(), w));
    ASSERT_TRUE(stbi_write_png(path("rgb.png").c_str(), w, h, 3, rgb.data(), w * 3));
    Heightfield g = loadHeightfield(path("grey.png"));
    ASSERT_EQ(g.width(), w);
    ASSERT_EQ(g.height(), h);
    EXPECT_FALSE(g.hasMask());
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) EXPECT_EQ(g.at(i, j), float((j * w + i) * 17));
    // Colour is refused unless a channel is asked for.
    EXPECT_THAT(loadError(path("rgb.png")),
                HasSubstr("PNG is colour (RGB); a heightmap must be greyscale"));
    Heightfield c = loadHeightfield(path("rgb.png"), {.channel = "r"});
    EXPECT_EQ(c.at(0, 0), 255.0f);
    EXPECT_EQ(c.at(4, 2), float(255 - 14));
    EXPECT_EQ(loadHeightfield(path("rgb.png"), {.channel = "g"}).at(3, 1), 7.0f);
    EXPECT_EQ(loadHeightfield(path("rgb.png"), {.channel = "b"}).at(3, 1), 9.0f);
    Heightfield l = loadHeightfield(path("rgb.png"), {.channel = "luminance"});
    EXPECT_NEAR(l.at(4, 2), 0.2126f * (255 - 14) + 0.7152f * 7 + 0.0722f * 9, 1e-3f);
    EXPECT_THAT(loadError(path("rgb.png"), {.channel = "red"}),
                HasSubstr("unknown channel 'red'; expected luminance, r, g or b"));
    // Grey+alpha: the alpha is ignored.
    std::vector<uint8_t> ga(w * h * 2);
    for (int k = 0; k < w * h; ++k) ga[2 * k] = uint8_t(k * 3), ga[2 * k + 1] = uint8_t(k);
    ASSERT_TRUE(stbi_write_png(path("ga.png").c_str(), w, h, 2, ga.data(), w * 2));
    Heightfield a = loadHeightfield(path("ga.png"));
    EXPECT_EQ(a.at(4, 2), 42.0f);
    EXPECT_FALSE(a.hasMask());
}

TEST_F(TerrainLoaders, Png16FromOurEncoder) {
    const std::vector<uint16_t> v = {0, 1, 258, 65535, 4660, 30000};  // 258 = 0x0102: byte order
    writeFileAtomic(path("a.png"), encodePngGrey16(3, 2, v));
    Heightfield f = loadHeightfield(path("a.png"));
    ASSERT_EQ(f.width(), 3);
    ASSERT_EQ(f.height(), 2);
    for (int k = 0; k < 6; ++k) EXPECT_EQ(f.samples()[k], float(v[k])) << k;
}

TEST_F(TerrainLoaders, Png16LargerThanOneStoredBlock) {
    // 300 x 200 x 2 bytes spans several 65535-byte stored blocks.
    const int w = 300, h = 200;
    std::vector<uint16_t> v(w * h);
    for (size_t k = 0; k < v.size(); ++k) v[k] = uint16_t(k * 7919);
    writeFileAtomic(path("big.png"), encodePngGrey16(w, h, v));
    Heightfield f = loadHeightfield(path("big.png"));
    ASSERT_EQ(f.width(), w);
    for (size_t k = 0; k < v.size(); ++k) ASSERT_EQ(f.samples()[k], float(v[k])) << k;
}

TEST_F(TerrainLoaders, Png16OverEightMebibytes) {
    // 2100 x 2000 x 2 bytes in stored blocks: an 8.4 MB file, over libspng's
    // 8 MiB chunk cache that once made such files unreadable.
    const int w = 2100, h = 2000;
    std::vector<uint16_t> v(size_t(w) * h);
    for (size_t k = 0; k < v.size(); ++k) v[k] = uint16_t(k * 40503u >> 3);
    const std::vector<uint8_t> png = encodePngGrey16(w, h, v);
    ASSERT_GT(png.size(), size_t(8) << 20);
    writeFileAtomic(path("large.png"), png);
    Heightfield f = loadHeightfield(path("large.png"));
    ASSERT_EQ(f.width(), w);
    ASSERT_EQ(f.height(), h);
    for (size_t k = 0; k < v.size(); k += 997) ASSERT_EQ(f.samples()[k], float(v[k])) << k;
    EXPECT_EQ(f.samples().back(), float(v.back()));
}

TEST_F(TerrainLoaders, PgmAsciiAndBinary8And16Bit) {
    Heightfield a =
        loadHeightfield(write("a.pgm", "P2\n# a comment\n3 2\n255\n0 1 2\n253 254 255\n"));
    ASSERT_EQ(a.width(), 3);
    ASSERT_EQ(a.height(), 2);
    EXPECT_EQ(a.at(2, 0), 2.0f);
    EXPECT_EQ(a.at(0, 1), 253.0f);

    Heightfield b = loadHeightfield(write("b.pgm", "P2 2 2 1000 0 999\n1000 500\n"));
    EXPECT_EQ(b.at(1, 0), 999.0f);
    EXPECT_EQ(b.at(0, 1), 1000.0f);

    Bytes p5 = {'P', '5', '\n', '2', ' ', '2', '\n', '2', '0', '0', '\n', 0, 10, 199, 200};
    Heightfield c = loadHeightfield(write("c.PGM", p5));
    EXPECT_EQ(c.at(1, 0), 10.0f);
    EXPECT_EQ(c.at(1, 1), 200.0f);

    std::string head = "P5\n3 2\n65535\n";
    Bytes p16(head.begin(), head.end());
    for (uint16_t v :
         {uint16_t(0x0102), uint16_t(65535), uint16_t(7), uint16_t(1), uint16_t(2), uint16_t(3)})
        putBe16(p16, v);
    Heightfield d = loadHeightfield(write("d.pgm", p16));
    EXPECT_EQ(d.at(0, 0), 258.0f);  // big-endian
    EXPECT_EQ(d.at(1, 0), 65535.0f);
    EXPECT_EQ(d.at(2, 0), 7.0f);
}

TEST_F(TerrainLoaders, RawR16AndR32) {
    Bytes r16;
    for (uint16_t v = 0; v < 12; ++v) putLe16(r16, uint16_t(v * 1000 + 1));
    Heightfield a = loadHeightfield(write("a.r16", r16), {.rawWidth = 4, .rawHeight = 3});
    ASSERT_EQ(a.width(), 4);
    ASSERT_EQ(a.height(), 3);
    EXPECT_EQ(a.at(3, 2), 11001.0f);
    EXPECT_EQ(a.at(1, 1), 5001.0f);

    Bytes sq;
    for (uint16_t v = 0; v < 9; ++v) putLe16(sq, uint16_t(300 + v));
    Heightfield b = loadHeightfield(write("b.r16", sq));  // 3x3 guessed
    ASSERT_EQ(b.width(), 3);
    EXPECT_EQ(b.at(2, 2), 308.0f);

    Heightfield c =
        loadHeightfield(write("c.r32", floats32({-1.5f, 2.25f, 1e6f, -0.0f, 3.0f, 4.0f})),
                        {.rawWidth = 2, .rawHeight = 3});
    EXPECT_EQ(c.at(0, 0), -1.5f);
    EXPECT_EQ(c.at(1, 0), 2.25f);
    EXPECT_EQ(c.at(0, 1), 1e6f);
    EXPECT_EQ(c.at(1, 2), 4.0f);
}

TEST_F(TerrainLoaders, SrtmHgt1201WithNoData) {
    const int n = 1201;
    Bytes b;
    b.reserve(size_t(n) * n * 2);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            int16_t v = int16_t((i + 2 * j) % 3000 - 500);
            if (i == 10 && j == 20) v = -32768;
            putBe16(b, uint16_t(v));
        }
    Heightfield f = loadHeightfield(write("N45E006.hgt", b));
    ASSERT_EQ(f.width(), n);
    ASSERT_EQ(f.height(), n);
    EXPECT_EQ(f.at(0, 0), -500.0f);
    EXPECT_EQ(f.at(7, 0), -493.0f);
    EXPECT_EQ(f.at(1000, 1000), float((1000 + 2000) % 3000 - 500));
    EXPECT_EQ(f.at(1, 1000), float((1 + 2000) % 3000 - 500));  // negative: sign kept
    ASSERT_TRUE(f.hasMask());
    EXPECT_FALSE(f.valid(10, 20));
    EXPECT_TRUE(f.valid(11, 20));
    EXPECT_TRUE(f.valid(10, 21));
    // The void is filled from its neighbours, not left at -32768.
    EXPECT_EQ(f.at(10, 20), (f.at(9, 20) + f.at(11, 20) + f.at(10, 19) + f.at(10, 21)) / 4.0f);
    auto [lo, hi] = f.range();
    EXPECT_EQ(lo, -500.0f);
    EXPECT_EQ(hi, 2499.0f);
    // 3 arc-seconds on WGS 84 at 45.5 N (the name gives the south edge, 45 N):
    // 92.6 m north-south, 65.1 m east-west.
    EXPECT_NEAR(f.spacingZ(), 92.6, 0.05);
    EXPECT_NEAR(f.spacingX(), 65.13, 0.01);
    EXPECT_TRUE(f.metres());
    // S45 spans 45 to 44 S: the same spacing as N44, mirrored.
    EXPECT_FLOAT_EQ(loadHeightfield(write("s45w070.hgt", b)).spacingX(),
                    loadHeightfield(write("N44W070.hgt", b)).spacingX());
    EXPECT_GT(loadHeightfield(write("N44W070.hgt", b)).spacingX(), f.spacingX() + 1.0f);
    // A name that gives no latitude keeps the nominal 90 m.
    Heightfield unnamed = loadHeightfield(write("tile.hgt", b));
    EXPECT_EQ(unnamed.spacingX(), 90.0f);
    EXPECT_EQ(unnamed.spacingZ(), 90.0f);
    EXPECT_TRUE(unnamed.metres());
}

TEST_F(TerrainLoaders, NpyFloat32Float64Int16Uint16Uint8) {
    Heightfield f4 = loadHeightfield(
        write("f4.npy", npy("<f4", "(2, 3)", floats32({0.5f, -1.0f, 2.0f, 3.0f, 4.0f, 1e-3f}))));
    ASSERT_EQ(f4.width(), 3);   // columns
    ASSERT_EQ(f4.height(), 2);  // rows
    EXPECT_EQ(f4.at(0, 0), 0.5f);
    EXPECT_EQ(f4.at(1, 0), -1.0f);
    EXPECT_EQ(f4.at(2, 1), 1e-3f);

    Bytes d8;
    for (double v : {1.25, -2.5, 1e5, 7.0}) putLe64(d8, std::bit_cast<uint64_t>(v));
    Heightfield f8 = loadHeightfield(write("f8.npy", npy("<f8", "(2, 2)", d8)));
    EXPECT_EQ(f8.at(0, 0), 1.25f);
    EXPECT_EQ(f8.at(1, 0), -2.5f);
    EXPECT_EQ(f8.at(0, 1), 1e5f);

    Bytes i2;
    for (int16_t v : {int16_t(-32000), int16_t(-1), int16_t(0), int16_t(32767), int16_t(5),
                      int16_t(6), int16_t(7), int16_t(8)})
        putLe16(i2, uint16_t(v));
    Heightfield fi = loadHeightfield(write("i2.npy", npy("<i2", "(2, 4)", i2)));
    EXPECT_EQ(fi.at(0, 0), -32000.0f);
    EXPECT_EQ(fi.at(1, 0), -1.0f);
    EXPECT_EQ(fi.at(3, 0), 32767.0f);

    Bytes u2;
    for (uint16_t v : {uint16_t(65535), uint16_t(1), uint16_t(258), uint16_t(2)}) putLe16(u2, v);
    Heightfield fu = loadHeightfield(write("u2.npy", npy("<u2", "(2,2)", u2)));
    ASSERT_EQ(fu.width(), 2);
    EXPECT_EQ(fu.at(0, 0), 65535.0f);
    EXPECT_EQ(fu.at(0, 1), 258.0f);

    Heightfield fb = loadHeightfield(write("u1.npy", npy("|u1", "(2, 2)", {200, 3, 1, 2})));
    EXPECT_EQ(fb.at(0, 0), 200.0f);
    EXPECT_EQ(fb.at(1, 0), 3.0f);

    Heightfield v2 = loadHeightfield(
        write("v2.npy", npy("<f4", "(2, 2)", floats32({9.0f, 8.0f, 7.0f, 6.0f}), false, 2)));
    EXPECT_EQ(v2.at(1, 0), 8.0f);
}

// ------------------------------------------------------------------ round trips

TEST_F(TerrainLoaders, NpyRoundTripIsExact) {
    Heightfield f(37, 23);
    for (int j = 0; j < f.height(); ++j)
        for (int i = 0; i < f.width(); ++i)
            f.at(i, j) = std::sin(i * 0.37f) * 1234.567f - j * 0.001f;
    saveHeightfield(path("rt.npy"), f);
    Heightfield g = loadHeightfield(path("rt.npy"));
    ASSERT_EQ(g.width(), f.width());
    ASSERT_EQ(g.height(), f.height());
    for (size_t k = 0; k < f.samples().size(); ++k)
        ASSERT_EQ(std::bit_cast<uint32_t>(g.samples()[k]), std::bit_cast<uint32_t>(f.samples()[k]));
    // No temporary file left beside it.
    int files = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_)) ++files;
    EXPECT_EQ(files, 1);
}

TEST_F(TerrainLoaders, Png16RoundTripIsExactForIntegerHeights) {
    // range() is exactly 0..65535, so the linear mapping is the identity.
    Heightfield f(61, 17);
    for (int j = 0; j < f.height(); ++j)
        for (int i = 0; i < f.width(); ++i) f.at(i, j) = float((i * 1543 + j * 7717) % 65536);
    f.at(0, 0) = 0.0f;
    f.at(60, 16) = 65535.0f;
    saveHeightfield(path("rt.png"), f);
    Heightfield g = loadHeightfield(path("rt.png"));
    ASSERT_EQ(g.width(), f.width());
    ASSERT_EQ(g.height(), f.height());
    for (size_t k = 0; k < f.samples().size(); ++k) ASSERT_EQ(g.samples()[k], f.samples()[k]) << k;
}

TEST_F(TerrainLoaders, Png16MapsRangeLinearly) {
    Heightfield f(3, 2, 0.0f);
    f.at(0, 0) = -10.0f, f.at(1, 0) = 0.0f, f.at(2, 0) = 10.0f;
    saveHeightfield(path("lin.png"), f);
    Heightfield g = loadHeightfield(path("lin.png"));
    EXPECT_EQ(g.at(0, 0), 0.0f);
    EXPECT_EQ(g.at(1, 0), 32768.0f);  // 32767.5 rounds up
    EXPECT_EQ(g.at(2, 0), 65535.0f);
}

// ------------------------------------------------------------------ bad files

TEST_F(TerrainLoaders, MissingFileAndUnknownExtension) {
    const std::string missing = path("nope.png");
    EXPECT_THAT(loadError(missing),
                HasSubstr("cannot open " + missing + ": No such file or directory"));
    const std::string odd = write("a.xyz", "hello");
    EXPECT_THAT(loadError(odd), HasSubstr("unknown heightfield extension '.xyz'"));
    EXPECT_THAT(loadError(odd), HasSubstr(".png .pgm .r16 .r32 .hgt .npy"));
    EXPECT_THAT(loadError(write("noext", "x")), HasSubstr("unknown heightfield extension ''"));
#ifdef SIERRA_WITH_GDAL
    EXPECT_THAT(loadError(write("a.tif", "x")),
                HasSubstr("cannot open " + path("a.tif") + " with GDAL"));
#else
    EXPECT_THAT(loadError(write("a.tif", "x")), HasSubstr("SIERRA_WITH_GDAL"));
#endif
    fs::create_directory(path("dir.png"));
    EXPECT_THAT(loadError(path("dir.png")),
                HasSubstr("cannot open " + path("dir.png") +
                          ": it is a directory; expected a regular file"));
}

TEST_F(TerrainLoaders, GarbagePng) {
    EXPECT_THAT(loadError(write("g.png", "this is not an image at all")),
                HasSubstr("not a PNG file"));
    EXPECT_THAT(loadError(write("e.png", "")), HasSubstr("not a PNG file"));
    Bytes sigThenJunk = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 1, 2, 3, 4, 5, 6, 7, 8, 9};
    EXPECT_THAT(loadError(write("j.png", sigThenJunk)), HasSubstr("unreadable PNG header"));
}

TEST_F(TerrainLoaders, TruncatedFiles) {
    std::vector<uint16_t> v(64 * 64);
    for (size_t k = 0; k < v.size(); ++k) v[k] = uint16_t(k * 31);
    Bytes png = encodePngGrey16(64, 64, v);
    png.resize(png.size() / 2);
    EXPECT_THAT(loadError(write("t.png", png)), HasSubstr("truncated or corrupt"));

    Bytes p5 = {'P', '5', ' ', '4', ' ', '4', ' ', '2', '5', '5', '\n', 1, 2, 3};
    EXPECT_THAT(loadError(write("t.pgm", p5)),
                HasSubstr("truncated PGM: 4x4 samples need 16 bytes of data, the file has 3"));
    EXPECT_THAT(loadError(write("t2.pgm", "P2 3 2 255 1 2 3 4 5")),
                HasSubstr("truncated PGM: sample 6 of 6 is missing"));
    EXPECT_THAT(loadError(write("t3.pgm", "P5 3 2")), HasSubstr("expected the maxval"));

    Bytes r16(10, 0);
    EXPECT_THAT(loadError(write("t.r16", r16), {.rawWidth = 4, .rawHeight = 4}),
                HasSubstr("raw file has 10 bytes but 4x4 uint16 samples are 32 bytes"));

    Bytes data = floats32({1, 2, 3});
    EXPECT_THAT(loadError(write("t.npy", npy("<f4", "(2, 2)", data))),
                HasSubstr("truncated .npy data"));
    Bytes header = npy("<f4", "(2, 2)", {});
    header.resize(20);
    EXPECT_THAT(loadError(write("h.npy", header)), HasSubstr("truncated .npy header"));

    Bytes hgt(2 * 1201 * 1201 - 2, 0);
    EXPECT_THAT(loadError(write("t.hgt", hgt)), HasSubstr("expected 2884802 (1201x1201, SRTM3)"));
}

TEST_F(TerrainLoaders, WrongSizes) {
    EXPECT_THAT(loadError(write("w.hgt", Bytes(1000, 0))),
                HasSubstr("SRTM .hgt file has 1000 bytes; expected 2884802"));
    EXPECT_THAT(loadError(write("w.r16", Bytes(40, 0)), {.rawWidth = 4, .rawHeight = 4}),
                HasSubstr("check rawWidth and rawHeight"));
    EXPECT_THAT(loadError(write("g.r16", Bytes(12, 0))),  // 6 samples: not a square
                HasSubstr("cannot guess the size of a raw file of 12 bytes"));
    EXPECT_THAT(loadError(write("o.r32", Bytes(16, 0)), {.rawWidth = 2, .rawHeight = 0}),
                HasSubstr("give both LoadOptions rawWidth and rawHeight"));
    EXPECT_THAT(loadError(write("one.npy", npy("<f4", "(4,)", floats32({1, 2, 3, 4})))),
                HasSubstr("expected a 2-D array"));
    EXPECT_THAT(loadError(write("three.npy", npy("<f4", "(1, 1, 1)", floats32({1})))),
                HasSubstr("expected a 2-D array"));
}

TEST_F(TerrainLoaders, AbsurdDimensions) {
    EXPECT_THAT(loadError(write("big.pgm", "P5 70000 2 255\n\x01\x02")),
                HasSubstr("PGM size 70000x2 is outside 2..65537 samples per side"));
    EXPECT_THAT(loadError(write("zero.pgm", "P2 0 5 255\n")), HasSubstr("outside 2..65537"));
    EXPECT_THAT(loadError(write("huge.pgm", "P5 99999999999 99999999999 255\n")),
                HasSubstr("outside 2..65537"));
    // More samples than the limits allow: refused before allocating them.
    EXPECT_THAT(loadError(write("many.pgm", "P5 60000 60000 255\nabc")),
                HasSubstr("pads to a 65537x65537 grid"));
    // Within the limits but more samples than the file holds.
    EXPECT_THAT(loadError(write("many2.pgm", "P2 6000 6000 255\n1 2 3")),
                HasSubstr("truncated PGM"));
    EXPECT_THAT(loadError(write("z.npy", npy("<f4", "(0, 5)", {}))), HasSubstr("outside 2..65537"));
    EXPECT_THAT(loadError(write("h.npy", npy("<f4", "(100000, 100000)", floats32({1})))),
                HasSubstr("outside 2..65537"));
    EXPECT_THAT(loadError(write("m.npy", npy("<f4", "(6000, 6000)", floats32({1})))),
                HasSubstr("truncated .npy data"));
    EXPECT_THAT(loadError(write("a.r16", Bytes(8, 0)), {.rawWidth = 100000, .rawHeight = 2}),
                HasSubstr("raw size 100000x2 is outside 2..65537"));
    EXPECT_THAT(loadError(write("max.pgm", "P2 2 2 70000 5")),
                HasSubstr("maxval 70000 is outside 1..65535"));
}

TEST_F(TerrainLoaders, BadNpyHeaders) {
    EXPECT_THAT(loadError(write("i4.npy", npy("<i4", "(1, 1)", {0, 0, 0, 0}))),
                HasSubstr("dtype '<i4' is not supported; expected one of <f4 <f8 <i2 <u2 |u1"));
    EXPECT_THAT(loadError(write("be.npy", npy(">f4", "(1, 1)", {0, 0, 0, 0}))),
                HasSubstr("dtype '>f4' is not supported"));
    EXPECT_THAT(loadError(write("f.npy", npy("<f4", "(2, 2)", floats32({1, 2, 3, 4}), true))),
                HasSubstr("Fortran order"));
    Bytes v3 = npy("<f4", "(1, 1)", floats32({1}));
    v3[6] = 3;
    EXPECT_THAT(loadError(write("v3.npy", v3)), HasSubstr("format version 3.0 is not supported"));
    EXPECT_THAT(loadError(write("m.npy", "not numpy at all")), HasSubstr("not a NumPy .npy file"));
}

TEST_F(TerrainLoaders, NonFiniteFloatsRejected) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    EXPECT_THAT(loadError(write("n.npy", npy("<f4", "(2, 2)", floats32({1, nan, 3, 4})))),
                HasSubstr("NaN height at (1,0); heights must be finite (use a no-data value in "
                          ".hgt or mask)"));
    EXPECT_THAT(
        loadError(write("n.r32", floats32({1, 2, 3, nan})), {.rawWidth = 2, .rawHeight = 2}),
        HasSubstr("NaN height at (1,1)"));
    EXPECT_THAT(loadError(write("i.r32", floats32({1, inf, 3, 4}))),
                HasSubstr("infinite height at (1,0)"));
    Bytes d8;
    for (double v : {1.0, 1e300}) putLe64(d8, std::bit_cast<uint64_t>(v));  // overflows float32
    for (double v : {3.0, 4.0}) putLe64(d8, std::bit_cast<uint64_t>(v));
    EXPECT_THAT(loadError(write("o.npy", npy("<f8", "(2, 2)", d8))),
                HasSubstr("infinite height at (1,0)"));
}

TEST_F(TerrainLoaders, BadPgmContent) {
    EXPECT_THAT(loadError(write("p6.pgm", "P6 1 1 255\n\x01\x02\x03")),
                HasSubstr("magic must be P2 or P5"));
    EXPECT_THAT(loadError(write("over.pgm", "P2 2 2 100 5 101 1 1")),
                HasSubstr("PGM sample 101 at (1,0) exceeds the header's maxval 100"));
    EXPECT_THAT(loadError(write("word.pgm", "P2 2 2 100 5 x 1 1")),
                HasSubstr("is not a decimal number"));
}

TEST_F(TerrainLoaders, WriterErrorsLeaveNoFile) {
    Heightfield f(4, 4, 1.0f);
    try {
        saveHeightfield(path("no/such/dir/x.npy"), f);
        ADD_FAILURE() << "expected an error";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("cannot write " + path("no/such/dir/x.npy")));
    }
    try {
        saveHeightfield(path("x.bmp"), f);
        ADD_FAILURE() << "expected an error";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("writes .png (16-bit grey) or .npy (float32)"));
    }
    f.at(1, 2) = std::numeric_limits<float>::quiet_NaN();
    try {
        saveHeightfield(path("nan.png"), f);
        ADD_FAILURE() << "expected an error";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("height at (1,2) is not finite"));
    }
    EXPECT_THROW(saveHeightfield(path("empty.npy"), Heightfield()), Error);
    EXPECT_TRUE(fs::is_empty(dir_));
}

}  // namespace
}  // namespace sierra::terrain
