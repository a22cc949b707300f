// The command-line registrar: each option lands in its field, a --config file
// is overridden only by options actually given, --frames A:B selects part of a
// sequence, and bad values are refused with one clear message.

#include "temp_dir_test_util.h"

#include <sierra/core/Error.h>
#include <sierra/scene/Options.h>
#include <sierra/scene/SceneJson.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

namespace sierra::scene {
namespace {

namespace fs = std::filesystem;
using ::testing::AllOf;
using ::testing::HasSubstr;

// Parses `args` as a command line of an app with `defaults` and `groups`, and
// the app's own scene options `program` (apply(program)), if any.
Scene parse(const std::vector<std::string>& args, const Scene& defaults = {},
            unsigned groups = kAllOptions, bool* printed = nullptr,
            const std::function<void(Scene&)>& program = {}) {
    CLI::App app{"test"};
    Scene scene = defaults;
    SceneOptions options(app, scene, groups);
    std::vector<const char*> argv{"test"};
    for (const std::string& a : args) argv.push_back(a.c_str());
    app.parse(int(argv.size()), argv.data());
    if (program)
        options.apply(program);
    else
        options.apply();
    if (printed) *printed = options.printConfigRequested();
    return scene;
}

// The sierra::Error message of parsing `args` ("" if none).
std::string parseError(const std::vector<std::string>& args, const Scene& defaults = {}) {
    try {
        parse(args, defaults);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

class SceneOptionsTest : public test::TempDirTest {
  protected:
    void SetUp() override {
        TempDirTest::SetUp();
        heightmap_ = write("hm.npy", "not read by the registrar");
    }

    std::string heightmap_;
};

TEST_F(SceneOptionsTest, NoOptionsKeepTheAppDefaults) {
    Scene defaults;
    defaults.output.msaa = 0;
    defaults.output.width = 1920;
    defaults.path = {.type = PathType::Orbit, .frames = 60};
    EXPECT_EQ(parse({}, defaults), defaults);
    EXPECT_EQ(parse({}), Scene{});
}

TEST_F(SceneOptionsTest, EveryOptionLandsInItsField) {
    Scene want;
    want.terrain = {.heightmap = heightmap_,
                    .generateSize = 1025,
                    .seed = 18446744073709551615ull,
                    .roughness = 0.5f,
                    .hurst = 0.8f,
                    .rawWidth = 20000,
                    .rawHeight = 3,
                    .spacing = 30.0f,
                    .verticalScale = 2.5f,
                    .seaLevel = {.mode = SeaLevel::Mode::Value, .value = -4.5f},
                    .heightUnits = HeightUnits::Metres,
                    .channel = Channel::Green};
    want.camera = {.position = Vec3{-5.0f, 10.0f, -3.25f},
                   .target = Vec3{1.0f, 2.0f, 3.0f},
                   .fov = 60.0f,
                   .projection = Projection::Orthographic};
    want.path = {.type = PathType::Flyover, .frames = 10, .range = FrameRange{3, 5}};
    want.lighting = {.sunAzimuth = 90.0f,
                     .sunAltitude = 10.0f,
                     .ambient = 0.5f,
                     .fog = 0.0f,
                     .sky = {0.1f, 0.2f, 0.3f}};
    want.lod = {.mode = LodMode::Full, .tau = 2.5f, .geomorph = false, .cull = false, .threads = 3};
    want.output = {.width = 640,
                   .height = 480,
                   .msaa = 2,
                   .frame = "a.png",
                   .debug = "",
                   .depth = "d.npy",
                   .alpha = true};
    want.style.wireframe = true;
    Scene got = parse({"--heightmap",
                       heightmap_,
                       "--seed",
                       "18446744073709551615",
                       "--roughness",
                       "0.5",
                       "--hurst",
                       "0.8",
                       "--raw-size",
                       "20000x3",
                       "--spacing",
                       "30",
                       "--vertical-scale",
                       "2.5",
                       "--sea-level",
                       "-4.5",
                       "--height-units",
                       "m",
                       "--channel",
                       "g",
                       "--camera-pos",
                       "-5",
                       "10",
                       "-3.25",
                       "--camera-target",
                       "1",
                       "2",
                       "3",
                       "--fov",
                       "60",
                       "--ortho",
                       "--path",
                       "flyover",
                       "--frames",
                       "3:5",
                       "--frame-count",
                       "10",
                       "--sun-azimuth",
                       "90",
                       "--sun-altitude",
                       "10",
                       "--ambient",
                       "0.5",
                       "--fog",
                       "0",
                       "--sky",
                       "0.1,0.2,0.3",
                       "--lod",
                       "full",
                       "--tau",
                       "2.5",
                       "--no-geomorph",
                       "--no-cull",
                       "--threads",
                       "3",
                       "--size",
                       "640x480",
                       "--msaa",
                       "2",
                       "--out",
                       "a.png",
                       "--no-debug",
                       "--depth-out",
                       "d.npy",
                       "--alpha",
                       "--wireframe"});
    EXPECT_EQ(got, want);
    EXPECT_EQ(sceneToText(got), sceneToText(want));
}

TEST_F(SceneOptionsTest, RemainingOptionsLandInTheirFields) {
    Scene s = parse({"--generate", "257", "--azimuth", "30", "--elevation", "45", "--distance",
                     "900", "--debug-out", "dbg.png", "--sea-level", "none", "--frames", "7",
                     "--path", "orbit"});
    EXPECT_TRUE(s.terrain.heightmap.empty());
    EXPECT_EQ(s.terrain.generateSize, 257);
    EXPECT_EQ(s.camera.azimuth, 30.0f);
    EXPECT_EQ(s.camera.elevation, 45.0f);
    EXPECT_EQ(s.camera.distance, 900.0f);
    EXPECT_EQ(s.output.debug, "dbg.png");
    EXPECT_EQ(s.terrain.seaLevel.mode, SeaLevel::Mode::None);
    EXPECT_EQ(s.path.frames, 7);
    EXPECT_FALSE(s.path.range);
    EXPECT_EQ(parse({"--sea-level", "auto"}).terrain.seaLevel.mode, SeaLevel::Mode::Auto);
    EXPECT_EQ(parse({"--height-units", "none"}).terrain.heightUnits, HeightUnits::None);
    // Given twice, the last one counts.
    EXPECT_EQ(parse({"--tau", "1", "--tau", "2"}).lod.tau, 2.0f);
    EXPECT_EQ(parse({"--fog", "0.5", "--fog", "auto"}).lighting.fog, std::nullopt);
}

TEST_F(SceneOptionsTest, CommandLineOverridesOnlyWhatItGives) {
    Scene defaults;
    defaults.output.msaa = 0;
    std::string config = write("s.json", R"({"camera": {"fov": 30, "azimuth": 10},
        "lod": {"tau": 3}, "output": {"width": 320, "height": 200}, "path": {"type": "orbit", "frames": 8}})");
    Scene s = parse({"--config", config, "--fov", "50", "--size", "64x48"}, defaults);
    EXPECT_EQ(s.camera.fov, 50.0f);
    EXPECT_EQ(s.camera.azimuth, 10.0f);
    EXPECT_EQ(s.lod.tau, 3.0f);
    EXPECT_EQ(s.output.width, 64);
    EXPECT_EQ(s.output.height, 48);
    EXPECT_EQ(s.output.msaa, 0);  // neither the file nor the command line: the app's default
    EXPECT_EQ(s.path.frames, 8);

    // A position given on the command line replaces the file's angles.
    Scene p = parse({"--config", config, "--camera-pos", "1", "2", "3"});
    EXPECT_EQ(p.camera.position, (Vec3{1, 2, 3}));
    EXPECT_FALSE(p.camera.azimuth);
    // --generate given beside a file naming a heightmap generates.
    std::string withMap =
        write("m.json", msg(R"({"terrain": {"heightmap": ")", heightmap_, R"("}})"));
    EXPECT_EQ(parse({"--config", withMap}).terrain.heightmap, heightmap_);
    EXPECT_TRUE(parse({"--config", withMap, "--generate", "65"}).terrain.heightmap.empty());
}

TEST_F(SceneOptionsTest, FramesRangeTakesItsCountFromConfigOrFrameCount) {
    std::string config = write("s.json", R"({"path": {"type": "orbit", "frames": 8}})");
    Scene s = parse({"--config", config, "--frames", "3:5"});
    EXPECT_EQ(s.path.frames, 8);
    EXPECT_EQ(s.path.range, (FrameRange{3, 5}));
    Scene t = parse({"--path", "orbit", "--frames", "0:0", "--frame-count", "2"});
    EXPECT_EQ(t.path.frames, 2);
    EXPECT_EQ(t.path.range, (FrameRange{0, 0}));

    EXPECT_THAT(parseError({"--path", "orbit", "--frames", "3:12", "--frame-count", "10"}),
                AllOf(HasSubstr("--frames"), HasSubstr("3:12"), HasSubstr("< 10")));
    EXPECT_THAT(parseError({"--path", "orbit", "--frames", "5:3", "--frame-count", "10"}),
                HasSubstr("5:3"));
    EXPECT_THAT(parseError({"--path", "orbit", "--frames", "-1:3", "--frame-count", "10"}),
                HasSubstr("-1:3"));
    EXPECT_THAT(parseError({"--frames", "3:5"}), HasSubstr("< 1"));  // a count of 1 by default
    EXPECT_THAT(parseError({"--frames", "a:b"}),
                AllOf(HasSubstr("--frames 'a'"), HasSubstr("A:B")));
    EXPECT_THAT(parseError({"--frames", "3:"}), HasSubstr("--frames"));
    EXPECT_THAT(parseError({"--frames", "0"}), HasSubstr("path.frames (--frames)"));
    EXPECT_THAT(parseError({"--frames", "5", "--frame-count", "5"}),
                HasSubstr("--frame-count goes with"));
}

TEST_F(SceneOptionsTest, VideoOptionsLandInTheirFieldsAndAreChecked) {
    const Scene s = parse({"--out", "fly.MP4", "--fps", "24", "--video-codec", "hevc", "--bitrate",
                           "2.5M", "--video-preset", "slow"});
    EXPECT_TRUE(isVideoOutput(s.output.frame));
    EXPECT_EQ(s.output.fps, 24);
    EXPECT_EQ(s.output.videoCodec, "hevc");
    EXPECT_EQ(s.output.bitrate, 2500000);
    EXPECT_EQ(s.output.crf, -1);
    EXPECT_EQ(s.output.videoPreset, "slow");
    EXPECT_EQ(parse({"--out", "a.webm", "--crf", "31"}).output.crf, 31);
    EXPECT_EQ(parse({"--out", "a.gif", "--bitrate", "800k"}).output.bitrate, 800000);
    EXPECT_FALSE(isVideoOutput("frame.png"));
    EXPECT_THAT(parseError({"--out", "a.mp4", "--fps", "0"}),
                AllOf(HasSubstr("output.fps (--fps)"), HasSubstr("1..1000"), HasSubstr("got 0")));
    EXPECT_THAT(parseError({"--out", "a.mp4", "--fps", "-2"}), HasSubstr("got -2"));
    EXPECT_THAT(parseError({"--out", "a.mp4", "--fps", "2.5"}), HasSubstr("--fps '2.5'"));
    EXPECT_THAT(parseError({"--out", "a.mp4", "--crf", "64"}), HasSubstr("output.crf (--crf)"));
    EXPECT_THAT(parseError({"--out", "a.mp4", "--crf", "20", "--bitrate", "1M"}),
                HasSubstr("excludes output.bitrate (--bitrate)"));
    EXPECT_THAT(parseError({"--out", "a.mp4", "--bitrate", "fast"}),
                AllOf(HasSubstr("--bitrate 'fast'"), HasSubstr("8M")));
    EXPECT_THAT(parseError({"--out", "a.mov", "--alpha"}),
                AllOf(HasSubstr("output.alpha (--alpha)"), HasSubstr("a.mov")));
}

TEST_F(SceneOptionsTest, RawSizeAllowsTheLoadersLimit) {
    Scene s = parse({"--raw-size", "20000x3"});
    EXPECT_EQ(s.terrain.rawWidth, 20000);
    EXPECT_EQ(s.terrain.rawHeight, 3);
    EXPECT_EQ(parse({"--raw-size", "65537x65537"}).terrain.rawWidth, 65537);
    EXPECT_THAT(parseError({"--raw-size", "65538x3"}),
                AllOf(HasSubstr("--raw-size"), HasSubstr("1..65537")));
    EXPECT_THAT(parseError({"--raw-size", "20000"}), HasSubstr("WIDTHxHEIGHT"));
    // The frame size keeps its own, smaller limit.
    EXPECT_THAT(parseError({"--size", "20000x3"}),
                AllOf(HasSubstr("--size"), HasSubstr("1..16384")));
}

TEST_F(SceneOptionsTest, BadValuesGiveClearErrors) {
    EXPECT_THAT(parseError({"--tau", "0"}), AllOf(HasSubstr("lod.tau (--tau)"), HasSubstr("> 0")));
    EXPECT_THAT(parseError({"--tau", "abc"}),
                AllOf(HasSubstr("--tau 'abc'"), HasSubstr("expected a number")));
    EXPECT_THAT(parseError({"--tau", "1.5px"}), HasSubstr("--tau '1.5px'"));
    EXPECT_THAT(parseError({"--fov", "180"}), AllOf(HasSubstr("--fov"), HasSubstr("(0, 180)")));
    EXPECT_THAT(parseError({"--fov", "0"}), HasSubstr("--fov"));
    EXPECT_THAT(parseError({"--camera-pos", "1", "2", "3", "--camera-target", "1", "2", "3"}),
                AllOf(HasSubstr("--camera-pos"), HasSubstr("--camera-target")));
    EXPECT_THAT(parseError({"--camera-pos", "1", "2", "3", "--frames", "3"}),
                AllOf(HasSubstr("--path keyframes"), HasSubstr("3 frames")));
    EXPECT_EQ(parseError({"--camera-pos", "1", "2", "3", "--frames", "3", "--path", "orbit"}), "");
    EXPECT_THAT(parseError({"--msaa", "3"}),
                AllOf(HasSubstr("--msaa"), HasSubstr("0 (off), 2, 4 or 8")));
    EXPECT_THAT(parseError({"--sky", "1,2"}), AllOf(HasSubstr("--sky"), HasSubstr("R,G,B")));
    EXPECT_THAT(parseError({"--sky", "1,2,3"}), AllOf(HasSubstr("--sky"), HasSubstr("0..1")));
    EXPECT_THAT(parseError({"--sea-level", "deep"}), HasSubstr("--sea-level 'deep'"));
    EXPECT_THAT(parseError({"--lod", "fast"}), AllOf(HasSubstr("--lod"), HasSubstr("sbt, full")));
    EXPECT_THAT(parseError({"--path", "spiral"}), AllOf(HasSubstr("--path"), HasSubstr("orbit")));
    EXPECT_THAT(parseError({"--height-units", "feet"}), HasSubstr("--height-units"));
    EXPECT_THAT(parseError({"--channel", "alpha"}), HasSubstr("--channel"));
    EXPECT_THAT(parseError({"--size", "0x5"}), HasSubstr("--size"));
    EXPECT_THAT(parseError({"--depth-out", "d.png"}), HasSubstr(".npy"));
    // Frames are PNG or JPEG by their name: another extension is refused.
    EXPECT_THAT(
        parseError({"--out", "frame.tif"}),
        AllOf(HasSubstr("--out"), HasSubstr(".png"), HasSubstr(".jpg"), HasSubstr("frame.tif")));
    EXPECT_EQ(parseError({"--out", "frame.jpg", "--jpeg-quality", "75"}), "");
    EXPECT_EQ(parseError({"--out", "frame.JPEG"}), "");
    EXPECT_THAT(parseError({"--out", "frame.jpg", "--alpha"}),
                AllOf(HasSubstr("--alpha"), HasSubstr("JPEG has no alpha channel")));
    EXPECT_THAT(parseError({"--jpeg-quality", "0"}),
                AllOf(HasSubstr("--jpeg-quality"), HasSubstr("1..100")));
    EXPECT_THAT(parseError({"--jpeg-quality", "high"}), HasSubstr("--jpeg-quality 'high'"));
    EXPECT_THAT(parseError({"--png-compression", "ultra"}),
                AllOf(HasSubstr("--png-compression"), HasSubstr("fast, default, best")));
    EXPECT_EQ(parseError({"--png-compression", "best"}), "");
    EXPECT_THAT(parseError({"--max-queued-frames", "-1"}), HasSubstr("--max-queued-frames"));
    EXPECT_THAT(parseError({"--debug-out", "debug.bmp"}),
                AllOf(HasSubstr("--debug-out"), HasSubstr(".png")));
    EXPECT_THAT(parseError({"--snapshot-only", "ui"}),
                AllOf(HasSubstr("--snapshot-only"), HasSubstr(".png")));
    EXPECT_EQ(parseError({"--out", "FRAME.PNG", "--depth-out", "D.NPY"}), "");
    EXPECT_THAT(parseError({"--seed", "-1"}), HasSubstr("--seed"));
    EXPECT_THAT(parseError({"--threads", "1000"}), HasSubstr("--threads"));
    EXPECT_THAT(parseError({"--elevation", "95"}), HasSubstr("--elevation"));
    EXPECT_THAT(parseError({"--distance", "0"}), HasSubstr("--distance"));
    EXPECT_THAT(parseError({"--ambient", "nan"}), HasSubstr("--ambient"));
    EXPECT_THAT(parseError({"--roughness", "1e39"}), HasSubstr("--roughness"));
    EXPECT_THAT(parseError({"--fog", "-1"}), HasSubstr("--fog"));
    // A bad value from a scene file names the file too.
    std::string config = write("s.json", R"({"lod": {"tau": -1}})");
    EXPECT_THAT(parseError({"--config", config}), AllOf(HasSubstr("s.json"), HasSubstr("lod.tau")));
    EXPECT_EQ(parseError({"--config", config, "--tau", "2"}), "");
}

TEST_F(SceneOptionsTest, ParserRefusesWhatCannotGoTogether) {
    EXPECT_THROW(parse({"--camera-pos", "1", "2", "3", "--azimuth", "30"}), CLI::ExcludesError);
    EXPECT_THROW(parse({"--heightmap", heightmap_, "--generate", "65"}), CLI::ExcludesError);
    EXPECT_THROW(parse({"--no-debug", "--debug-out", "x.png"}), CLI::ExcludesError);
    EXPECT_THAT(parseError({"--camera-pos", "1", "2"}),
                HasSubstr("--camera-pos: expected 3 numbers"));
    EXPECT_THROW(parse({"--heightmap", (dir_ / "missing.png").string()}), CLI::ValidationError);
    // An app registers only the groups it needs.
    EXPECT_THROW(parse({"--fov", "30"}, Scene{}, kTerrainOptions), CLI::ExtrasError);
    EXPECT_EQ(parse({"--spacing", "2"}, Scene{}, kTerrainOptions).terrain.spacing, 2.0f);
    // Programs that build zones without drawing them (sierra-gen zones, sierra-tin) take the
    // zone options but not the shading ones.
    EXPECT_EQ(parse({"--zones", "auto", "--band", "3"}, Scene{}, kZoneOptions).zones.band, 3.0f);
    for (const char* shading : {"--blend", "--debug-view"})
        EXPECT_THROW(parse({shading, "linear"}, Scene{}, kZoneOptions), CLI::ExtrasError)
            << shading;
    EXPECT_THROW(parse({"--triplanar"}, Scene{}, kZoneOptions), CLI::ExtrasError);
    EXPECT_EQ(parse({"--blend", "linear"}, Scene{}, kZoneShadingOptions).zones.blend, "linear");
}

TEST_F(SceneOptionsTest, ReliefLightingAndTheSunFromATime) {
    Scene d;
    EXPECT_TRUE(d.lighting.shadows);
    EXPECT_TRUE(d.lighting.skyLight);
    EXPECT_EQ(d.lighting.sunSize, 0.53f);
    Scene s = parse({"--shadows", "off", "--sky-light", "off", "--sun-size", "2",
                     "--horizon-radius", "1500", "--sun-time", "2026-06-21T17:30:00Z", "--latitude",
                     "10", "--longitude", "-20", "--sun-step", "600"});
    EXPECT_FALSE(s.lighting.shadows);
    EXPECT_FALSE(s.lighting.skyLight);
    EXPECT_EQ(s.lighting.sunSize, 2.0f);
    EXPECT_EQ(s.lighting.horizonRadius, 1500.0f);
    EXPECT_EQ(s.lighting.sunTime, "2026-06-21T17:30:00Z");
    EXPECT_EQ(s.lighting.latitude, 10.0f);
    EXPECT_EQ(s.lighting.longitude, -20.0f);
    EXPECT_EQ(s.lighting.sunStep, 600.0f);
    EXPECT_TRUE(parse({"--shadows", "on"}).lighting.shadows);

    EXPECT_THAT(parseError({"--shadows", "maybe"}),
                HasSubstr("--shadows 'maybe': expected on or off"));
    EXPECT_THAT(parseError({"--sky-light", ""}), HasSubstr("--sky-light"));
    EXPECT_THAT(parseError({"--sun-size", "0"}),
                AllOf(HasSubstr("lighting.sun_size (--sun-size)"), HasSubstr("0.53")));
    EXPECT_THAT(parseError({"--sun-size", "-1"}), HasSubstr("--sun-size"));
    EXPECT_THAT(parseError({"--horizon-radius", "-5"}), HasSubstr("--horizon-radius"));
    EXPECT_THAT(parseError({"--sun-time", "2026-06-21T17:30:00"}),
                AllOf(HasSubstr("--sun-time"), HasSubstr("time zone")));
    EXPECT_THAT(parseError({"--sun-time", "tomorrow"}), HasSubstr("--sun-time 'tomorrow'"));
    EXPECT_THAT(parseError({"--latitude", "10"}), HasSubstr("with a time"));
    EXPECT_THAT(parseError({"--sun-time", "2026-06-21T17:30:00Z", "--latitude", "91"}),
                HasSubstr("lighting.latitude (--latitude)"));
    EXPECT_THAT(parseError({"--sun-step", "60"}), HasSubstr("--sun-time"));
    EXPECT_THROW(parse({"--sun-time", "2026-06-21T17:30:00Z", "--sun-azimuth", "30"}),
                 CLI::ExcludesError);
    // A fixed sun on the command line replaces a scene file's time.
    std::string config = write("timed.json", R"({"lighting": {"sun_time": "2026-06-21T17:30:00Z",
                                                 "latitude": 45, "longitude": 7}})");
    EXPECT_EQ(parse({"--config", config}).lighting.sunTime, "2026-06-21T17:30:00Z");
    Scene fixed = parse({"--config", config, "--sun-altitude", "20"});
    EXPECT_FALSE(fixed.lighting.sunTime);
    EXPECT_FALSE(fixed.lighting.latitude);
    EXPECT_EQ(fixed.lighting.sunAltitude, 20.0f);
    std::string bad = write("bad.json", R"({"lighting": {"sun_time": "21 June"}})");
    EXPECT_THAT(parseError({"--config", bad}), HasSubstr("lighting.sun_time"));
}

TEST_F(SceneOptionsTest, SunFromATimeOverTheTerrain) {
    Scene s;
    s.lighting.sunTime = "2026-06-21T17:30:00Z";
    terrain::Heightfield plain(5, 5);
    // No georeference and no place: one clear error naming the options.
    try {
        sceneSun(s, plain, 0);
        ADD_FAILURE() << "accepted a time without a place";
    } catch (const Error& e) {
        EXPECT_THAT(
            std::string(e.what()),
            AllOf(HasSubstr("no georeference"), HasSubstr("--latitude"), HasSubstr("--longitude")));
    }
    // Boulder, Colorado (tests/unit/terrain_sun_reference.py): from the DEM's centre ...
    terrain::Heightfield boulder(5, 5);
    boulder.setGeoCentre(terrain::Heightfield::GeoPoint{40.0150, -105.2705});
    SunAngles sun = sceneSun(s, boulder, 0);
    EXPECT_NEAR(sun.azimuth, 123.261057, 0.01);
    EXPECT_NEAR(sun.altitude, 64.353650, 0.01);
    // ... or the options over a DEM without one.
    s.lighting.latitude = 40.0150f;
    s.lighting.longitude = -105.2705f;
    EXPECT_NEAR(sceneSun(s, plain, 0).altitude, 64.353650, 0.01);
    // A sequence: frame k at the time plus k steps; the afternoon sun goes west.
    s.lighting.sunStep = 3600.0f;
    EXPECT_EQ(sceneSun(s, plain, 0).azimuth, sun.azimuth);
    EXPECT_GT(sceneSun(s, plain, 3).azimuth, 180.0f);
    // Without a time, the fixed sun whatever the frame.
    Scene fixed;
    EXPECT_EQ(sceneSun(fixed, plain, 7).azimuth, kDefaultSunAzimuth);
    EXPECT_EQ(sceneSun(fixed, plain, 7).altitude, kDefaultSunAltitude);
}

TEST_F(SceneOptionsTest, PrintConfigFedBackGivesTheSameScene) {
    bool printed = false;
    ::testing::internal::CaptureStdout();
    Scene s = parse({"--generate", "129", "--fov", "33.3", "--sky", "0.1,0.7,0.9", "--path",
                     "orbit", "--frames", "12", "--print-config"},
                    Scene{}, kAllOptions, &printed);
    std::string text = ::testing::internal::GetCapturedStdout();
    EXPECT_TRUE(printed);
    EXPECT_EQ(text, sceneToText(s));
    std::string config = write("printed.json", text);
    Scene back = parse({"--config", config}, Scene{}, kAllOptions, &printed);
    EXPECT_FALSE(printed);
    EXPECT_EQ(back, s);
    EXPECT_EQ(sceneToText(back), text);
}

// A program's own scene options (apply(program)): applied after --config and the
// registrar's options, checked with the scene and printed by --print-config.
TEST_F(SceneOptionsTest, ProgramOptionsAreCheckedAndPrinted) {
    auto run = [](const std::vector<std::string>& args,
                  const std::function<void(Scene&)>& program) {
        return parse(args, Scene{}, kTerrainOptions, nullptr, program);
    };
    std::string config = write(
        "zones.json", R"({"zones": {"map": "auto", "band": 2}, "terrain": {"generate": 65}})");
    ::testing::internal::CaptureStdout();
    Scene seen;
    Scene s = run({"--config", config, "--generate", "129", "--print-config"}, [&](Scene& scene) {
        seen = scene;  // what the program sees: the config under the command line
        scene.zones.epsilon = 1.5f;
    });
    const std::string text = ::testing::internal::GetCapturedStdout();
    EXPECT_EQ(seen.zones.map, "auto");
    EXPECT_EQ(seen.zones.band, 2.0f);
    EXPECT_EQ(seen.terrain.generateSize, 129);
    EXPECT_EQ(s.zones.epsilon, 1.5f);
    EXPECT_EQ(text, sceneToText(s));
    EXPECT_THAT(text, HasSubstr("\"epsilon\": 1.5"));
    // The program's values are checked like the rest.
    EXPECT_THROW(run({}, [](Scene& scene) { scene.zones.epsilon = -1.0f; }), Error);
}

TEST_F(SceneOptionsTest, HelpShowsTheAppDefaults) {
    Scene defaults;
    defaults.output = {.width = 1920, .height = 1080, .msaa = 0};
    CLI::App app{"test"};
    Scene scene = defaults;
    SceneOptions options(app, scene, kAllOptions);
    std::string help = app.help();
    EXPECT_THAT(help, HasSubstr("1920x1080"));
    EXPECT_THAT(help, HasSubstr("Level of detail"));
    EXPECT_THAT(help, HasSubstr("--print-config"));
}

TEST_F(SceneOptionsTest, AutoZoneThresholdsLandInTheirFieldsAndAreChecked) {
    const Scene base;
    Scene s = parse({"--zones", "auto", "--deep-water", "0.5", "--sand-top", "0.1",
                     "--zone-snow-line", "0.6", "--rock-slope", "30"},
                    base);
    EXPECT_EQ(s.zones.deepWater, 0.5f);
    EXPECT_EQ(s.zones.sandTop, 0.1f);
    EXPECT_EQ(s.zones.snowLine, 0.6f);
    EXPECT_EQ(s.zones.rockSlope, 30.0f);
    EXPECT_EQ(s.style.snowLine, base.style.snowLine)
        << "--zone-snow-line is not the style's --snow-line";
    const Scene& defaults = base;
    EXPECT_THAT(parseError({"--deep-water", "1.5"}, defaults),
                AllOf(HasSubstr("--deep-water"), HasSubstr("0..1")));
    EXPECT_THAT(parseError({"--sand-top", "-0.1"}, defaults), HasSubstr("--sand-top"));
    EXPECT_THAT(parseError({"--zone-snow-line", "2"}, defaults), HasSubstr("--zone-snow-line"));
    EXPECT_THAT(parseError({"--rock-slope", "90"}, defaults),
                AllOf(HasSubstr("--rock-slope"), HasSubstr("degrees")));
}

}  // namespace
}  // namespace sierra::scene
