// GeoTIFF loading, built only with -DSIERRA_WITH_GDAL=ON.
#ifdef SIERRA_WITH_GDAL

#include <sierra/core/Error.h>
#include <sierra/terrain/HeightfieldIO.h>

#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <gtest/gtest.h>

#include <filesystem>

using namespace sierra;

namespace {

std::string writeGeoTiff(const std::string& name, bool projected, bool withNoData) {
    GDALAllRegister();
    std::string path = (std::filesystem::temp_directory_path() / name).string();
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
    GDALDataset* data = driver->Create(path.c_str(), 4, 3, 1, GDT_Float32, nullptr);
    float values[12] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
    if (withNoData) values[5] = -9999.0f;
    EXPECT_EQ(data->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, 4, 3, values, 4, 3, GDT_Float32, 0, 0), CE_None);
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

}  // namespace

#endif  // SIERRA_WITH_GDAL
