// Vector layers through OGR (terrain/Vector.h): features placed on the grid in
// sample coordinates, reprojected, filtered, labelled, and bad files refused.
// Built with SIERRA_WITH_GDAL (on by default when GDAL is installed).
#ifdef SIERRA_WITH_GDAL

#include "gdal_test_util.h"
#include "temp_dir_test_util.h"

#include <sierra/terrain/Vector.h>

#include <ogr_spatialref.h>

#include <gtest/gtest.h>

namespace sierra::test {
namespace {

using terrain::GridPlacement;
using terrain::VectorFeature;
using terrain::VectorReadOptions;

// A FeatureCollection in WGS 84 longitude, latitude (GeoJSON's own system).
std::string collection(const std::string& features) {
    return R"({"type": "FeatureCollection", "features": [)" + features + "]}";
}
std::string feature(const std::string& geometry, const std::string& properties = "{}") {
    return R"({"type": "Feature", "properties": )" + properties + R"(, "geometry": )" + geometry +
           "}";
}

class VectorLayers : public TempDirTest {};

// A geographic grid of 101 x 51 samples, 0.01 degrees apart, its top-left
// pixel corner at 10 E, 47 N: sample (i, j) is at 10.005 + 0.01 i E,
// 46.995 - 0.01 j N.
GridPlacement geographicGrid() {
    return {{10.0, 0.01, 0.0, 47.0, 0.0, -0.01}, wktOf(4326), 101, 51};
}

TEST_F(VectorLayers, FeaturesLandOnTheirSamples) {
    const std::string file = write(
        "mixed.geojson",
        collection(
            feature(R"({"type": "Point", "coordinates": [10.205, 46.895]})", R"({"name": "Hut"})") +
            "," +
            feature(
                R"({"type": "LineString", "coordinates": [[10.005, 46.995], [10.505, 46.745]]})",
                R"({"name": "River"})") +
            "," +
            feature(
                R"({"type": "Polygon", "coordinates": [[[10.1, 46.9], [10.3, 46.9], [10.3, 46.8], [10.1, 46.9]]]})",
                R"({"name": "Lake"})") +
            "," +
            feature(R"({"type": "MultiPoint", "coordinates": [[10.015, 46.985], [12.0, 46.9]]})",
                    R"({"name": "Pair"})")));
    auto layer =
        terrain::readVectorLayer(file, {.placement = geographicGrid(), .labelField = "name"});
    EXPECT_EQ(layer.read, 4);
    EXPECT_EQ(layer.outside, 0);
    EXPECT_FALSE(layer.reprojected);
    ASSERT_EQ(layer.features.size(), 4u);  // the multipoint's second point is off the grid
    const auto& hut = layer.features[0];
    EXPECT_EQ(hut.kind, VectorFeature::Kind::Point);
    EXPECT_EQ(hut.label, "Hut");
    EXPECT_NEAR(hut.parts[0][0].i, 20.0, 1e-6);
    EXPECT_NEAR(hut.parts[0][0].j, 10.0, 1e-6);
    const auto& river = layer.features[1];
    EXPECT_EQ(river.kind, VectorFeature::Kind::Line);
    ASSERT_EQ(river.parts[0].size(), 2u);
    EXPECT_NEAR(river.parts[0][0].i, 0.0, 1e-6);
    EXPECT_NEAR(river.parts[0][0].j, 0.0, 1e-6);
    EXPECT_NEAR(river.parts[0][1].i, 50.0, 1e-6);
    EXPECT_NEAR(river.parts[0][1].j, 25.0, 1e-6);
    EXPECT_EQ(layer.features[2].kind, VectorFeature::Kind::Polygon);
    EXPECT_EQ(layer.features[2].parts[0].front(), layer.features[2].parts[0].back());
    EXPECT_EQ(layer.features[3].label, "Pair");
    EXPECT_NEAR(layer.features[3].parts[0][0].i, 1.0, 1e-6);
    EXPECT_EQ(layer.vertices, 1 + 2 + 4 + 1);
}

TEST_F(VectorLayers, AUtmGridGetsGeographicLayersReprojected) {
    // UTM zone 33 N: 15 E is its central meridian, where easting is 500 km and
    // 45 N lies 4,982,950.4 m north of the equator (on WGS 84).
    GridPlacement utm{{499000.0, 100.0, 0.0, 4984000.0, 0.0, -100.0}, wktOf(32633), 41, 41};
    const std::string file = write(
        "point.geojson", collection(feature(R"({"type": "Point", "coordinates": [15.0, 45.0]})")));
    auto layer = terrain::readVectorLayer(file, {.placement = utm});
    EXPECT_TRUE(layer.reprojected);
    ASSERT_EQ(layer.features.size(), 1u);
    const auto p = layer.features[0].parts[0][0];
    EXPECT_NEAR(p.i, (500000.0 - 499000.0) / 100.0 - 0.5, 0.01);
    EXPECT_NEAR(p.j, (4984000.0 - 4982950.4) / 100.0 - 0.5, 0.01);
}

TEST_F(VectorLayers, FilterSelectsAndOffGridFeaturesAreCounted) {
    const std::string file = write(
        "roads.geojson",
        collection(feature(R"({"type": "LineString", "coordinates": [[10.1, 46.9], [10.2, 46.8]]})",
                           R"({"kind": "road"})") +
                   "," +
                   feature(R"({"type": "LineString", "coordinates": [[10.1, 46.9], [10.3, 46.9]]})",
                           R"({"kind": "river"})") +
                   "," +
                   feature(R"({"type": "LineString", "coordinates": [[20.0, 40.0], [20.1, 40.0]]})",
                           R"({"kind": "road"})")));
    auto roads =
        terrain::readVectorLayer(file, {.placement = geographicGrid(), .where = "kind = 'road'"});
    EXPECT_EQ(roads.read, 2);
    EXPECT_EQ(roads.outside, 1);
    EXPECT_EQ(roads.features.size(), 1u);
    // A layer wholly off the grid is no error: the caller warns.
    const std::string far = write(
        "far.geojson",
        collection(
            feature(R"({"type": "LineString", "coordinates": [[20.0, 40.0], [20.1, 40.0]]})")));
    auto off = terrain::readVectorLayer(far, {.placement = geographicGrid()});
    EXPECT_TRUE(off.features.empty());
    EXPECT_EQ(off.outside, 1);
}

TEST_F(VectorLayers, WithoutPlacementCoordinatesAreSamples) {
    const std::string file = write(
        "grid.geojson", collection(feature(R"({"type": "Point", "coordinates": [3.5, 7.25]})")));
    auto layer = terrain::readVectorLayer(file, {.width = 10, .height = 10});
    ASSERT_EQ(layer.features.size(), 1u);
    EXPECT_EQ(layer.features[0].parts[0][0], (terrain::GridPoint{3.5, 7.25}));
}

TEST(GeographicPositions, LongitudeLatitudeToSamples) {
    // 15 E, 45 N on the UTM zone 33 N grid of the reprojection test.
    GridPlacement utm{{499000.0, 100.0, 0.0, 4984000.0, 0.0, -100.0}, wktOf(32633), 41, 41};
    const auto p = terrain::geographicToSamples(utm, 15.0, 45.0);
    EXPECT_NEAR(p.i, 9.5, 0.01);
    EXPECT_NEAR(p.j, (4984000.0 - 4982950.4) / 100.0 - 0.5, 0.01);
    const auto q = terrain::geographicToSamples(geographicGrid(), 10.205, 46.895);
    EXPECT_NEAR(q.i, 20.0, 1e-6);
    EXPECT_NEAR(q.j, 10.0, 1e-6);
    GridPlacement none{{0.0, 1.0, 0.0, 0.0, 0.0, 1.0}, "", 10, 10};
    EXPECT_THROW(terrain::geographicToSamples(none, 15.0, 45.0), Error);
    EXPECT_THROW(terrain::geographicToSamples(utm, 15.0, 95.0), Error);
}

TEST_F(VectorLayers, BadFilesAreClearErrors) {
    const VectorReadOptions options{.placement = geographicGrid()};
    auto error = [&](const std::string& file, VectorReadOptions o) {
        return errorOf([&] { terrain::readVectorLayer(file, o); }, "no error");
    };
    EXPECT_NE(error(path("missing.geojson"), options).find("missing.geojson"), std::string::npos);
    EXPECT_NE(error(write("bad.geojson", std::string("{\"type\": \"FeatureCo")), options)
                  .find("cannot open"),
              std::string::npos);
    const std::string empty = write("empty.geojson", collection(""));
    EXPECT_NE(error(empty, options).find("no features"), std::string::npos);
    const std::string one =
        write("one.geojson", collection(feature(R"({"type": "Point", "coordinates": [10.2, 46.9]})",
                                                R"({"name": "A"})")));
    EXPECT_NE(
        error(one, {.placement = geographicGrid(), .where = "name ="}).find("not valid OGR SQL"),
        std::string::npos);
    EXPECT_NE(error(one, {.placement = geographicGrid(), .where = "name = 'B'"})
                  .find("no feature matches"),
              std::string::npos);
    const std::string fieldError =
        error(one, {.placement = geographicGrid(), .labelField = "title"});
    EXPECT_NE(fieldError.find("no field \"title\" (its fields: name)"), std::string::npos)
        << fieldError;
}

}  // namespace
}  // namespace sierra::test

#endif  // SIERRA_WITH_GDAL
