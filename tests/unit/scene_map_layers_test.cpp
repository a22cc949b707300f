// The scene's layers (scene/MapLayers.h): the command line's forms of drapes,
// vector layers and labels, and the checks of their values.

#include "temp_dir_test_util.h"

#include <sierra/scene/MapLayers.h>
#include <sierra/scene/Scene.h>

#include <gtest/gtest.h>

namespace sierra::test {
namespace {

using namespace sierra::scene;

std::string errorText(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

TEST(MapLayers, DrapeSpecsTakeAnOpacityAfterTheLastColon) {
    EXPECT_EQ(parseDrapeSpec("ortho.tif", "--drape").image, "ortho.tif");
    EXPECT_FLOAT_EQ(parseDrapeSpec("ortho.tif", "--drape").opacity, 1.0f);
    const auto d = parseDrapeSpec("ortho.tif:0.6", "--drape");
    EXPECT_EQ(d.image, "ortho.tif");
    EXPECT_FLOAT_EQ(d.opacity, 0.6f);
    // A colon that is not followed by a number is part of the path (GDAL's
    // virtual paths, a drive letter).
    EXPECT_EQ(parseDrapeSpec("/vsizip/a.zip/b:c.tif", "--drape").image, "/vsizip/a.zip/b:c.tif");
    EXPECT_NE(errorText([] { parseDrapeSpec("ortho.tif:1.5", "--drape"); }).find("0..1"),
              std::string::npos);
    EXPECT_NE(errorText([] { parseDrapeSpec(":0.5", "--drape"); }).find("no image"),
              std::string::npos);
}

TEST(MapLayers, VectorSpecsTakeAStyle) {
    EXPECT_EQ(parseVectorSpec("rivers.geojson", "--vector").file, "rivers.geojson");
    const auto dashed = parseVectorSpec("r.geojson:dash=8/4", "--vector");
    EXPECT_EQ(dashed.dashOn, 8.0f);
    EXPECT_EQ(dashed.dashOff, 4.0f);
    EXPECT_THROW(parseVectorSpec("r.geojson:dash=8", "--vector"), sierra::Error);
    const auto v = parseVectorSpec(
        "roads.gpkg:colour=#ff8000,width=3.5,opacity=0.8,fill=0,field=name", "--vector");
    EXPECT_EQ(v.file, "roads.gpkg");
    EXPECT_FLOAT_EQ(v.colour[0], 1.0f);
    EXPECT_NEAR(v.colour[1], 128.0f / 255.0f, 1e-6);
    EXPECT_FLOAT_EQ(v.colour[2], 0.0f);
    EXPECT_FLOAT_EQ(v.width, 3.5f);
    EXPECT_FLOAT_EQ(v.opacity, 0.8f);
    EXPECT_FLOAT_EQ(v.fillOpacity, 0.0f);
    EXPECT_EQ(v.labelField, "name");
    EXPECT_NE(errorText([] { parseVectorSpec("a.geojson:size=3", "--vector"); }).find("size=3"),
              std::string::npos);
    EXPECT_NE(
        errorText([] { parseVectorSpec("a.geojson:colour=red", "--vector"); }).find("#RRGGBB"),
        std::string::npos);
    EXPECT_NE(errorText([] { parseVectorSpec("a.geojson:width=wide", "--vector"); }).find("number"),
              std::string::npos);
}

TEST(MapLayers, LabelsGoAtWorldPlacesOrAtLongitudeAndLatitude) {
    const auto world = parseLabelSpec("Hut@120.5,-30", "--label");
    EXPECT_EQ(world.text, "Hut");
    EXPECT_FALSE(world.geographic);
    EXPECT_DOUBLE_EQ(world.x, 120.5);
    EXPECT_DOUBLE_EQ(world.z, -30.0);
    const auto geo = parseLabelSpec("Mont Blanc@6.865E,45.832N", "--label");
    EXPECT_EQ(geo.text, "Mont Blanc");
    EXPECT_TRUE(geo.geographic);
    EXPECT_DOUBLE_EQ(geo.x, 6.865);
    EXPECT_DOUBLE_EQ(geo.z, 45.832);
    const auto west = parseLabelSpec("a@b@3W,2S", "--label");  // the last @ splits
    EXPECT_EQ(west.text, "a@b");
    EXPECT_DOUBLE_EQ(west.x, -3.0);
    EXPECT_DOUBLE_EQ(west.z, -2.0);
    for (const char* bad : {"Hut", "@1,2", "Hut@1", "Hut@1,x", "Hut@3E,4", "Hut@3E,-4N"})
        EXPECT_NE(errorText([&] { parseLabelSpec(bad, "--label"); }).find("--label"),
                  std::string::npos)
            << bad;
}

TEST(MapLayers, BoundsAreFourNumbers) {
    EXPECT_EQ(parseBounds("0,10.5,-3,4e2", "--drape-bounds"),
              (std::array<double, 4>{0, 10.5, -3, 400}));
    EXPECT_THROW(parseBounds("0,1,2", "--drape-bounds"), Error);
    EXPECT_THROW(parseBounds("0,1,2,x", "--drape-bounds"), Error);
    EXPECT_THROW(parseBounds("0,1,2,3,4", "--drape-bounds"), Error);
}

TEST(MapLayers, TheSceneChecksItsLayers) {
    Scene scene;
    scene.layers.drapes.push_back({.image = "a.tif", .opacity = 0.5f});
    scene.layers.vectors.push_back({.file = "b.geojson"});
    scene.layers.labels.push_back({.text = "c", .x = 1.0, .z = 2.0});
    EXPECT_NO_THROW(validateScene(scene));
    auto bad = [&](auto change) {
        Scene s = scene;
        change(s);
        return errorText([&] { validateScene(s); });
    };
    EXPECT_NE(
        bad([](Scene& s) { s.layers.drapes[0].blend = "screen"; }).find("layers.drapes[0].blend"),
        std::string::npos);
    EXPECT_NE(
        bad([](Scene& s) { s.layers.vectors[0].width = 0.0f; }).find("layers.vectors[0].width"),
        std::string::npos);
    EXPECT_NE(bad([](Scene& s) {
                  s.layers.labels[0] = {.text = "x", .z = 95.0, .geographic = true};
              }).find("latitude"),
              std::string::npos);
    EXPECT_NE(bad([](Scene& s) { s.layers.furniture.textPixels = 2.0f; }).find("text_pixels"),
              std::string::npos);
}

}  // namespace
}  // namespace sierra::test
