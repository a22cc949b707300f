// Imagery drapes (terrain/Drape.h): images placed over the grid's extent by
// their georeference, by bounds, or stretched; warped between systems;
// reduced to the texture limit; bad images refused. Built with
// SIERRA_WITH_GDAL (on by default when GDAL is installed).
#ifdef SIERRA_WITH_GDAL

#include "gdal_test_util.h"
#include "temp_dir_test_util.h"

#include <sierra/terrain/Drape.h>

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <gtest/gtest.h>

#include <array>
#include <functional>

namespace sierra::test {
namespace {

using terrain::DrapeBounds;
using terrain::DrapeOptions;
using terrain::GridPlacement;

using Colour = std::function<std::array<uint8_t, 4>(int x, int y)>;

// Writes a `bands`-band 8-bit image through GDAL's `driver` (GTiff, PNG),
// pixel (x, y) coloured by `colour` (its first `bands` channels, 255 beyond four), with a
// geotransform and system when given.
std::string writeImage(const std::string& path, const char* driver, int width, int height,
                       int bands, const Colour& colour,
                       const std::optional<std::array<double, 6>>& geo = std::nullopt,
                       const std::string& wkt = "") {
    GDALAllRegister();
    GDALDataset* mem = GetGDALDriverManager()->GetDriverByName("MEM")->Create(
        "", width, height, bands, GDT_Byte, nullptr);
    for (int b = 0; b < bands; ++b) {
        std::vector<uint8_t> plane(size_t(width) * height);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)  // bands past the fourth (a bad image): 255
                plane[size_t(y) * width + x] = b < 4 ? colour(x, y)[size_t(b)] : 255;
        EXPECT_EQ(mem->GetRasterBand(b + 1)->RasterIO(GF_Write, 0, 0, width, height, plane.data(),
                                                      width, height, GDT_Byte, 0, 0, nullptr),
                  CE_None);
    }
    if (geo) {
        auto g = *geo;
        mem->SetGeoTransform(g.data());
    }
    if (!wkt.empty()) mem->SetProjection(wkt.c_str());
    GDALDataset* out = GetGDALDriverManager()->GetDriverByName(driver)->CreateCopy(
        path.c_str(), mem, FALSE, nullptr, nullptr, nullptr);
    EXPECT_NE(out, nullptr) << path;
    GDALClose(out);
    GDALClose(mem);
    return path;
}

// 8-pixel squares, black and white.
std::array<uint8_t, 4> checker(int x, int y) {
    const uint8_t v = ((x / 8 + y / 8) % 2) ? 255 : 0;
    return {v, v, v, 255};
}

const uint8_t* texel(const terrain::DrapeImage& d, int x, int y) {
    return &d.rgba[(size_t(y) * d.width + x) * 4];
}

class Drapes : public TempDirTest {};

// A geographic grid of 64 x 32 samples, 0.01 degrees apart, pixel corners from
// 10 E, 47 N.
GridPlacement geographicGrid() {
    return {{10.0, 0.01, 0.0, 47.0, 0.0, -0.01}, wktOf(4326), 64, 32};
}

TEST_F(Drapes, AnImageOnTheGridsPixelsIsCopiedTexelForTexel) {
    const auto file =
        writeImage(path("ortho.tif"), "GTiff", 64, 32, 3, checker,
                   std::array<double, 6>{10.0, 0.01, 0.0, 47.0, 0.0, -0.01}, wktOf(4326));
    auto d = terrain::readDrape(file, {.placement = geographicGrid()});
    EXPECT_FALSE(d.stretched);
    EXPECT_FALSE(d.reprojected);
    ASSERT_EQ(d.width, 64);
    ASSERT_EQ(d.height, 32);
    EXPECT_DOUBLE_EQ(d.coverage, 1.0);
    int wrong = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 64; ++x) wrong += texel(d, x, y)[0] != checker(x, y)[0];
    EXPECT_EQ(wrong, 0);
}

