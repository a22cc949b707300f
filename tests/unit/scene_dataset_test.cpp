// Dataset outputs without GL: the camera JSON and transforms.json from plain
// camera numbers (scene/CameraJson.h), the zone palette JSON, the scene's
// checks of the dataset outputs, and the georeference kept through padding.

#include <sierra/core/Error.h>
#include <sierra/scene/CameraJson.h>
#include <sierra/scene/Scene.h>
#include <sierra/terrain/Heightfield.h>
#include <sierra/terrain/Padding.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <numbers>
#include <string>

using namespace sierra;
using ::testing::HasSubstr;

namespace {

// A camera at (0, 10, 0) looking along -z (north), level: GL's view matrix is
// a translation by -10 in y; OpenCV's R turns y and z round.
scene::CameraRecord northCamera(double x) {
    scene::CameraRecord c;
    c.width = 64;
    c.height = 48;
    c.fx = c.fy = 50.0;
    c.cx = 32.0;
    c.cy = 24.0;
    c.fovYDegrees = 2.0 * std::atan(24.0 / 50.0) * 180.0 / std::numbers::pi;
    c.fovXDegrees = 2.0 * std::atan(32.0 / 50.0) * 180.0 / std::numbers::pi;
    c.view = {{{1, 0, 0, -x}, {0, 1, 0, -10}, {0, 0, 1, 0}, {0, 0, 0, 1}}};
    c.rotation = {{{1, 0, 0}, {0, -1, 0}, {0, 0, -1}}};
    c.translation = {-x, 10, 0};
    c.position = {x, 10, 0};
    c.nearPlane = 0.5;
    c.farPlane = 500.0;
    return c;
}

TEST(SceneDataset, CameraJsonHoldsKRtAndTheGlMatrices) {
    scene::CameraRecord c = northCamera(3.0);
    c.georeference =
        scene::CameraGeoreference{.geoTransform = {500000.0, 30.0, 0.0, 4100000.0, 0.0, -30.0},
                                  .crsWkt = "PROJCS[\"UTM\"]",
                                  .position = {500105.0, 4099985.0, 10.0}};
    const nlohmann::json j = nlohmann::json::parse(scene::cameraJson(c));
    EXPECT_EQ(j["model"], "perspective");
    EXPECT_EQ(j["width"], 64);
    EXPECT_EQ(j["K"], nlohmann::json::parse("[[50,0,32],[0,50,24],[0,0,1]]"));
    EXPECT_EQ(j["R"][1][1], -1.0);
    EXPECT_EQ(j["t"][0], -3.0);
    EXPECT_EQ(j["gl_view"][0][3], -3.0);
    EXPECT_EQ(j["near"], 0.5);
    EXPECT_EQ(j["far"], 500.0);
    EXPECT_EQ(j["pixel_centre"], 0.5);
    EXPECT_EQ(j["position_crs"][0], 500105.0);
    EXPECT_EQ(j["terrain"]["geotransform"][1], 30.0);
    EXPECT_EQ(j["terrain"]["crs_wkt"], "PROJCS[\"UTM\"]");
    EXPECT_FALSE(j.contains("pixel_size"));
    // Orthographic: the model says so and the pixel size replaces the fields of view.
    c.orthographic = true;
    c.pixelSize = 0.02;
    c.georeference.reset();
    const nlohmann::json o = nlohmann::json::parse(scene::cameraJson(c));
    EXPECT_EQ(o["model"], "orthographic");
    EXPECT_EQ(o["pixel_size"], 0.02);
    EXPECT_FALSE(o.contains("fov_y_degrees"));
    EXPECT_FALSE(o.contains("position_crs"));
}

TEST(SceneDataset, TransformsAreCameraToWorldInGlAxes) {
    const std::string text =
        scene::transformsJson({{"f_0000.png", northCamera(0.0)}, {"f_0001.png", northCamera(5.0)}});
    const nlohmann::json t = nlohmann::json::parse(text);
    EXPECT_EQ(t["w"], 64);
    EXPECT_EQ(t["h"], 48);
    EXPECT_EQ(t["fl_x"], 50.0);
    EXPECT_NEAR(t["camera_angle_x"].get<double>(), 2.0 * std::atan(32.0 / 50.0), 1e-12);
    ASSERT_EQ(t["frames"].size(), 2u);
    EXPECT_EQ(t["frames"][1]["file_path"], "f_0001.png");
    // The camera-to-world matrix of a camera at (5, 10, 0) with GL's axes
    // aligned to the world's: the identity rotation and its position.
    EXPECT_EQ(t["frames"][1]["transform_matrix"],
              nlohmann::json::parse("[[1,0,0,5],[0,1,0,10],[0,0,1,0],[0,0,0,1]]"));
    EXPECT_THROW(scene::transformsJson({}), Error);
    scene::CameraRecord other = northCamera(0.0);
    other.width = 32;
    EXPECT_THROW(scene::transformsJson({{"a.png", northCamera(0.0)}, {"b.png", other}}), Error);
}

TEST(SceneDataset, PaletteJsonListsIdNameAndColour) {
    zones::Palette palette;
    palette.surfaces = {{.name = "grass", .colour = 0x4f8f37},
                        {.name = "rock", .colour = 0x8c8782}};
    const nlohmann::json j = nlohmann::json::parse(scene::zonePaletteJson(palette));
    ASSERT_EQ(j["zones"].size(), 2u);
    EXPECT_EQ(j["zones"][1]["id"], 1);
    EXPECT_EQ(j["zones"][1]["name"], "rock");
    EXPECT_EQ(j["zones"][1]["colour"], "#8c8782");
    EXPECT_EQ(j["zones"][0]["rgb"], nlohmann::json::parse("[79,143,55]"));
}

std::string validationError(const scene::Scene& s) {
    try {
        scene::validateScene(s);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(SceneDataset, OutputsAreCheckedByExtension) {
    scene::Scene s;
    s.output.normals = "n.npy";
    s.output.mask = "m.png";
    s.output.camera = "c.json";
    s.output.transforms = "transforms.json";
    EXPECT_EQ(validationError(s), "");
    s.output.normals = "n.exr";
    s.output.normalsPrecision = "float16";
    s.output.normalsSpace = "world";
    EXPECT_EQ(validationError(s), "");

    scene::Scene bad = s;
    bad.output.normals = "n.png";
    EXPECT_THAT(validationError(bad), HasSubstr("--normals-out"));
    bad = s;
    bad.output.normalsSpace = "screen";
    EXPECT_THAT(validationError(bad), HasSubstr("must be camera or world"));
    bad = s;
    bad.output.normalsPrecision = "float64";
    EXPECT_THAT(validationError(bad), HasSubstr("float32 or float16"));
    bad = s;
    bad.output.mask = "m.exr";  // .exr holds float images: the normals only
    EXPECT_THAT(validationError(bad), HasSubstr(".exr holds float images"));
    bad = s;
    bad.output.camera = "c.txt";
    EXPECT_THAT(validationError(bad), HasSubstr("--camera-out"));
    bad = s;
    bad.output.mask = "c.json";
    EXPECT_THAT(validationError(bad), HasSubstr("--mask-out"));
    bad = s;
    bad.output.transforms = "c.json";  // the camera's own name
    EXPECT_THAT(validationError(bad), HasSubstr("each output needs its own file"));
    bad = s;
    bad.output.frame = "fly.mp4";
    EXPECT_THAT(validationError(bad), HasSubstr("is a video"));
    // Zone ids need zones.
    bad = s;
    bad.output.zoneIds = "z.png";
    EXPECT_THAT(validationError(bad), HasSubstr("needs zones"));
    bad.zones.map = "auto";
    EXPECT_EQ(validationError(bad), "");
}

TEST(SceneDataset, GeoreferenceSurvivesPaddingAndIsChecked) {
    terrain::Heightfield f(5, 3, 1.0f);
    f.setGeoreference(terrain::Heightfield::Georeference{{10.0, 2.0, 0.0, 20.0, 0.0, -2.0}, "W"});
    const terrain::Heightfield padded = terrain::padToPowerOfTwoPlusOne(f);
    EXPECT_EQ(padded.width(), 5);
    EXPECT_EQ(padded.height(), 5);
    EXPECT_EQ(padded.georeference(), f.georeference());
    EXPECT_THROW(f.setGeoreference(terrain::Heightfield::Georeference{{0, 0, 0, 0, 0, 0}, ""}),
                 Error);
    EXPECT_THROW(f.setGeoreference(terrain::Heightfield::Georeference{{NAN, 1, 0, 0, 0, 1}, ""}),
                 Error);
}

}  // namespace
