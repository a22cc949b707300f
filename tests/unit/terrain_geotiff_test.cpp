// GeoTIFF loading, built with SIERRA_WITH_GDAL (on by default when GDAL is
// installed). The files are written with GDAL by the test.
#ifdef SIERRA_WITH_GDAL

#include <sierra/core/Error.h>
#include <sierra/terrain/HeightfieldIO.h>

#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogr_spatialref.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <limits>

using namespace sierra;

namespace {

std::string writeGeoTiff(const std::string& name, bool projected, bool withNoData) {
    GDALAllRegister();
    std::string path = (std::filesystem::temp_directory_path() / name).string();
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
    GDALDataset* data = driver->Create(path.c_str(), 4, 3, 1, GDT_Float32, nullptr);
    float values[12] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
    if (withNoData) values[5] = -9999.0f;
    EXPECT_EQ(
        data->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, 4, 3, values, 4, 3, GDT_Float32, 0, 0),
        CE_None);
    if (withNoData) data->GetRasterBand(1)->SetNoDataValue(-9999.0);
    if (projected) {
        double geo[6] = {500000.0, 25.0, 0.0, 4000000.0, 0.0, -25.0};
        data->SetGeoTransform(geo);
        OGRSpatialReference srs;
        srs.importFromEPSG(32633);  // UTM 33N, metres
        data->SetSpatialRef(&srs);
    }
    GDALClose(GDALDataset::ToHandle(data));
    return path;
}

TEST(TerrainGeoTiff, ValuesSpacingAndNoData) {
    std::string path = writeGeoTiff("sierra_geotiff_test.tif", true, true);
    terrain::Heightfield field = terrain::loadHeightfield(path);
    EXPECT_EQ(field.width(), 4);
    EXPECT_EQ(field.height(), 3);
    EXPECT_FLOAT_EQ(field.at(0, 0), 1.0f);
    EXPECT_FLOAT_EQ(field.at(3, 2), 12.0f);
    EXPECT_FLOAT_EQ(field.spacingX(), 25.0f);
    EXPECT_FLOAT_EQ(field.spacingZ(), 25.0f);
    ASSERT_TRUE(field.hasMask());
    EXPECT_FALSE(field.valid(1, 1));
    EXPECT_TRUE(field.valid(0, 0));
    EXPECT_TRUE(std::isfinite(field.at(1, 1)));
    // The geotransform and reference system are kept as the file has them.
    ASSERT_TRUE(field.georeference().has_value());
    EXPECT_EQ(field.georeference()->geoTransform,
              (std::array<double, 6>{500000.0, 25.0, 0.0, 4000000.0, 0.0, -25.0}));
    EXPECT_NE(field.georeference()->crsWkt.find("UTM zone 33N"), std::string::npos);
    std::filesystem::remove(path);
}

TEST(TerrainGeoTiff, UnprojectedKeepsUnitSpacingAndGarbageIsRejected) {
    std::string path = writeGeoTiff("sierra_geotiff_plain.tif", false, false);
    terrain::Heightfield field = terrain::loadHeightfield(path);
    EXPECT_FLOAT_EQ(field.spacingX(), 1.0f);
    EXPECT_FALSE(field.hasMask());
    std::filesystem::remove(path);
    std::string bad = (std::filesystem::temp_directory_path() / "sierra_geotiff_bad.tif").string();
    FILE* f = std::fopen(bad.c_str(), "wb");
    std::fputs("not a tiff", f);
    std::fclose(f);
    EXPECT_THROW(terrain::loadHeightfield(bad), Error);
    std::filesystem::remove(bad);
}

// A 4x3 float raster in WGS 84 (degrees), 3 arc-second pixels, its centre at
// `latitude`; `noData` set as the band's no-data value and stored at (2, 1).
std::string writeGeographic(const std::string& name, double latitude, double noData) {
    GDALAllRegister();
    std::string path = (std::filesystem::temp_directory_path() / name).string();
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
    GDALDataset* data = driver->Create(path.c_str(), 4, 3, 1, GDT_Float32, nullptr);
    float values[12] = {100, 200, 300, 400, 500, 600, 700, 800, 900, 1000, 1100, 1200};
    values[6] = float(noData);
    EXPECT_EQ(data->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, 4, 3, values, 4, 3, GDT_Float32, 0,
                                               0, nullptr),
              CE_None);
    data->GetRasterBand(1)->SetNoDataValue(noData);
    const double pixel = 1.0 / 1200.0;  // 3 arc-seconds
    double geo[6] = {10.0, pixel, 0.0, latitude + 1.5 * pixel, 0.0, -pixel};
    data->SetGeoTransform(geo);
    OGRSpatialReference srs;
    srs.importFromEPSG(4326);
    data->SetSpatialRef(&srs);
    GDALClose(GDALDataset::ToHandle(data));
    return path;
}

// Degrees become metres at the tile's latitude: one degree of WGS 84 spans
// 111 132 m north-south and 78 847 m east-west at 45 degrees, 110 574 m and
// 111 320 m at the equator (published reference values).
TEST(TerrainGeoTiff, GeographicDegreesGetMetricSpacingAtTheTilesLatitude) {
    std::string path = writeGeographic("sierra_geotiff_45.tif", 45.0, -9999.0);
    terrain::Heightfield field = terrain::loadHeightfield(path);
    EXPECT_NEAR(field.spacingX(), 78847.0 / 1200.0, 0.05);
    EXPECT_NEAR(field.spacingZ(), 111132.0 / 1200.0, 0.05);
    std::filesystem::remove(path);
    path = writeGeographic("sierra_geotiff_0.tif", 0.0, -9999.0);
    field = terrain::loadHeightfield(path);
    EXPECT_NEAR(field.spacingX(), 111320.0 / 1200.0, 0.05);
    EXPECT_NEAR(field.spacingZ(), 110574.0 / 1200.0, 0.05);
    std::filesystem::remove(path);
}

// No data comes from the band's no-data value, NaN included: masked and
// filled from the valid neighbours, not drawn as a -9999 m pit.
TEST(TerrainGeoTiff, NoDataValueBecomesTheMask) {
    for (double noData : {-9999.0, double(std::numeric_limits<float>::quiet_NaN())}) {
        std::string path = writeGeographic("sierra_geotiff_nodata.tif", 30.0, noData);
        terrain::Heightfield field = terrain::loadHeightfield(path);
        ASSERT_TRUE(field.hasMask()) << noData;
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 4; ++i) EXPECT_EQ(field.valid(i, j), !(i == 2 && j == 1)) << i << j;
        // Filled with the mean of its valid 4-neighbours: 300, 1100, 600, 800.
        EXPECT_FLOAT_EQ(field.at(2, 1), 700.0f);
        EXPECT_FLOAT_EQ(field.range().first, 100.0f);
        std::filesystem::remove(path);
    }
}

}  // namespace

#endif  // SIERRA_WITH_GDAL
