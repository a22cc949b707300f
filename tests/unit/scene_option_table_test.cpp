// The option table drives the command line and the scene file alike: every
// entry with a flag changes the scene, and every key comes back from the
// written file; the three JSON readers (scenes, styles, palettes) share one
// rule set for keys and numbers.

#include "temp_dir_test_util.h"

#include <sierra/core/Error.h>
#include <sierra/scene/OptionTable.h>
#include <sierra/scene/Options.h>
#include <sierra/scene/PaletteJson.h>
#include <sierra/scene/SceneJson.h>
#include <sierra/scene/StyleJson.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace sierra::scene {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

Scene parse(const std::vector<std::string>& args) {
    CLI::App app{"test"};
    Scene scene;
    SceneOptions options(app, scene, kAllOptions);
    std::vector<const char*> argv{"test"};
    for (const std::string& a : args) argv.push_back(a.c_str());
    app.parse(int(argv.size()), argv.data());
    options.apply();
    return scene;
}

template <typename F>
std::string errorOf(F f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

class OptionTable : public test::TempDirTest {
  protected:
    // A command line for each flag that gives it a value other than the
    // default (with what it needs beside it); a flag missing here fails the
    // test, so a new entry gets a case.
    std::map<std::string, std::vector<std::string>> samples() const {
        const std::string mesh = write("mesh.obj", "v 0 0 0\n");
        const std::string heightmap = write("hm.npy", "not read by the registrar");
        return {
            {"--heightmap", {"--heightmap", heightmap}},
            {"--generate", {"--generate", "257"}},
            {"--seed", {"--seed", "18446744073709551615"}},
            {"--roughness", {"--roughness", "0.7"}},
            {"--hurst", {"--hurst", "0.8"}},
            {"--raw-size", {"--raw-size", "20x30"}},
            {"--spacing", {"--spacing", "30"}},
            {"--vertical-scale", {"--vertical-scale", "2.5"}},
            {"--sea-level", {"--sea-level", "12.5"}},
            {"--height-units", {"--height-units", "m"}},
            {"--channel", {"--channel", "luminance"}},
            {"--camera-pos", {"--camera-pos", "1", "2.5", "3"}},
            {"--camera-target", {"--camera-target", "4", "5", "6.25"}},
            {"--azimuth", {"--azimuth", "210"}},
            {"--elevation", {"--elevation", "35"}},
            {"--distance", {"--distance", "900"}},
            {"--fov", {"--fov", "40"}},
            {"--ortho", {"--ortho"}},
            {"--path", {"--path", "orbit", "--frames", "4"}},
            {"--frames", {"--path", "orbit", "--frames", "12"}},
            {"--frame-count", {"--path", "orbit", "--frames", "2:3", "--frame-count", "10"}},
            {"--sun-azimuth", {"--sun-azimuth", "135"}},
            {"--sun-altitude", {"--sun-altitude", "30"}},
            {"--ambient", {"--ambient", "0.2"}},
            {"--fog", {"--fog", "0.01"}},
            {"--sky", {"--sky", "0.1,0.2,0.3"}},
            {"--shadows", {"--shadows", "off"}},
            {"--sky-light", {"--sky-light", "off"}},
            {"--sun-size", {"--sun-size", "1.5"}},
            {"--horizon-radius", {"--horizon-radius", "500"}},
            {"--sun-time",
             {"--sun-time", "2026-06-21T17:30:00Z", "--latitude", "45", "--longitude", "7"}},
            {"--latitude", {"--sun-time", "2026-06-21T17:30:00Z", "--latitude", "46.5"}},
            {"--longitude", {"--sun-time", "2026-06-21T17:30:00Z", "--longitude", "8.25"}},
            {"--sun-step", {"--sun-time", "2026-06-21T17:30:00Z", "--sun-step", "60"}},
            {"--lod", {"--lod", "full"}},
            {"--tau", {"--tau", "0.75"}},
            {"--no-geomorph", {"--no-geomorph"}},
            {"--no-cull", {"--no-cull"}},
            {"--threads", {"--threads", "3"}},
            {"--mesh", {"--mesh", mesh}},
            {"--size", {"--size", "64x48"}},
            {"--msaa", {"--msaa", "8"}},
            {"--out", {"--out", "x/frame.png"}},
            {"--depth-out", {"--depth-out", "x/depth.npy"}},
            {"--normals-out", {"--normals-out", "x/n.exr"}},
            {"--normals-space", {"--normals-space", "world"}},
            {"--normals-precision", {"--normals-precision", "float16"}},
            {"--zones-out", {"--zones", "auto", "--zones-out", "x/z.png"}},
            {"--mask-out", {"--mask-out", "x/m.png"}},
            {"--camera-out", {"--camera-out", "x/c.json"}},
            {"--transforms-out", {"--transforms-out", "x/transforms.json"}},
            {"--drape", {"--drape", "a.tif:0.5", "--drape", "b.png:multiply"}},
            {"--drape-bounds", {"--drape", "a.tif", "--drape-bounds", "0,0,10,10"}},
            {"--drape-bounds-units",
             {"--drape", "a.tif", "--drape-bounds", "0,1,2,0", "--drape-bounds-units", "crs"}},
            {"--vector", {"--vector", "r.geojson:colour=#ff0000,width=3", "--vector", "s.gpkg"}},
            {"--vector-where", {"--vector", "r.geojson", "--vector-where", "kind = 'river'"}},
            {"--label-field", {"--vector", "r.geojson", "--label-field", "name"}},
            {"--label", {"--label", "Hut@10,20", "--label", "Peak@6.8E,45.8N"}},
            {"--scale-bar", {"--scale-bar"}},
            {"--north-arrow", {"--north-arrow"}},
            {"--title", {"--title", "A valley"}},
            {"--legend", {"--legend"}},
            {"--text-size", {"--text-size", "20"}},
            {"--title-corner", {"--title", "T", "--title-corner", "bottom-right"}},
            {"--scale-bar-corner", {"--scale-bar", "--scale-bar-corner", "top-left"}},
            {"--north-arrow-corner", {"--north-arrow", "--north-arrow-corner", "bottom-left"}},
            {"--legend-corner", {"--legend", "--legend-corner", "top-right"}},
            {"--alpha", {"--alpha"}},
            {"--png-compression", {"--png-compression", "best"}},
            {"--jpeg-quality", {"--jpeg-quality", "70"}},
            {"--max-queued-frames", {"--max-queued-frames", "5"}},
            {"--fps", {"--out", "a.mp4", "--fps", "24"}},
            {"--crf", {"--out", "a.mp4", "--crf", "20"}},
            {"--bitrate", {"--out", "a.mp4", "--bitrate", "8M"}},
            {"--video-codec", {"--out", "a.mp4", "--video-codec", "hevc"}},
            {"--video-preset", {"--out", "a.mp4", "--video-preset", "slow"}},
            {"--debug-out", {"--debug-out", "x/debug.png"}},
            {"--snapshot", {"--snapshot", "x/snap.png"}},
            {"--no-debug", {"--no-debug"}},
            {"--snapshot-only", {"--snapshot-only", "x/only.png"}},
            {"--snapshot-every", {"--path", "orbit", "--frames", "4", "--snapshot-every", "2"}},
            {"--snapshot-deterministic", {"--snapshot-deterministic"}},
            {"--zones", {"--zones", "auto"}},
            {"--palette", {"--zones", "auto", "--palette", "p.json"}},
            {"--band", {"--zones", "auto", "--band", "2"}},
            {"--zone-epsilon", {"--zones", "auto", "--zone-epsilon", "1.5"}},
            {"--deep-water", {"--zones", "auto", "--deep-water", "0.3"}},
            {"--sand-top", {"--zones", "auto", "--sand-top", "0.05"}},
            {"--zone-snow-line", {"--zones", "auto", "--zone-snow-line", "0.8"}},
            {"--rock-slope", {"--zones", "auto", "--rock-slope", "30"}},
            {"--blend", {"--zones", "auto", "--blend", "linear"}},
            {"--triplanar", {"--zones", "auto", "--triplanar"}},
            {"--no-tile-variation", {"--zones", "auto", "--no-tile-variation"}},
            {"--debug-view", {"--zones", "auto", "--debug-view", "bands"}},
            {"--wireframe", {"--wireframe"}},
            {"--colour-by", {"--colour-by", "level"}},
            {"--display", {"--display", "points,wireframe"}},
            {"--tree-line", {"--tree-line", "1500"}},
            {"--snow-line", {"--snow-line", "2500"}},
            {"--cpt", {"--cpt", "x.cpt"}},
            {"--preset", {"--preset", "fig3a"}},
            {"--style", {"--style", "shaded,lines"}},
            {"--curvature", {"--curvature", "edge-angle"}},
            {"--curvature-distance", {"--curvature-distance", "2"}},
            {"--curvature-scale", {"--curvature-scale", "4"}},
            {"--normals", {"--normals", "edge"}},
            {"--signed", {"--signed"}},
            {"--levels", {"--levels", "0.1,0.9,1.5"}},
            {"--line-width", {"--line-width", "2"}},
            {"--min-length", {"--min-length", "7"}},
            {"--line-threshold", {"--line-threshold", "0.25"}},
            {"--hatch-length", {"--hatch-length", "1.5"}},
            {"--hatch-width", {"--hatch-width", "3"}},
            {"--hatch-direction", {"--hatch-direction", "across"}},
        };
    }
};

// Every flag changes the scene, and the changed scene comes back from its
// JSON text unchanged: CLI -> scene -> JSON -> scene.
TEST_F(OptionTable, EveryEntryRoundTripsFromTheCommandLineThroughJson) {
    const auto cases = samples();
    const Scene defaults;
    std::set<std::string> flags;
    for (const OptionEntry& e : optionTable()) {
        if (e.flag.empty()) continue;
        EXPECT_TRUE(flags.insert(e.flag).second) << e.flag << " is in the table twice";
        auto it = cases.find(e.flag);
        ASSERT_NE(it, cases.end()) << e.flag << " has no case in this test";
        const Scene s = parse(it->second);
        EXPECT_NE(s, defaults) << e.flag << " changed nothing";
        if (!e.key.empty()) {
            EXPECT_NE(e.toJson(s), e.toJson(defaults)) << e.flag << " did not reach " << e.key;
        }
        const std::string text = sceneToText(s);
        const Scene back = sceneFromJson(parseJson(text, "t.json"), "t.json");
        EXPECT_EQ(back, s) << e.flag;
        EXPECT_EQ(sceneToText(back), text) << e.flag;
    }
    EXPECT_EQ(flags.size(), cases.size());
}

// Every key is written, and a file giving only that key (with its value from
// a changed scene) changes the default scene in that key alone.
TEST_F(OptionTable, EveryKeyIsWrittenAndReadOnItsOwn) {
    Scene changed = parse({"--generate",
                           "257",
                           "--seed",
                           "9",
                           "--roughness",
                           "0.5",
                           "--hurst",
                           "0.8",
                           "--raw-size",
                           "20x30",
                           "--spacing",
                           "30",
                           "--sea-level",
                           "none",
                           "--height-units",
                           "m",
                           "--channel",
                           "r",
                           "--camera-pos",
                           "1",
                           "2",
                           "3",
                           "--camera-target",
                           "4",
                           "5",
                           "6",
                           "--fov",
                           "40",
                           "--ortho",
                           "--path",
                           "orbit",
                           "--frames",
                           "2:3",
                           "--frame-count",
                           "10",
                           "--sun-time",
                           "2026-06-21T17:30:00Z",
                           "--latitude",
                           "45",
                           "--longitude",
                           "7",
                           "--sun-step",
                           "30",
                           "--ambient",
                           "0.2",
                           "--fog",
                           "0.01",
                           "--sky",
                           "0.1,0.2,0.3",
                           "--shadows",
                           "off",
                           "--sky-light",
                           "off",
                           "--sun-size",
                           "1",
                           "--horizon-radius",
                           "9",
                           "--lod",
                           "full",
                           "--tau",
                           "2",
                           "--no-geomorph",
                           "--no-cull",
                           "--threads",
                           "2",
                           "--mesh",
                           write("m.obj", ""),
                           "--size",
                           "64x48",
                           "--msaa",
                           "0",
                           "--out",
                           "a.png",
                           "--depth-out",
                           "d.npy",
                           "--alpha",
                           "--png-compression",
                           "best",
                           "--jpeg-quality",
                           "50",
                           "--max-queued-frames",
                           "3",
                           "--debug-out",
                           "b.png",
                           "--snapshot-only",
                           "c.png",
                           "--snapshot-every",
                           "2",
                           "--snapshot-deterministic",
                           "--zones",
                           "auto",
                           "--palette",
                           "p.json",
                           "--band",
                           "2",
                           "--zone-epsilon",
                           "1",
                           "--blend",
                           "linear",
                           "--triplanar",
                           "--no-tile-variation",
                           "--debug-view",
                           "zones",
                           "--deep-water",
                           "0.3",
                           "--sand-top",
                           "0.1",
                           "--zone-snow-line",
                           "0.9",
                           "--rock-slope",
                           "40",
                           "--display",
                           "points,wireframe",
                           "--colour-by",
                           "error",
                           "--tree-line",
                           "1000",
                           "--snow-line",
                           "1200",
                           "--cpt",
                           "x.cpt"});
    // Fields that the command line above excludes or replaces, set directly
    // (the file is not checked here).
    changed.terrain.heightmap = "h.npy";
    changed.terrain.verticalScale = 2.0f;
    changed.camera.azimuth = 10.0f;
    changed.camera.elevation = 20.0f;
    changed.camera.distance = 30.0f;
    changed.lighting.sunAzimuth = 100.0f;
    changed.lighting.sunAltitude = 10.0f;
    changed.path.keyframes = {{0.0f, {1, 2, 3}, {0, 0, 0}}, {1.0f, {4, 5, 6}, {0, 0, 0}}};
    changed.output.crf = 20;
    changed.output.fps = 12;
    changed.output.videoCodec = "hevc";
    changed.output.videoPreset = "slow";
    changed.output.bitrate = 8000000;  // with crf: the file is not checked here
    changed.output.normals = "n.npy";
    changed.output.normalsSpace = "world";
    changed.output.normalsPrecision = "float16";
    changed.output.zoneIds = "z.png";
    changed.output.mask = "m.png";
    changed.output.camera = "c.json";
    changed.output.transforms = "t.json";
    changed.layers.drapes = {{.image = "a.tif",
                              .opacity = 0.5f,
                              .blend = "multiply",
                              .bounds = std::array<double, 4>{0, 1, 2, 3},
                              .boundsUnits = "crs"}};
    changed.layers.vectors = {
        {.file = "r.geojson", .where = "a = 1", .labelField = "name", .width = 3.0f}};
    changed.layers.labels = {{.text = "Hut", .x = 1.0, .z = 2.0, .geographic = true}};
    changed.layers.furniture = {.scaleBar = true,
                                .northArrow = true,
                                .title = "T",
                                .legend = true,
                                .textPixels = 20.0f,
                                .titleCorner = FrameCorner::BottomRight,
                                .scaleBarCorner = FrameCorner::TopRight,
                                .northArrowCorner = FrameCorner::BottomLeft,
                                .legendCorner = FrameCorner::TopLeft};
    const Scene defaults;
    const Json written = sceneToJson(changed);
    for (const OptionEntry& e : optionTable()) {
        if (e.key.empty()) continue;
        const size_t dot = e.key.find('.');
        const std::string part = e.key.substr(0, dot), leaf = e.key.substr(dot + 1);
        ASSERT_TRUE(written.contains(part) && written[part].contains(leaf)) << e.key;
        EXPECT_NE(e.toJson(changed), e.toJson(defaults)) << e.key << " is not changed here";
        Json one = Json::object();
        one[part][leaf] = written[part][leaf];
        const Scene s = sceneFromJson(one, "one.json");
        EXPECT_EQ(e.toJson(s), e.toJson(changed)) << e.key;
        Scene expected = defaults;
        e.fromJson(expected, JsonObject(one, "", "one.json"), one[part][leaf], e.key);
        EXPECT_EQ(s, expected) << e.key;
    }
}

TEST_F(OptionTable, SceneFilesFollowTheNumberAndKeyRules) {
    auto scene = [](const std::string& text) {
        return sceneFromJson(parseJson(text, "s.json"), "s.json");
    };
    EXPECT_EQ(scene(R"({"output": {"msaa": 2.0}})").output.msaa, 2);
    EXPECT_EQ(scene(R"({"terrain": {"seed": 5.0}})").terrain.seed, 5u);
    EXPECT_THAT(errorOf([&] { scene(R"({"output": {"msaa": 5.5}})"); }),
                AllOf(HasSubstr("s.json: output.msaa"), HasSubstr("expected an integer")));
    EXPECT_THAT(errorOf([&] { scene(R"({"camera": {"fov": NaN}})"); }),
                AllOf(HasSubstr("s.json"), HasSubstr("not a JSON file")));
    Json nan = {{"camera", {{"fov", std::nan("")}}}};
    EXPECT_THAT(errorOf([&] { sceneFromJson(nan, "s.json"); }),
                AllOf(HasSubstr("camera.fov"), HasSubstr("finite")));
    EXPECT_THAT(errorOf([&] { scene(R"({"camera": {"fovy": 30}})"); }),
                AllOf(HasSubstr("unknown key camera.fovy"), HasSubstr("did you mean fov?"),
                      HasSubstr("expected one of: position, target")));
    EXPECT_THAT(errorOf([&] { scene(R"({"output": {"jpegQuality": 50}})"); }),
                HasSubstr("unknown key output.jpegQuality: keys are snake_case, use "
                          "output.jpeg_quality"));
}

TEST_F(OptionTable, StylesFollowTheNumberAndKeyRules) {
    auto style = [](const std::string& text) {
        return styleFromJson(parseJson(text, "t.json"), "t.json");
    };
    EXPECT_EQ(style(R"({"curvature": {"distance": 2.0}})").curvature.distance, 2);
    EXPECT_THAT(errorOf([&] { style(R"({"curvature": {"distance": 2.5}})"); }),
                AllOf(HasSubstr("t.json: style.curvature.distance"),
                      HasSubstr("expected an integer >= 1")));
    EXPECT_THAT(errorOf([&] { style(R"({"lines": {"width": NaN}})"); }),
                HasSubstr("not a JSON file"));
    Json nan = {{"hatch", {{"width", std::nan("")}}}};
    EXPECT_THAT(errorOf([&] { styleFromJson(nan, "t.json"); }),
                AllOf(HasSubstr("style.hatch.width"), HasSubstr("finite")));
    EXPECT_THAT(errorOf([&] { style(R"({"lines": {"minLength": 3}})"); }),
                HasSubstr("keys are snake_case, use style.lines.min_length"));
    EXPECT_THAT(
        errorOf([&] { style(R"({"hatch": {"lenght": 1}})"); }),
        AllOf(HasSubstr("unknown key style.hatch.lenght"), HasSubstr("did you mean length?")));
    // A scene file's style object holds the same keys under the same rules.
    EXPECT_THAT(errorOf([&] {
                    sceneFromJson(parseJson(R"({"style": {"lines": {"min_length": 4.5}}})", "s"),
                                  "s");
                }),
                HasSubstr("style.lines.min_length: expected an integer"));
}

TEST_F(OptionTable, PalettesFollowTheNumberAndKeyRules) {
    std::filesystem::create_directories(dir_ / "tiles");
    write("tiles/a.png", "x");
    auto palette = [&](const std::string& zone, const std::string& top = "") {
        return parsePalette(R"({)" + top + R"("zones": [{"name": "a", "colour": "#ff0000",
                            "tile": "tiles/a.png")" +
                                zone + "}]}",
                            dir_.string(), "p.json");
    };
    EXPECT_EQ(palette(R"(, "tile_size": 8.0)").surfaces[0].tileSize, 8.0f);
    EXPECT_EQ(palette("", R"("band_width": 3, )").bandWidth, 3.0f);
    EXPECT_THAT(errorOf([&] { palette(R"(, "tileSize": 8)"); }),
                HasSubstr("unknown key zones[0].tileSize: keys are snake_case, use "
                          "zones[0].tile_size"));
    EXPECT_THAT(errorOf([&] { palette("", R"("bandWidth": 3, )"); }),
                HasSubstr("keys are snake_case, use band_width"));
    EXPECT_THAT(errorOf([&] { palette(R"(, "height_blend": NaN)"); }),
                HasSubstr("not a JSON file"));
    EXPECT_THAT(errorOf([&] { palette(R"(, "height_blend": 2)"); }),
                AllOf(HasSubstr("zones[0].height_blend"), HasSubstr("must be in [0, 1]")));
    EXPECT_THAT(errorOf([&] { palette(R"(, "tiles": "x")"); }),
                AllOf(HasSubstr("unknown key zones[0].tiles"), HasSubstr("did you mean tile?")));
    // The writer's keys read back.
    const zones::Palette p = palette(R"(, "tile_size": 4, "height_blend": 0.25)");
    const zones::Palette back = parsePalette(paletteToJson(p), "", "back.json", false);
    EXPECT_EQ(back.surfaces[0].tileSize, 4.0f);
    EXPECT_EQ(back.surfaces[0].heightBlend, 0.25f);
}

}  // namespace
}  // namespace sierra::scene