TEST_F(Drapes, AnImageOverHalfTheGridLeavesTheOtherHalfClear) {
    // Twice the grid's resolution, over its west half.
    const auto file = writeImage(
        path("west.tif"), "GTiff", 64, 64, 4,
        [](int, int) {
            return std::array<uint8_t, 4>{200, 30, 30, 255};
        },
        std::array<double, 6>{10.0, 0.005, 0.0, 47.0, 0.0, -0.005}, wktOf(4326));
    auto d = terrain::readDrape(file, {.placement = geographicGrid()});
    ASSERT_EQ(d.width, 128);  // the image's resolution over the whole grid
    ASSERT_EQ(d.height, 64);
    EXPECT_NEAR(d.coverage, 0.5, 0.02);
    EXPECT_EQ(texel(d, 10, 30)[3], 255);
    EXPECT_EQ(texel(d, 10, 30)[0], 200);
    EXPECT_EQ(texel(d, 100, 30)[3], 0) << "the east half is clear";
}

TEST_F(Drapes, AUtmImageOnAGeographicGridIsWarped) {
    // A red 3x3 spot of 100 m pixels around 15 E, 45 N: easting 500,000 m and
    // northing 4,982,950.4 m in UTM zone 33 N.
    const double east = 500000.0, north = 4982950.4;
    const auto file = writeImage(
        path("utm.tif"), "GTiff", 200, 200, 3,
        [](int x, int y) {
            const bool spot = std::abs(x - 100) <= 1 && std::abs(y - 100) <= 1;
            return std::array<uint8_t, 4>{uint8_t(spot ? 255 : 0), 0, uint8_t(spot ? 0 : 255), 255};
        },
        std::array<double, 6>{east - 100.5 * 100.0, 100.0, 0.0, north + 100.5 * 100.0, 0.0, -100.0},
        wktOf(32633));
    // The grid: 0.1 degrees square around the spot, 0.002 degrees a sample.
    GridPlacement grid{{14.95, 0.002, 0.0, 45.05, 0.0, -0.002}, wktOf(4326), 50, 50};
    auto d = terrain::readDrape(file, {.placement = grid});
    EXPECT_TRUE(d.reprojected);
    EXPECT_FALSE(d.stretched);
    // The reddest texel sits where 15 E, 45 N falls: the grid's centre.
    int best = -1, bx = 0, by = 0;
    for (int y = 0; y < d.height; ++y)
        for (int x = 0; x < d.width; ++x)
            if (texel(d, x, y)[0] > best) best = texel(d, x, y)[0], bx = x, by = y;
    EXPECT_GT(best, 100);
    EXPECT_NEAR((bx + 0.5) / d.width, 0.5, 0.02);
    EXPECT_NEAR((by + 0.5) / d.height, 0.5, 0.02);
    EXPECT_LT(texel(d, 2, 2)[0], 50) << "blue away from the spot";

    // In strips of 7 rows: the same bytes, strip by strip, top first.
    std::vector<uint8_t> strips;
    int sized = 0, next = 0;
    const auto header = terrain::readDrapeStrips(
        file, {.placement = grid}, size_t(d.width) * 4 * 7,
        [&](const terrain::DrapeImage& size) { sized = size.width * size.height; },
        [&](const terrain::DrapeStrip& s) {
            EXPECT_EQ(s.row, next);
            EXPECT_LE(s.rows, 7);
            next += s.rows;
            strips.insert(strips.end(), s.rgba, s.rgba + size_t(s.width) * s.rows * 4);
        });
    EXPECT_EQ(sized, d.width * d.height);
    EXPECT_EQ(next, d.height);
    EXPECT_TRUE(header.rgba.empty());
    EXPECT_DOUBLE_EQ(header.coverage, d.coverage);
    EXPECT_EQ(strips, d.rgba);
}

