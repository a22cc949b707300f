// Overlay styles in the scene: presets found in the assets directory (or
// $SIERRA_ASSETS), --style and the curvature, line and hatch options, the same
// keys in a scene file over a preset, and clear errors for bad values.

#include <sierra/core/Error.h>
#include <sierra/scene/Options.h>
#include <sierra/scene/SceneJson.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <vector>

namespace sierra::scene {
namespace {

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

std::string parseError(const std::vector<std::string>& args) {
    try {
        parse(args);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(SceneOverlays, DefaultIsTheShadedTerrainAlone) {
    Scene s = parse({});
    EXPECT_TRUE(s.style.overlay.layers.shaded);
    EXPECT_FALSE(s.style.overlay.layers.lines || s.style.overlay.layers.hatch ||
                 s.style.overlay.layers.contours);
}

TEST(SceneOverlays, EveryPresetLoads) {
    for (char c = 'a'; c <= 'n'; ++c) {
        analysis::StyleParams p = loadPreset(std::string("fig3") + c);
        EXPECT_TRUE(p.layers.lines) << c;
        EXPECT_FALSE(p.layers.hatch) << c;
    }
    for (char c = 'a'; c <= 'h'; ++c) {
        analysis::StyleParams p = loadPreset(std::string("fig4") + c);
        EXPECT_TRUE(p.layers.hatch) << c;
    }
}

TEST(SceneOverlays, OptionsAfterAPresetOverrideIt) {
    Scene s = parse({"--hatch-length", "2", "--preset", "fig4a", "--curvature-scale", "9"});
    EXPECT_EQ(s.style.preset, "fig4a");
    EXPECT_TRUE(s.style.overlay.layers.hatch);
    EXPECT_FLOAT_EQ(s.style.overlay.hatch.length, 2.0f);
    EXPECT_FLOAT_EQ(s.style.overlay.curvature.scale, 9.0f);
    EXPECT_EQ(s.style.overlay.curvature.method, loadPreset("fig4a").curvature.method);
}

TEST(SceneOverlays, CurvatureScaleAutoAndBack) {
    Scene s = parse({"--preset", "fig3a", "--curvature-scale", "auto"});
    EXPECT_TRUE(s.style.overlay.autoScale);
    EXPECT_FLOAT_EQ(s.style.overlay.curvature.scale, loadPreset("fig3a").curvature.scale);
    Scene fixed = parse({"--curvature-scale", "auto", "--curvature-scale", "3"});
    EXPECT_FALSE(fixed.style.overlay.autoScale);
    EXPECT_FLOAT_EQ(fixed.style.overlay.curvature.scale, 3.0f);
    EXPECT_THAT(parseError({"--curvature-scale", "auto", "--levels", "0.1,0.9,1"}),
                HasSubstr("is auto, which picks the scale from the values"));
}

TEST(SceneOverlays, EveryOptionLandsInItsField) {
    Scene s = parse({"--style",
                     "lines,hatch,contours",
                     "--curvature",
                     "edge-angle",
                     "--curvature-distance",
                     "3",
                     "--normals",
                     "edge",
                     "--signed",
                     "--levels",
                     "0.1,0.8,2",
                     "--line-width",
                     "2.5",
                     "--min-length",
                     "7",
                     "--line-threshold",
                     "0.25",
                     "--hatch-width",
                     "1.5",
                     "--hatch-direction",
                     "across"});
    const analysis::StyleParams& o = s.style.overlay;
    EXPECT_FALSE(o.layers.shaded);
    EXPECT_TRUE(o.layers.lines && o.layers.hatch && o.layers.contours);
    EXPECT_EQ(o.curvature.method, analysis::CurvatureMethod::EdgeAngle);
    EXPECT_EQ(o.curvature.distance, 3);
    EXPECT_EQ(o.curvature.normals, analysis::NormalMethod::Edge);
    EXPECT_TRUE(o.curvature.signedValues);
    EXPECT_TRUE(o.curvature.levels.enabled);
    EXPECT_FLOAT_EQ(o.curvature.levels.white, 0.8f);
    EXPECT_FLOAT_EQ(o.curvature.levels.gamma, 2.0f);
    EXPECT_FLOAT_EQ(o.lines.width, 2.5f);
    EXPECT_EQ(o.lines.minLength, 7);
    EXPECT_FLOAT_EQ(o.lines.threshold, 0.25f);
    EXPECT_FLOAT_EQ(o.hatch.width, 1.5f);
    EXPECT_EQ(o.hatch.direction, analysis::HatchDirection::Across);
}

TEST(SceneOverlays, BadValuesGiveClearErrors) {
    EXPECT_THAT(parseError({"--preset", "fig5a"}),
                HasSubstr("unknown preset 'fig5a' (expected fig3a..fig3n"));
    EXPECT_THAT(parseError({"--curvature-distance", "0"}),
                HasSubstr("distance must be an integer >= 1"));
    EXPECT_THAT(parseError({"--curvature-scale", "-1"}),
                HasSubstr("scale must be finite and >= 0"));
    EXPECT_THAT(parseError({"--curvature", "four-normal"}),
                HasSubstr("unknown curvature method 'four-normal'"));
    EXPECT_THAT(parseError({"--style", "lines,shadows"}), HasSubstr("unknown layer 'shadows'"));
    EXPECT_THAT(parseError({"--hatch-length", "0"}), HasSubstr("style.hatch.length"));
    EXPECT_THAT(parseError({"--levels", "0.1,0.9"}), HasSubstr("expected BLACK,WHITE,GAMMA"));
}

TEST(SceneOverlays, SceneFileKeysOverAPreset) {
    Json json =
        Json::parse(R"({"style": {"preset": "fig3b", "lines": {"width": 3}, "contours": true}})");
    Scene s = sceneFromJson(json, "test.json");
    EXPECT_EQ(s.style.preset, "fig3b");
    EXPECT_TRUE(s.style.overlay.layers.lines);
    EXPECT_TRUE(s.style.overlay.layers.contours);
    EXPECT_FLOAT_EQ(s.style.overlay.lines.width, 3.0f);
    EXPECT_EQ(s.style.overlay.lines.minLength, loadPreset("fig3b").lines.minLength);
    // And back: the written scene reads as the same scene.
    EXPECT_EQ(sceneFromJson(sceneToJson(s), "again.json"), s);
    Json bad = Json::parse(R"({"style": {"curvature": {"method": "nope"}}})");
    EXPECT_THROW(sceneFromJson(bad, "bad.json"), Error);
}

TEST(SceneOverlays, AssetsDirectoryFromTheEnvironment) {
    ::setenv("SIERRA_ASSETS", "/nonexistent-sierra-assets", 1);
    std::string message;
    try {
        presetPath("fig3a");
    } catch (const Error& e) {
        message = e.what();
    }
    ::unsetenv("SIERRA_ASSETS");
    EXPECT_THAT(message, HasSubstr("/nonexistent-sierra-assets/presets/fig3a.json"));
    EXPECT_THAT(presetPath("fig3a"), HasSubstr("assets/presets/fig3a.json"));
}

}  // namespace
}  // namespace sierra::scene
