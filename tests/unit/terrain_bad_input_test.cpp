// The bad-input table: hostile or broken heightmaps, each refused with one
// clear sierra::Error, quickly and without a big allocation. Every row runs in a
// forked child, so the row's own time and peak memory are measured (wait4's
// ru_maxrss less the child's resident size at the start) and a hang is caught
// by a time limit instead of stalling the suite. The files are built here.

#include "temp_dir_test_util.h"

#include <sierra/terrain/FileIO.h>
#include <sierra/terrain/HeightfieldIO.h>
#include <sierra/terrain/Maps.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <thread>
#include <vector>

#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

namespace sierra::terrain {
namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<uint8_t>;

// Limits every row must stay within. Generous for a loaded 2-core machine and
// a sanitizer build; a row that allocated for its claimed size (1 GiB and more)
// or read /dev/zero would exceed them by orders of magnitude.
constexpr double kMaxSeconds = 5.0;
constexpr long kMaxPeakKiB = 64 * 1024;

uint32_t crc32(const uint8_t* data, size_t size) {
    uint32_t crc = 0xffffffffu;
    for (size_t k = 0; k < size; ++k) {
        crc ^= data[k];
        for (int b = 0; b < 8; ++b) crc = (crc & 1) ? 0xedb88320u ^ (crc >> 1) : crc >> 1;
    }
    return ~crc;
}

void putBe32(Bytes& out, uint32_t v) {
    for (int s = 24; s >= 0; s -= 8) out.push_back(uint8_t(v >> s));
}

struct Chunk {
    std::string type;
    Bytes data;
};

// The chunks of a PNG (signature skipped), CRCs dropped.
std::vector<Chunk> chunksOf(const Bytes& png) {
    std::vector<Chunk> chunks;
    for (size_t at = 8; at + 12 <= png.size();) {
        const uint32_t length = (uint32_t(png[at]) << 24) | (uint32_t(png[at + 1]) << 16) |
                                (uint32_t(png[at + 2]) << 8) | png[at + 3];
        chunks.push_back({std::string(png.begin() + at + 4, png.begin() + at + 8),
                          Bytes(png.begin() + at + 8, png.begin() + at + 8 + length)});
        at += 12 + length;
    }
    return chunks;
}

// A PNG from chunks with correct CRCs.
Bytes pngOf(const std::vector<Chunk>& chunks) {
    Bytes png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    for (const Chunk& c : chunks) {
        putBe32(png, uint32_t(c.data.size()));
        const size_t start = png.size();
        png.insert(png.end(), c.type.begin(), c.type.end());
        png.insert(png.end(), c.data.begin(), c.data.end());
        putBe32(png, crc32(png.data() + start, png.size() - start));
    }
    return png;
}

// A valid 16-bit grey 8x8 PNG from Sierra's own encoder.
Bytes goodPng() {
    std::vector<uint16_t> v(64);
    for (size_t k = 0; k < v.size(); ++k) v[k] = uint16_t(k * 1000);
    return encodePngGrey16(8, 8, v);
}

// A float32 .npy file of the given shape text and values.
Bytes npyOf(const std::string& shape, const std::vector<float>& values) {
    Bytes npy = {0x93, 'N', 'U', 'M', 'P', 'Y', 1, 0};
    std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': " + shape + ", }";
    header.append((64 - (10 + header.size() + 1) % 64) % 64, ' ');
    header.push_back('\n');
    npy.push_back(uint8_t(header.size()));
    npy.push_back(uint8_t(header.size() >> 8));
    npy.insert(npy.end(), header.begin(), header.end());
    for (float v : values) {
        const uint32_t u = std::bit_cast<uint32_t>(v);
        for (int b = 0; b < 4; ++b) npy.push_back(uint8_t(u >> (8 * b)));
    }
    return npy;
}

struct Outcome {
    std::string message;  // the sierra::Error's text, or what went wrong instead
    bool sierraError = false;
    double seconds = 0.0;
    long peakKiB = 0;  // child's peak resident size less its size at the start
    bool timedOut = false;
};

long residentKiB() {
    long pages = 0, resident = 0;
    if (std::FILE* f = std::fopen("/proc/self/statm", "r")) {
        if (std::fscanf(f, "%ld %ld", &pages, &resident) != 2) resident = 0;
        std::fclose(f);
    }
    return resident * (sysconf(_SC_PAGESIZE) / 1024);
}

// Loads `file` in a forked child; the child writes its start size, its
// outcome (0 = sierra::Error, 1 = loaded, 2 = another exception) and the
// message through a pipe.
Outcome loadInChild(const std::string& file, const LoadOptions& options) {
    int fds[2];
    if (pipe(fds) != 0) return {"pipe failed"};
    const auto start = std::chrono::steady_clock::now();
    const pid_t pid = fork();
    if (pid == 0) {
        close(fds[0]);
        const long startKiB = residentKiB();
        int kind = 1;
        std::string text;
        try {
            loadHeightfield(file, options);
        } catch (const Error& e) {
            kind = 0;
            text = e.what();
        } catch (const std::exception& e) {
            kind = 2;
            text = std::string("not a sierra::Error: ") + e.what();
        }
        const std::string out = std::to_string(startKiB) + " " + std::to_string(kind) + " " + text;
        if (write(fds[1], out.data(), out.size()) < 0) _exit(3);
        _exit(0);
    }
    close(fds[1]);
    Outcome outcome;
    int status = 0;
    rusage usage{};
    for (;;) {
        const pid_t done = wait4(pid, &status, WNOHANG, &usage);
        outcome.seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (done == pid) break;
        if (outcome.seconds > 4 * kMaxSeconds) {
            kill(pid, SIGKILL);
            wait4(pid, &status, 0, &usage);
            outcome.timedOut = true;
            break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    std::string text;
    char buffer[4096];
    for (ssize_t n; (n = read(fds[0], buffer, sizeof buffer)) > 0;) text.append(buffer, size_t(n));
    close(fds[0]);
    if (outcome.timedOut) {
        outcome.message = "timed out (hang)";
        return outcome;
    }
    long startKiB = 0;
    int kind = 3;
    int consumed = 0;
    if (std::sscanf(text.c_str(), "%ld %d %n", &startKiB, &kind, &consumed) < 2) {
        outcome.message = "child died without an answer (status " + std::to_string(status) + ")";
        return outcome;
    }
    outcome.peakKiB = usage.ru_maxrss - startKiB;
    outcome.sierraError = kind == 0;
    outcome.message = kind == 1 ? "loaded without an error" : text.substr(size_t(consumed));
    return outcome;
}

class TerrainBadInput : public test::TempDirTest {
  protected:
    // One row of the table: the load fails with a sierra::Error containing
    // `expected`, within the time and memory limits.
    void expectRow(const std::string& row, const std::string& file, const std::string& expected,
                   const LoadOptions& options = {}) {
        SCOPED_TRACE(row);
        const Outcome o = loadInChild(file, options);
        std::printf("bad input | %-34s | %7.1f ms | %6ld KiB | %s\n", row.c_str(), 1e3 * o.seconds,
                    o.peakKiB, o.message.c_str());
        EXPECT_FALSE(o.timedOut);
        EXPECT_TRUE(o.sierraError) << o.message;
        EXPECT_THAT(o.message, ::testing::HasSubstr(expected));
        EXPECT_THAT(o.message, ::testing::Not(::testing::HasSubstr("\n")));  // one line
        EXPECT_LT(o.seconds, kMaxSeconds);
        EXPECT_LT(o.peakKiB, kMaxPeakKiB);
    }
};

TEST_F(TerrainBadInput, EveryRowFailsFastWithAClearMessage) {
    // An RGB photo is not a heightmap unless a channel is asked for.
    {
        std::vector<uint8_t> rgb(16 * 16 * 3, 100);
        ASSERT_TRUE(stbi_write_png(path("rgb.png").c_str(), 16, 16, 3, rgb.data(), 16 * 3));
        expectRow("RGB PNG", path("rgb.png"),
                  "PNG is colour (RGB); a heightmap must be greyscale (8 or 16 bit), or pick a "
                  "channel: luminance, r, g or b");
        std::vector<uint8_t> rgba(16 * 16 * 4, 100);
        ASSERT_TRUE(stbi_write_png(path("rgba.png").c_str(), 16, 16, 4, rgba.data(), 16 * 4));
        expectRow("RGBA PNG", path("rgba.png"), "PNG is colour (RGBA)");
        expectRow("RGB PNG, unknown channel", path("rgb.png"), "unknown channel 'alpha'",
                  {.channel = "alpha"});
    }
    // 1x1: no surface to draw.
    {
        const uint8_t one = 7;
        ASSERT_TRUE(stbi_write_png(path("one.png").c_str(), 1, 1, 1, &one, 1));
        expectRow("1x1 PNG", path("one.png"),
                  "PNG size 1x1: a heightfield needs at least 2x2 samples");
        expectRow("1x1 PGM", write("one.pgm", "P2 1 1 255 7"),
                  "PGM size 1x1: a heightfield needs at least 2x2 samples");
        expectRow("1x1 .r32", write("one.r32", Bytes{0, 0, 128, 63}),
                  "raw size 1x1: a heightfield needs at least 2x2 samples");
    }
    // PNG corruption: libspng checks every CRC and every chunk length.
    {
        Bytes png = goodPng();
        std::vector<Chunk> chunks = chunksOf(png);
        ASSERT_EQ(chunks[1].type, "IDAT");
        // IHDR: bytes 8..32 (length, type, 13 bytes, CRC); IDAT from byte 33.
        const size_t idatData = 8 + 25 + 8;
        Bytes badCrc = png;
        badCrc[idatData + chunks[1].data.size()] ^= 0x40;  // IDAT's CRC, data intact
        expectRow("PNG with a corrupt IDAT CRC", write("crc.png", badCrc),
                  "cannot decode PNG (libspng: invalid chunk checksum)");
        Bytes badData = png;
        badData[idatData + 20] ^= 0x40;  // a byte of IDAT's data, CRC kept
        expectRow("PNG with a flipped IDAT byte", write("flip.png", badData),
                  "cannot decode PNG (libspng: ");
        Bytes badHeaderCrc = png;
        badHeaderCrc[8 + 8 + 13] ^= 0x01;  // the IHDR CRC
        expectRow("PNG with a corrupt IHDR CRC", write("crc2.png", badHeaderCrc),
                  "(libspng: invalid chunk checksum)");

        Bytes huge = png;  // IDAT's length field claims 1 GiB; the file has ~200 bytes
        const size_t idatLength = 8 + 12 + 13;
        huge[idatLength] = 0x40,
        huge[idatLength + 1] = huge[idatLength + 2] = huge[idatLength + 3] = 0;
        expectRow("PNG IDAT claiming 1 GiB", write("huge.png", huge),
                  "cannot decode PNG (libspng: ");

        std::vector<Chunk> empty = {chunks[0], {"IDAT", {}}, {"IEND", {}}};
        expectRow("PNG with only a zero-length IDAT", write("empty.png", pngOf(empty)),
                  "cannot decode PNG (libspng: ");
        Bytes truncated(png.begin(), png.begin() + png.size() / 2);
        expectRow("truncated PNG", write("half.png", truncated), "cannot decode PNG (libspng: ");
        // The size limits come before any pixel: a 65537x65537 header over 1 KiB of data.
        std::vector<Chunk> wide = chunks;
        wide[0].data = {0, 1, 0, 1, 0, 1, 0, 1, 16, 0, 0, 0, 0};
        expectRow("PNG header 65537x65537", write("wide.png", pngOf(wide)),
                  "PNG size 65537x65537 pads to a 65537x65537 grid (4295098369 samples), over the "
                  "limit of 16385x16385 samples");
    }
    // Headers claiming more samples than the limits allow.
    {
        expectRow("PGM header 16385x1",
                  write("strip.pgm", "P5 16385 1 255\n" + std::string(16385, 'a')),
                  "PGM size 16385x1: a heightfield needs at least 2x2 samples");
        expectRow("PGM header 16386x2",
                  write("wide.pgm", "P5 16386 2 255\n" + std::string(32772, 'a')),
                  "PGM size 16386x2 pads to a 32769x32769 grid (1073807361 samples), over the "
                  "limit of 16385x16385 samples (maxPaddedSide");
        expectRow("PGM header 65537x1", write("w65537.pgm", "P5 65537 1 255\n"),
                  "PGM size 65537x1: a heightfield needs at least 2x2 samples");
        expectRow("PGM header 65537x2", write("w65537b.pgm", "P5 65537 2 255\n"),
                  "PGM size 65537x2 pads to a 65537x65537 grid");
        expectRow("PGM header 70000x70000", write("w70000.pgm", "P5 70000 70000 65535\n"),
                  "PGM size 70000x70000 is outside 2..65537 samples per side");
        expectRow(".npy shape (16386, 16386)", write("big.npy", npyOf("(16386, 16386)", {})),
                  ".npy array size 16386x16386 pads to a 32769x32769 grid");
    }
    // Inputs that are not regular files: never a hang, never read to the end.
    {
        ASSERT_EQ(mkfifo(path("fifo.png").c_str(), 0600), 0);
        expectRow("FIFO as .png", path("fifo.png"),
                  "cannot open " + path("fifo.png") +
                      ": it is a FIFO (named pipe); expected a regular file");
        ASSERT_EQ(mkfifo(path("fifo.r16").c_str(), 0600), 0);
        expectRow("FIFO as .r16 with a size", path("fifo.r16"), "it is a FIFO (named pipe)",
                  {.rawWidth = 4, .rawHeight = 4});
        fs::create_symlink("/dev/zero", path("zero.r16"));
        expectRow("symlink to /dev/zero as .r16", path("zero.r16"),
                  "cannot open " + path("zero.r16") +
                      ": it is a character device; expected a "
                      "regular file");
        fs::create_symlink("/dev/zero", path("zero.npy"));
        expectRow("symlink to /dev/zero as .npy", path("zero.npy"), "it is a character device");
#ifdef SIERRA_WITH_GDAL
        ASSERT_EQ(mkfifo(path("fifo.tif").c_str(), 0600), 0);
        expectRow("FIFO as .tif", path("fifo.tif"), "it is a FIFO (named pipe)");
#endif
    }
    // Files larger than the format can be for the limits: refused before reading
    // (sparse files, so the test writes nothing big).
    {
        write("big.hgt", Bytes{});
        fs::resize_file(path("big.hgt"), 3601ull * 3601 * 2 + 2);
        expectRow(".hgt larger than SRTM1", path("big.hgt"),
                  "big.hgt has 25934404 bytes, more than the 25934402 bytes allowed; the largest "
                  "SRTM tile (3601x3601, SRTM1) is 25934402 bytes");
        write("big2.npy", Bytes{});
        fs::resize_file(path("big2.npy"), 5ull << 30);
        expectRow(".npy of 5 GiB", path("big2.npy"),
                  "big2.npy has 5368709120 bytes, more than the 2148794376 bytes allowed; a .npy "
                  "heightmap within the limit of 16385x16385 samples (maxPaddedSide) is smaller");
    }
    // Non-finite floats: the first bad sample is named.
    {
        const float nan = std::numeric_limits<float>::quiet_NaN();
        expectRow("NaN in .npy",
                  write("nan.npy", npyOf("(2, 3)", {1.0f, 2.0f, 3.0f, 4.0f, nan, nan})),
                  "NaN height at (1,1); heights must be finite");
        Bytes r32;
        for (float v : {1.0f, 2.0f, nan, 4.0f}) {
            const uint32_t u = std::bit_cast<uint32_t>(v);
            for (int b = 0; b < 4; ++b) r32.push_back(uint8_t(u >> (8 * b)));
        }
        expectRow("NaN in .r32", write("nan.r32", r32), "NaN height at (0,1)");
    }
    // Raw files: the size from the options is checked against the file first.
    {
        expectRow("truncated .r16", write("short.r16", Bytes(30, 0)),
                  "raw file has 30 bytes but 4x4 uint16 samples are 32 bytes; check rawWidth and "
                  "rawHeight",
                  {.rawWidth = 4, .rawHeight = 4});
        expectRow(".r32 sized 16385x16385, 16 bytes", write("claim.r32", Bytes(16, 0)),
                  "raw file has 16 bytes but 16385x16385 float32 samples are 1073872900 bytes",
                  {.rawWidth = 16385, .rawHeight = 16385});
        expectRow(".r16 sized 60000x60000", write("claim.r16", Bytes(16, 0)),
                  "raw size 60000x60000 pads to a 65537x65537 grid",
                  {.rawWidth = 60000, .rawHeight = 60000});
    }
}

// A zero-length IDAT before the real one is valid PNG: decoded, not refused.
TEST_F(TerrainBadInput, ZeroLengthFirstIdatIsValid) {
    std::vector<Chunk> chunks = chunksOf(goodPng());
    chunks.insert(chunks.begin() + 1, Chunk{"IDAT", {}});
    Heightfield field = loadHeightfield(write("z.png", pngOf(chunks)));
    ASSERT_EQ(field.width(), 8);
    EXPECT_EQ(field.at(7, 7), 63000.0f);
}

// The limit is an option: a smaller budget refuses what the default takes.
TEST_F(TerrainBadInput, PaddedSideLimitIsAnOption) {
    const std::string file = write("small.pgm", "P5 30 2 255\n" + std::string(60, '\x09'));
    EXPECT_EQ(loadHeightfield(file).width(), 30);
    const Outcome o = loadInChild(file, {.maxPaddedSide = 17});
    EXPECT_THAT(o.message, ::testing::HasSubstr("PGM size 30x2 pads to a 33x33 grid (1089 "
                                                "samples), over the limit of 17x17 samples"));
}

// Bytes in memory go through the same decoders and limits as files.
TEST_F(TerrainBadInput, DecodeFromMemoryMatchesTheFileLoader) {
    const Bytes png = goodPng();
    const Heightfield fromFile = loadHeightfield(write("g.png", png));
    const Heightfield fromBytes = decodeHeightfield("g.png", png);
    ASSERT_EQ(fromBytes.width(), fromFile.width());
    for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 8; ++i) EXPECT_EQ(fromBytes.at(i, j), fromFile.at(i, j));
    const Bytes npy = npyOf("(2, 3)", {1, 2, 3, 4, 5, 6});
    EXPECT_EQ(decodeHeightfield("h.npy", npy).at(2, 1), 6.0f);
    const std::string pgm = "P5 30 2 255\n" + std::string(60, '\x09');
    try {
        decodeHeightfield("small.pgm", Bytes(pgm.begin(), pgm.end()), {.maxPaddedSide = 17});
        ADD_FAILURE() << "a PGM over the padded-side limit was decoded";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(),
                    ::testing::HasSubstr("small.pgm: PGM size 30x2 pads to a 33x33 grid"));
    }
    EXPECT_THROW(decodeHeightfield("x.tif", png), Error);
    EXPECT_THROW(decodeHeightfield("x.bmp", png), Error);
}

// Colour PNGs (zone maps) get the same CRC and size checks as heightmaps.
TEST_F(TerrainBadInput, RgbPngDecodeChecksCrcAndSize) {
    const uint8_t rgb[2 * 2 * 3] = {255, 0, 0, 0, 255, 0, 0, 0, 255, 9, 9, 9};
    ASSERT_TRUE(stbi_write_png(path("rgb.png").c_str(), 2, 2, 3, rgb, 2 * 3));
    std::ifstream in(path("rgb.png"), std::ios::binary);
    Bytes png((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const RgbImage image = decodePngRgb8("map", png);
    ASSERT_EQ(image.width, 2);
    ASSERT_EQ(image.height, 2);
    EXPECT_TRUE(std::equal(image.rgb.begin(), image.rgb.end(), std::begin(rgb)));
    Bytes badCrc = png;
    badCrc[8 + 8 + 13] ^= 0x01;  // the IHDR CRC
    EXPECT_THROW(decodePngRgb8("map", badCrc), Error);
    std::vector<Chunk> chunks = chunksOf(png);
    chunks[0].data = {0, 1, 0, 1, 0, 1, 0, 1, 8, 2, 0, 0, 0};  // 65537x65537 RGB
    try {
        decodePngRgb8("map", pngOf(chunks));
        ADD_FAILURE() << "a 65537x65537 header was decoded";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), ::testing::HasSubstr("over the limit of 16385x16385 samples"));
    }
    EXPECT_THROW(decodePngRgb8("map", Bytes{1, 2, 3}), Error);
}

}  // namespace
}  // namespace sierra::terrain
