// Scene files: save -> load gives the same scene and the same bytes, floats
// come back bit for bit, missing keys keep the base scene's values, and bad
// files (unknown key, wrong type, not JSON) are refused naming the file, the
// key path and the expected type.

// GCC 12 reports the std::string inside Scene::style.overlay as "maybe used
// uninitialized" where the tests' Scene temporaries are destroyed after
// inlining; every Scene here is value-initialised, so the warning is a false
// positive of that compiler, silenced for this file only.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#include "temp_dir_test_util.h"

#include <sierra/core/Error.h>
#include <sierra/scene/SceneJson.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>

namespace sierra::scene {
namespace {

namespace fs = std::filesystem;
using ::testing::AllOf;
using ::testing::HasSubstr;

class SceneJson : public test::TempDirTest {
  protected:
    // The message of the sierra::Error that loading `text` throws ("" if none).
    std::string loadError(const std::string& text) const {
        std::string file = write("bad.json", text);
        try {
            loadScene(file);
        } catch (const Error& e) {
            return e.what();
        }
        return "";
    }
};

// Every field away from its default, optionals present, awkward floats.
Scene unusualScene() {
    Scene s;
    s.terrain = {.heightmap = "dem/alps tile.npy",
                 .generateSize = 257,
                 .seed = std::numeric_limits<uint64_t>::max(),
                 .roughness = 0.1f,
                 .hurst = 0.85f,
                 .rawWidth = 20000,
                 .rawHeight = 3,
                 .spacing = 30.000002f,
                 .verticalScale = 1e-7f,
                 .seaLevel = {.mode = SeaLevel::Mode::Value, .value = -12.345678f},
                 .heightUnits = HeightUnits::Metres,
                 .channel = Channel::Luminance};
    s.camera = {.position = std::nullopt,
                .target = Vec3{256.5f, -3.0f, 1e6f},
                .azimuth = 359.99997f,
                .elevation = -89.5f,
                .distance = 3.4e38f,
                .fov = 1.0f / 3.0f,
                .projection = Projection::Orthographic};
    s.path = {
        .type = PathType::Keyframes,
        .frames = 240,
        .range = FrameRange{10, 19},
        .keyframes = {{.time = 0.0f, .position = {1, 2, 3}, .target = {4, 5, 6}},
                      {.time = 2.5f, .position = {-1e-3f, 7.25f, 0.3f}, .target = {0, 0, 0}}}};
    s.lighting = {.sunAzimuth = 90.0f,
                  .sunAltitude = 0.7f,
                  .ambient = 0.123456789f,
                  .fog = 0.0f,
                  .sky = {0.0f, 1.0f, 0.333f},
                  .shadows = false,
                  .skyLight = false,
                  .sunSize = 1.25f,
                  .horizonRadius = 5000.0f,
                  .sunTime = "2026-06-21T19:30:00+02:00",
                  .latitude = 46.5f,
                  .longitude = -7.25f,
                  .sunStep = 60.0f};
    s.lod = {.mode = LodMode::Full,
             .tau = 2.75f,
             .geomorph = false,
             .cull = false,
             .threads = 7,
             .mesh = "tin.obj"};
    s.output = {.width = 333,
                .height = 4097,
                .msaa = 8,
                .frame = "f/x.png",
                .debug = "",
                .depth = "d.npy",
                .alpha = true,
                .fps = 24,
                .videoCodec = "hevc",
                .crf = 18,
                .bitrate = 4000000000,  // beyond 32 bits
                .videoPreset = "slow",
                .pngCompression = PngCompression::Best,
                .jpegQuality = 42,
                .maxQueuedFrames = 5};
    s.style = {.wireframe = true};
    return s;
}

TEST_F(SceneJson, DefaultSceneRoundTripsByteForByte) {
    Scene s;
    saveScene(path("default.json"), s);
    Scene back = loadScene(path("default.json"));
    EXPECT_EQ(back, s);
    EXPECT_EQ(read(path("default.json")), sceneToText(s));
    saveScene(path("again.json"), back);
    EXPECT_EQ(read(path("again.json")), read(path("default.json")));
}

TEST_F(SceneJson, EveryFieldRoundTripsByteForByte) {
    Scene s = unusualScene();
    ASSERT_NE(s, Scene{});
    saveScene(path("a.json"), s);
    Scene back = sceneFromJson(readJsonFile(path("a.json")), "a.json");
    EXPECT_EQ(back, s);
    EXPECT_EQ(sceneToText(back), read(path("a.json")));
    // Optionals set in one direction must also clear in the other.
    Scene cleared = sceneFromJson(sceneToJson(Scene{}), "mem", s);
    EXPECT_EQ(cleared, Scene{});
}

TEST_F(SceneJson, FloatsComeBackBitForBit) {
    std::mt19937 rng(12345);
    std::uniform_int_distribution<uint32_t> bits;
    auto finite = [&] {
        for (;;)
            if (float f = std::bit_cast<float>(bits(rng)); std::isfinite(f)) return f;
    };
    // 5000 random floats, eight to a scene (each with its negation and its
    // neighbour towards zero).
    for (int round = 0; round < 625; ++round) {
        Scene s;
        const float f = finite();
        s.lighting.ambient = f;
        s.camera.position = Vec3{f, -f, std::nextafter(f, 0.0f)};
        s.camera.target = Vec3{finite(), finite(), finite()};
        s.lighting.sunAzimuth = finite();
        s.lighting.sunAltitude = finite();
        s.lod.tau = finite();
        Json parsed = Json::parse(sceneToText(s));
        Scene back = sceneFromJson(parsed, "mem");
        ASSERT_EQ(std::bit_cast<uint32_t>(back.lighting.ambient), std::bit_cast<uint32_t>(f)) << f;
        ASSERT_EQ(back.camera.position, s.camera.position) << f;
        ASSERT_EQ(back.camera.target, s.camera.target);
        ASSERT_EQ(std::bit_cast<uint32_t>(back.lighting.sunAzimuth),
                  std::bit_cast<uint32_t>(s.lighting.sunAzimuth));
        ASSERT_EQ(std::bit_cast<uint32_t>(back.lighting.sunAltitude),
                  std::bit_cast<uint32_t>(s.lighting.sunAltitude));
        ASSERT_EQ(std::bit_cast<uint32_t>(back.lod.tau), std::bit_cast<uint32_t>(s.lod.tau));
    }
    // Written short: the shortest decimal that reads back as the same float.
    Scene s;
    s.lighting.ambient = 0.32f;
    EXPECT_THAT(sceneToText(s), HasSubstr("\"ambient\": 0.32,"));
}

TEST_F(SceneJson, MissingKeysKeepTheBaseScene) {
    Scene base;
    base.output.msaa = 0;
    base.output.width = 1920;
    base.path.type = PathType::Orbit;
    Scene s = sceneFromJson(Json::parse(R"({"camera": {"fov": 30}, "output": {"height": 200}})"),
                            "mem", base);
    EXPECT_EQ(s.camera.fov, 30.0f);
    EXPECT_EQ(s.output.height, 200);
    EXPECT_EQ(s.output.width, 1920);
    EXPECT_EQ(s.output.msaa, 0);
    EXPECT_EQ(s.path.type, PathType::Orbit);
    EXPECT_EQ(sceneFromJson(Json::parse("{}"), "mem", base), base);
}

TEST_F(SceneJson, SeaLevelTakesAutoNoneOrAHeight) {
    auto sea = [](const char* text) {
        return sceneFromJson(Json::parse(msg(R"({"terrain": {"sea_level": )", text, "}}")), "mem")
            .terrain.seaLevel;
    };
    EXPECT_EQ(sea("\"auto\"").mode, SeaLevel::Mode::Auto);
    EXPECT_EQ(sea("\"none\"").mode, SeaLevel::Mode::None);
    EXPECT_EQ(sea("12.5").mode, SeaLevel::Mode::Value);
    EXPECT_EQ(sea("12.5").value, 12.5f);
    EXPECT_THROW(sea("\"deep\""), Error);
    EXPECT_THROW(sea("true"), Error);
}

TEST_F(SceneJson, UnknownKeyNamesKeyAndFile) {
    EXPECT_THAT(
        loadError(R"({"camera": {"fovy": 30}})"),
        AllOf(HasSubstr("bad.json"), HasSubstr("unknown key camera.fovy"), HasSubstr("fov")));
    EXPECT_THAT(loadError(R"({"cameras": {}})"),
                AllOf(HasSubstr("bad.json"), HasSubstr("unknown key cameras")));
    EXPECT_THAT(
        loadError(
            R"({"path": {"keyframes": [{"time": 0, "position": [0,0,0], "targ": [1,1,1]}]}})"),
        HasSubstr("unknown key path.keyframes[0].targ"));
}

TEST_F(SceneJson, WrongTypeNamesKeyFileAndExpectedType) {
    EXPECT_THAT(loadError(R"({"camera": {"fov": "wide"}})"),
                AllOf(HasSubstr("bad.json"), HasSubstr("camera.fov"),
                      HasSubstr("expected a number"), HasSubstr("got a string")));
    EXPECT_THAT(loadError(R"({"output": {"msaa": 4.5}})"),
                AllOf(HasSubstr("output.msaa"), HasSubstr("expected an integer")));
    EXPECT_THAT(loadError(R"({"lod": {"cull": 1}})"),
                AllOf(HasSubstr("lod.cull"), HasSubstr("true or false")));
    EXPECT_THAT(loadError(R"({"camera": {"position": [1, "2", 3]}})"),
                AllOf(HasSubstr("camera.position[1]"), HasSubstr("expected a number")));
    EXPECT_THAT(loadError(R"({"camera": {"target": [1, 2]}})"),
                AllOf(HasSubstr("camera.target"), HasSubstr("3 numbers")));
    EXPECT_THAT(loadError(R"({"terrain": {"seed": -1}})"),
                AllOf(HasSubstr("terrain.seed"), HasSubstr(">= 0")));
    EXPECT_THAT(loadError(R"({"style": []})"),
                AllOf(HasSubstr("style"), HasSubstr("expected an object")));
    EXPECT_THAT(loadError(R"({"lod": {"mode": "fast"}})"),
                AllOf(HasSubstr("lod.mode"), HasSubstr("sbt, full")));
    EXPECT_THAT(loadError(R"({"lighting": {"ambient": 1e39}})"),
                AllOf(HasSubstr("lighting.ambient"), HasSubstr("float range")));
    EXPECT_THAT(loadError(R"([1, 2])"),
                AllOf(HasSubstr("the top level"), HasSubstr("expected an object")));
}

TEST_F(SceneJson, NotJsonGivesTheParserPosition) {
    EXPECT_THAT(loadError("{\n  \"camera\": {\"fov\": 30,}\n}"),
                AllOf(HasSubstr("bad.json"), HasSubstr("not a JSON"), HasSubstr("line 2")));
    EXPECT_THAT(loadError(""), HasSubstr("bad.json"));
    // A number beyond double's range is refused the same way (found by fuzzing the palette reader).
    EXPECT_THAT(loadError("{\"lod\": {\"tau\": 3e58836}}"),
                AllOf(HasSubstr("bad.json"), HasSubstr("not a JSON")));
}

TEST_F(SceneJson, MissingFileIsNamed) {
    try {
        loadScene(path("nowhere.json"));
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("nowhere.json"));
    }
}

TEST_F(SceneJson, LoadSceneChecksRanges) {
    EXPECT_THAT(loadError(R"({"camera": {"fov": 200}})"),
                AllOf(HasSubstr("bad.json"), HasSubstr("camera.fov"), HasSubstr("(0, 180)")));
    EXPECT_THAT(loadError(R"({"lod": {"tau": 0}})"), HasSubstr("lod.tau"));
    EXPECT_THAT(loadError(R"({"path": {"frames": 10, "range": [4, 10]}})"),
                HasSubstr("path.range"));
    EXPECT_THAT(
        loadError(R"({"path": {"type": "keyframes", "keyframes": [{"time": 1}, {"time": 1}]}})"),
        HasSubstr("path.keyframes"));
    EXPECT_THAT(loadError(R"({"output": {"frame": "a.mp4", "fps": 0}})"),
                AllOf(HasSubstr("output.fps (--fps)"), HasSubstr("got 0")));
    EXPECT_THAT(loadError(R"({"output": {"frame": "a.mp4", "crf": 20, "bitrate": 8000000}})"),
                HasSubstr("excludes output.bitrate"));
    EXPECT_THAT(loadError(R"({"output": {"frame": "a.webm", "alpha": true}})"),
                HasSubstr("output.alpha (--alpha)"));
    EXPECT_THAT(loadError(R"({"output": {"frame": "a.avi"}})"),
                HasSubstr(".png, .jpg or .jpeg file or a video (.mp4, .mov, .mkv, .webm, .gif"));
}

}  // namespace
}  // namespace sierra::scene
