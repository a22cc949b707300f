// Style presets: every Figure 3 and Figure 4 row parses to the document's
// values, and bad parameters give one clear error.
#include <sierra/analysis/Style.h>
#include <sierra/core/Error.h>
#include <sierra/scene/StyleJson.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

using namespace sierra;
using namespace sierra::analysis;
using sierra::scene::Json;
using sierra::scene::loadStyleFile;
using sierra::scene::styleFromJson;
using sierra::scene::styleToJson;
using json = sierra::scene::Json;

namespace {

const std::string kPresetDir = SIERRA_PRESET_DIR;

// A row of the document's tables: method, reinforcement distance (1 for
// n/a), scale, contours, min length or hatch length, line width, direction.
struct Row {
    const char* name;
    CurvatureMethod method;
    int distance;
    float scale;
    bool contours;
    float length;
    float width;
    HatchDirection direction = HatchDirection::Along;
};

constexpr auto k3N = CurvatureMethod::ThreeNormal;
constexpr auto k2N = CurvatureMethod::TwoNormal;
constexpr auto kEdge = CurvatureMethod::EdgeAngle;
constexpr auto k3V = CurvatureMethod::ThreeVertex;
constexpr auto kWith = HatchDirection::Along;
constexpr auto kPerp = HatchDirection::Across;

const Row kFigure3[] = {
    {"fig3a", k3N, 2, 6, false, 6, 1},  {"fig3b", k3N, 2, 6, true, 6, 1},
    {"fig3c", k3N, 2, 11, true, 2, 1},  {"fig3d", k2N, 1, 2, false, 5, 1},
    {"fig3e", k2N, 1, 11, false, 2, 1}, {"fig3f", k2N, 1, 6, false, 2, 1},
    {"fig3g", k3N, 2, 3, true, 5, 1},   {"fig3h", k2N, 1, 3, false, 5, 1},
    {"fig3i", kEdge, 1, 2, true, 5, 1}, {"fig3j", k3V, 1, 2, false, 5, 1},
    {"fig3k", k2N, 1, 1, false, 5, 1},  {"fig3l", kEdge, 1, 1, true, 5, 1},
    {"fig3m", k3V, 1, 1, false, 5, 1},  {"fig3n", k3N, 1, 1.5f, false, 2, 6},
};
const Row kFigure4[] = {
    {"fig4a", k3N, 2, 4, false, 0.75f, 1, kWith}, {"fig4b", k3N, 1, 4, false, 0.75f, 1, kWith},
    {"fig4c", k3N, 1, 4, false, 0.75f, 1, kPerp}, {"fig4d", k2N, 1, 4, false, 0.75f, 4, kPerp},
    {"fig4e", k2N, 1, 8, false, 0.25f, 1, kPerp}, {"fig4f", k3N, 2, 8, true, 0.75f, 1, kPerp},
    {"fig4g", k3N, 1, 3, false, 2.15f, 2, kPerp}, {"fig4h", k3V, 1, 2, false, 0.45f, 3, kWith},
};

std::string errorOf(const json& style) {
    try {
        styleFromJson(style, "test.json");
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

}  // namespace

TEST(AnalysisStyle, EveryFigure3PresetParsesToTheTable) {
    for (const Row& r : kFigure3) {
        StyleParams s = loadStyleFile(kPresetDir + "/" + r.name + ".json");
        EXPECT_EQ(s.curvature.method, r.method) << r.name;
        EXPECT_EQ(s.curvature.distance, r.distance) << r.name;
        EXPECT_FLOAT_EQ(s.curvature.scale, r.scale) << r.name;
        EXPECT_EQ(s.layers.contours, r.contours) << r.name;
        EXPECT_EQ(s.lines.minLength, int(r.length)) << r.name;
        EXPECT_FLOAT_EQ(s.lines.width, r.width) << r.name;
        EXPECT_TRUE(s.layers.lines) << r.name;
        EXPECT_FALSE(s.layers.hatch) << r.name;
        EXPECT_EQ(s.curvature.normals, NormalMethod::Quad) << r.name;
        EXPECT_NE(s.description.find("Figure 3"), std::string::npos) << r.name;
        EXPECT_EQ(lineOptions(s).minVertices, int(r.length));
    }
}

TEST(AnalysisStyle, EveryFigure4PresetParsesToTheTable) {
    for (const Row& r : kFigure4) {
        StyleParams s = loadStyleFile(kPresetDir + "/" + r.name + ".json");
        EXPECT_EQ(s.curvature.method, r.method) << r.name;
        EXPECT_EQ(s.curvature.distance, r.distance) << r.name;
        EXPECT_FLOAT_EQ(s.curvature.scale, r.scale) << r.name;
        EXPECT_EQ(s.layers.contours, r.contours) << r.name;
        EXPECT_FLOAT_EQ(s.hatch.length, r.length) << r.name;
        EXPECT_FLOAT_EQ(s.hatch.width, r.width) << r.name;
        EXPECT_EQ(s.hatch.direction, r.direction) << r.name;
        EXPECT_TRUE(s.layers.hatch) << r.name;
        EXPECT_FALSE(s.layers.lines) << r.name;
    }
}

TEST(AnalysisStyle, PresetDirectoryHoldsExactlyTheTwentyTwoFigures) {
    int count = 0;
    for (auto& entry : std::filesystem::directory_iterator(kPresetDir)) {
        std::string name = entry.path().filename().string();
        if (name.rfind("fig", 0) != 0) continue;
        ++count;
        EXPECT_NO_THROW(loadStyleFile(entry.path().string())) << name;
    }
    EXPECT_EQ(count, 14 + 8);
}

TEST(AnalysisStyle, RoundTripAndDefaults) {
    StyleParams s = loadStyleFile(kPresetDir + "/fig4f.json");
    s.curvature.levels = {.enabled = true, .black = 0.1f, .white = 0.8f, .gamma = 2.0f};
    s.curvature.signedValues = true;
    s.lines.polarity = LinePolarity::Ridges;
    StyleParams back = styleFromJson(styleToJson(s));
    EXPECT_EQ(styleToJson(back), styleToJson(s));
    EXPECT_TRUE(back.layers.contours);
    EXPECT_TRUE(back.curvature.levels.enabled);
    EXPECT_FLOAT_EQ(back.curvature.levels.gamma, 2.0f);

    // No "styles": shaded, plus the layers whose objects are present.
    StyleParams d = styleFromJson(json::parse(R"({"lines": {"width": 2}})"));
    EXPECT_TRUE(d.layers.shaded);
    EXPECT_TRUE(d.layers.lines);
    EXPECT_FALSE(d.layers.hatch);
    EXPECT_FALSE(d.layers.contours);
    EXPECT_EQ(d.curvature.method, CurvatureMethod::ThreeNormal);
    StyleParams all =
        styleFromJson(json::parse(R"({"styles": ["shaded", "lines", "hatch", "contours"]})"));
    EXPECT_TRUE(all.layers.shaded && all.layers.lines && all.layers.hatch && all.layers.contours);
}

TEST(AnalysisStyle, BadParametersGiveClearErrors) {
    EXPECT_EQ(
        errorOf(json::parse(R"({"curvature": {"method": "three-normal", "distance": 0}})")),
        "test.json: style.curvature.distance: must be an integer >= 1 (1 = no reinforcement), "
        "got 0");
    EXPECT_EQ(errorOf(json::parse(R"({"curvature": {"scale": -2}})")),
              "test.json: style.curvature.scale: must be >= 0, got -2");
    EXPECT_EQ(errorOf(json::parse(R"({"curvature": {"method": "four-normal"}})")),
              "test.json: style.curvature.method: unknown curvature method 'four-normal' (expected "
              "two-normal, "
              "three-normal, three-vertex or edge-angle)");
    auto has = [](const std::string& text, const std::string& words) {
        return text.find(words) != std::string::npos;
    };
    EXPECT_TRUE(
        has(errorOf(json::parse(R"({"curvature": {"method": "two-normal", "distance": 2}})")),
            "style.curvature.distance: must be 1 for two-normal"));
    EXPECT_TRUE(has(errorOf(json::parse(R"({"curvature": {"distance": 1.5}})")),
                    "expected an integer >= 1"));
    EXPECT_TRUE(has(errorOf(json::parse(R"({"curvature": {"scale": "big"}})")),
                    "style.curvature.scale: must be a number"));
    EXPECT_TRUE(has(errorOf(json::parse(R"({"curvature": {"dist": 2}})")),
                    "unknown key style.curvature.dist"));
    EXPECT_TRUE(has(errorOf(json::parse(R"({"lines": {"min_length": 1}})")),
                    "style.lines.min_length: must be an integer >= 2"));
    EXPECT_TRUE(
        has(errorOf(json::parse(R"({"lines": {"width": 0}})")), "style.lines.width: must be > 0"));
    EXPECT_TRUE(has(errorOf(json::parse(R"({"hatch": {"direction": "with"}})")),
                    "unknown hatch direction 'with'"));
    EXPECT_TRUE(has(errorOf(json::parse(R"({"hatch": {"length": -1}})")),
                    "style.hatch.length: must be > 0"));
    EXPECT_TRUE(has(errorOf(json::parse(R"({"styles": ["lines", "watercolour"]})")),
                    "unknown style \"watercolour\""));
    EXPECT_TRUE(
        has(errorOf(json::parse(R"({"styles": "lines"})")), "style.styles: expected an array"));
    EXPECT_TRUE(has(errorOf(json::parse(R"({"styles": ["contours"], "contours": false})")),
                    "style.contours: is false but \"styles\" lists contours"));
    EXPECT_TRUE(
        has(errorOf(json::parse(R"({"curvature": {"levels": {"black": 0.5, "white": 0.2}}})")),
            "style.curvature.levels.white: must be above the black point"));
    EXPECT_TRUE(has(errorOf(json::parse(R"([1, 2])")), "style: expected an object"));

    auto dir = std::filesystem::temp_directory_path() / "sierra_analysis_style_test";
    std::filesystem::create_directories(dir);
    auto bad = (dir / "bad.json").string();
    std::ofstream(bad) << "{\"style\": {";
    try {
        loadStyleFile(bad);
        ADD_FAILURE() << "no error for broken JSON";
    } catch (const Error& e) {
        EXPECT_TRUE(has(e.what(), bad + ": not a JSON file")) << e.what();
    }
    auto noStyle = (dir / "nostyle.json").string();
    std::ofstream(noStyle) << "{\"camera\": {}}";
    EXPECT_THROW(loadStyleFile(noStyle), Error);
    EXPECT_THROW(loadStyleFile((dir / "missing.json").string()), Error);
    std::filesystem::remove_all(dir);
}

TEST(AnalysisStyle, AutoScaleReadsAndWritesBack) {
    const StyleParams s =
        styleFromJson(json::parse(R"({"curvature": {"scale": "auto"}, "lines": {}})"));
    EXPECT_TRUE(s.autoScale);
    EXPECT_EQ(styleToJson(s)["curvature"]["scale"], "auto");
    EXPECT_EQ(styleFromJson(styleToJson(s)), s);
    EXPECT_FALSE(styleFromJson(json::parse(R"({"curvature": {"scale": 3}})")).autoScale);
    auto has = [](const std::string& text, const std::string& words) {
        return text.find(words) != std::string::npos;
    };
    EXPECT_TRUE(has(errorOf(json::parse(R"({"curvature": {"scale": "twice"}})")),
                    R"(style.curvature.scale: must be a number >= 0 or "auto", got "twice")"));
    EXPECT_TRUE(
        has(errorOf(json::parse(R"({"curvature": {"scale": "auto", "levels": {"white": 0.5}}})")),
            R"(style.curvature.scale: is "auto", which picks the scale from the values)"));
}

// A row of 101 samples whose largest magnitudes are 0, 0.02, ..., 2 (in
// direction 1, signed), one no-data sample beside them.
CurvatureField rampField() {
    CurvatureField f;
    f.width = 102;
    f.height = 1;
    f.values.assign(size_t(f.width) * kDirectionCount, 0.0f);
    for (int i = 0; i <= 100; ++i) {
        f.values[size_t(i) * 4 + 0] = 0.01f * float(i);
        f.values[size_t(i) * 4 + 1] = -0.02f * float(i);
        f.values[size_t(i) * 4 + 2] = NAN;
    }
    for (int d = 0; d < 4; ++d) f.values[101 * 4 + size_t(d)] = NAN;
    return f;
}

TEST(AnalysisStyle, AutoScaleBringsTheTopFivePercentToTheLineThresholdOrFullOpacity) {
    const CurvatureField f = rampField();
    std::vector<float> largest = largestMagnitudes(f);
    ASSERT_EQ(largest.size(), 101u);                 // the no-data sample left out
    EXPECT_FLOAT_EQ(topFivePercent(largest), 1.9f);  // rank 95 of 0..100
    std::vector<float> none;
    EXPECT_EQ(topFivePercent(none), 0.0f);

    StyleParams lines = styleFromJson(json::parse(R"({"lines": {"threshold": 0.4}})"));
    lines.curvature.scale = 2.0f;
    EXPECT_FLOAT_EQ(autoCurvatureScale(f, lines), 2.0f * 0.4f / 1.9f);
    StyleParams hatches = styleFromJson(json::parse(R"({"hatch": {}})"));
    hatches.curvature.scale = 2.0f;
    EXPECT_FLOAT_EQ(autoCurvatureScale(f, hatches), 2.0f * 1.0f / 1.9f);

    // The field at the returned scale (values proportional to it) has its
    // top 5% at the threshold.
    CurvatureField scaled = f;
    for (float& v : scaled.values) v *= autoCurvatureScale(f, lines) / lines.curvature.scale;
    std::vector<float> scaledLargest = largestMagnitudes(scaled);
    EXPECT_NEAR(topFivePercent(scaledLargest), 0.4f, 1e-6f);

    // A flat field keeps the scale it has.
    CurvatureField flat = f;
    for (float& v : flat.values)
        if (!std::isnan(v)) v = 0.0f;
    EXPECT_EQ(autoCurvatureScale(flat, lines), 2.0f);
}