TEST_F(Drapes, WithoutGeoreferenceAnImageIsStretchedOrPlacedByBounds) {
    const auto file = writeImage(path("plain.png"), "PNG", 32, 16, 3, checker);
    auto stretched = terrain::readDrape(file, {.placement = geographicGrid()});
    EXPECT_TRUE(stretched.stretched);
    EXPECT_EQ(stretched.width, 32);  // its own resolution over the grid
    EXPECT_EQ(stretched.height, 16);
    EXPECT_DOUBLE_EQ(stretched.coverage, 1.0);
    // Over the grid's east half, in samples (the grid's corners: -0.5 and 63.5).
    DrapeBounds east{DrapeBounds::Units::Samples, 31.5, -0.5, 63.5, 31.5};
    auto placed = terrain::readDrape(file, {.width = 64, .height = 32, .bounds = east});
    EXPECT_FALSE(placed.stretched);
    EXPECT_EQ(placed.width, 64);
    EXPECT_NEAR(placed.coverage, 0.5, 0.02);
    EXPECT_EQ(texel(placed, 10, 8)[3], 0);
    EXPECT_EQ(texel(placed, 40, 8)[3], 255);
    // The same in the grid's system.
    DrapeBounds crs{DrapeBounds::Units::Crs, 10.32, 47.0, 10.64, 46.68};
    auto inCrs = terrain::readDrape(file, {.placement = geographicGrid(), .bounds = crs});
    EXPECT_EQ(inCrs.rgba, placed.rgba);
}

TEST_F(Drapes, AnImageOverTheTextureLimitIsReduced) {
    const auto file = writeImage(path("big.png"), "PNG", 256, 128, 3, checker);
    auto d = terrain::readDrape(file, {.width = 64, .height = 32, .maxTexels = 100});
    EXPECT_EQ(d.reducedFrom, (std::array<int, 2>{256, 128}));
    EXPECT_EQ(d.width, 100);
    EXPECT_EQ(d.height, 50);
}

TEST_F(Drapes, BadImagesAreClearErrors) {
    const DrapeOptions options{.placement = geographicGrid()};
    auto error = [&](const std::string& file, const DrapeOptions& o) {
        return errorOf([&] { terrain::readDrape(file, o); }, "no error");
    };
    EXPECT_NE(error(path("missing.tif"), options).find("missing.tif"), std::string::npos);
    const auto good = writeImage(path("good.png"), "PNG", 16, 16, 3, checker);
    std::string bytes = read(good);
    bytes.resize(bytes.size() / 3);
    const auto truncated = write("truncated.png", bytes);
    EXPECT_NE(error(truncated, options), "no error");
    EXPECT_NE(
        error(write("text.png", std::string("not an image at all")), options).find("cannot read"),
        std::string::npos);
    const auto five = writeImage(path("five.tif"), "GTiff", 8, 8, 5, checker);
    EXPECT_NE(error(five, options).find("5 bands"), std::string::npos);
    DrapeBounds empty{DrapeBounds::Units::Samples, 3.0, 0.0, 3.0, 10.0};
    EXPECT_NE(error(good, {.placement = geographicGrid(), .bounds = empty}).find("empty"),
              std::string::npos);
    const auto far =
        writeImage(path("far.tif"), "GTiff", 8, 8, 3, checker,
                   std::array<double, 6>{100.0, 0.01, 0.0, 10.0, 0.0, -0.01}, wktOf(4326));
    EXPECT_NE(error(far, options).find("outside the terrain"), std::string::npos);
    DrapeBounds crs{DrapeBounds::Units::Crs, 0.0, 10.0, 10.0, 0.0};
    EXPECT_NE(error(good, {.width = 64, .height = 32, .bounds = crs}).find("georeferenced terrain"),
              std::string::npos);
}

}  // namespace
}  // namespace sierra::test

#endif  // SIERRA_WITH_GDAL
