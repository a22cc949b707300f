// Palettes, zone map files, auto-zoning and tiles: good files read back, bad
// ones give one clear message.
#include "temp_dir_test_util.h"

#include <sierra/scene/PaletteJson.h>
#include <sierra/zones/Palette.h>
#include <sierra/zones/Tiles.h>
#include <sierra/zones/ZoneMap.h>

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>

#include "zones_test_maps.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace sierra::zones {
namespace {

namespace fs = std::filesystem;
using scene::loadPalette;
using scene::paletteToJson;
using scene::parsePalette;

class ZonesIo : public sierra::test::TempDirTest {
  protected:
    void SetUp() override {
        TempDirTest::SetUp();
        fs::create_directories(dir_ / "tiles");
        write("tiles/a.png", "x");
        write("tiles/b.png", "x");
    }
    static std::string errorOf(const std::function<void()>& f) {
        return TempDirTest::errorOf(f, "(no error)");
    }
    const std::string kGood = R"({"zones": [
        {"name": "a", "colour": "#ff0000", "tile": "tiles/a.png", "tile_size": 8},
        {"name": "b", "colour": "#00FF00", "tile": "tiles/b.png", "height_blend": 0.25}]})";
};

TEST_F(ZonesIo, PaletteReadsFieldsAndResolvesTiles) {
    Palette p = loadPalette(write("p.json", kGood));
    ASSERT_EQ(p.surfaces.size(), 2u);
    EXPECT_EQ(p.surfaces[0].colour, 0xff0000u);
    EXPECT_EQ(p.surfaces[1].colour, 0x00ff00u);
    EXPECT_EQ(p.surfaces[0].tileSize, 8.0f);
    EXPECT_EQ(p.surfaces[1].heightBlend, 0.25f);
    EXPECT_EQ(fs::path(p.surfaces[1].tile), (dir_ / "tiles" / "b.png").lexically_normal());
    EXPECT_EQ(p.borderline, 0x000000u);
    EXPECT_EQ(p.find(0x00ff00), 1);
    EXPECT_EQ(p.findName("a"), 0);
}

TEST_F(ZonesIo, BadPalettesSayWhy) {
    EXPECT_NE(errorOf([&] { loadPalette(write("p.json", "{zones: oops")); }).find("not a JSON"),
              std::string::npos);
    // A number beyond double's range (found by fuzzing): a clear error, not an escaped exception.
    EXPECT_NE(errorOf([&] {
                  loadPalette(write("p.json", R"({"zones": [], "x": 3e58836})"));
              }).find("not a JSON"),
              std::string::npos);
    std::string missing =
        R"({"zones": [{"name": "a", "colour": "#ff0000", "tile": "tiles/none.png"}]})";
    std::string e = errorOf([&] { loadPalette(write("p.json", missing)); });
    EXPECT_NE(e.find("none.png"), std::string::npos) << e;
    EXPECT_NE(e.find("does not exist"), std::string::npos) << e;
    std::string twice = R"({"zones": [{"name": "a", "colour": "#ff0000", "tile": "tiles/a.png"},
                                      {"name": "b", "colour": "#ff0000", "tile": "tiles/b.png"}]})";
    EXPECT_NE(errorOf([&] { loadPalette(write("p.json", twice)); }).find("used twice"),
              std::string::npos);
    std::string badColour = R"({"zones": [{"name": "a", "colour": "red", "tile": "tiles/a.png"}]})";
    EXPECT_NE(errorOf([&] { loadPalette(write("p.json", badColour)); }).find("#rrggbb"),
              std::string::npos);
    std::string black = R"({"zones": [{"name": "a", "colour": "#000000", "tile": "tiles/a.png"}]})";
    EXPECT_NE(errorOf([&] { loadPalette(write("p.json", black)); }).find("borderline colour"),
              std::string::npos);
    EXPECT_NE(errorOf([&] { loadPalette((dir_ / "absent.json").string()); }).find("cannot open"),
              std::string::npos);
}

TEST_F(ZonesIo, ZoneMapRoundTripsThroughPng) {
    Palette p = loadPalette(write("p.json", kGood));
    for (bool figure1 : {false, true}) {
        ZoneMap m = test::makeMap(20, 12, [](int x, int y) { return x + y < 14 ? 0 : 1; });
        if (figure1) m = drawBorderlines(m);
        std::string path = (dir_ / "map.png").string();
        writeFileAtomic(path, encodeZoneMapPng(m, p));
        ZoneMap back = loadZoneMap(path, p);
        EXPECT_EQ(back.width, 20);
        EXPECT_EQ(back.height, 12);
        EXPECT_EQ(back.ids, m.ids);
        EXPECT_EQ(back.layout, figure1 ? ZoneLayout::Borderlines : ZoneLayout::Touching);
    }
}

TEST_F(ZonesIo, UnknownColourNamesColourAndFirstPixel) {
    Palette p = loadPalette(write("p.json", kGood));
    ZoneMap m = test::makeMap(6, 5, [](int, int) { return 0; });
    auto rgb = zoneMapRgb(m, p);
    for (auto [x, y] : {std::pair{4, 3}, {3, 2}, {5, 4}}) {  // (3, 2) comes first in row order
        uint8_t* px = &rgb[size_t(y * 6 + x) * 3];
        px[0] = 0x12, px[1] = 0x34, px[2] = 0x56;
    }
    std::string e = errorOf([&] { classifyZoneMap(6, 5, rgb, p, "map.png"); });
    EXPECT_NE(e.find("#123456"), std::string::npos) << e;
    EXPECT_NE(e.find("(3, 2)"), std::string::npos) << e;
    EXPECT_NE(e.find("map.png"), std::string::npos) << e;
}

TEST_F(ZonesIo, Figure1ZonesMustNotTouch) {
    Palette p = loadPalette(write("p.json", kGood));
    ZoneMap m = drawBorderlines(test::makeMap(10, 10, [](int x, int) { return x < 5 ? 0 : 1; }));
    auto rgb = zoneMapRgb(m, p);
    // Open a gap in the line at row 7: zones a and b touch there.
    size_t gap = size_t(7 * 10 + 4) * 3;
    rgb[gap] = 0xff, rgb[gap + 1] = 0, rgb[gap + 2] = 0;
    std::string e = errorOf([&] { classifyZoneMap(10, 10, rgb, p, "map.png"); });
    EXPECT_NE(e.find("no borderline"), std::string::npos) << e;
    EXPECT_NE(e.find("(4, 7)"), std::string::npos) << e;
}

// A Figure 1 map's frame runs through its outer pixel centres: a single row or
// column of pixels has no frame, and the map's own name says so (a 2x2 map is fine).
TEST_F(ZonesIo, Figure1MapNeedsTwoByTwo) {
    Palette p = loadPalette(write("p.json", kGood));
    for (std::pair<int, int> size : {std::pair{1, 1}, {5, 1}, {1, 4}}) {
        const int w = size.first, h = size.second;       // captured below: no structured binding
        std::vector<uint8_t> rgb(size_t(w) * h * 3, 0);  // all borderline (#000000)
        std::string e = errorOf([&] { classifyZoneMap(w, h, rgb, p, "tiny.png"); });
        EXPECT_NE(e.find("tiny.png"), std::string::npos) << e;
        EXPECT_NE(e.find("at least 2x2"), std::string::npos) << e;
    }
    ZoneMap two = drawBorderlines(test::makeMap(2, 2, [](int x, int) { return x; }));
    EXPECT_NO_THROW(classifyZoneMap(2, 2, zoneMapRgb(two, p), p, "two.png"));
}

TEST_F(ZonesIo, NotAnImageIsReported) {
    Palette p = loadPalette(write("p.json", kGood));
    std::string e = errorOf([&] { loadZoneMap(write("map.png", "this is not a PNG"), p); });
    EXPECT_NE(e.find("is not an image"), std::string::npos) << e;
    EXPECT_NE(errorOf([&] { loadZoneMap((dir_ / "none.png").string(), p); }).find("cannot open"),
              std::string::npos);
}

TEST(ZonesAuto, BandsByHeightAndSlope) {
    Palette p;
    for (const std::string& name : tileNames())
        p.surfaces.push_back({name, Colour(p.surfaces.size() + 1), "", 16, 0.5});
    // A gentle ramp from -10 up to 5.8, a cliff rising 0.7 per sample (35
    // degrees) to 12.3, then a flat plateau at 13.
    terrain::Heightfield field(101, 21);
    for (int j = 0; j < 21; ++j)
        for (int i = 0; i < 101; ++i)
            field.at(i, j) = i < 80 ? -10.0f + 0.2f * i : i < 90 ? 6.0f + 0.7f * (i - 80) : 13.0f;
    AutoZoneDesc desc{.seaLevel = 0,
                      .deepWater = 0.5f,
                      .sandTop = 0.1f,
                      .snowLine = 0.7f,
                      .rockSlope = 30.0f,
                      .smoothPasses = 0};
    ZoneMap m = autoZones(field, p, desc);
    ASSERT_EQ(m.layout, ZoneLayout::Touching);
    auto name = [&](int i) { return p.surfaces[size_t(m.at(i, 10))].name; };
    EXPECT_EQ(name(10), "deep-water");     // -8: deeper than half the 10 m depth
    EXPECT_EQ(name(40), "shallow-water");  // -2
    EXPECT_EQ(name(50), "sand");           // 0: up to 10% of the 13 m land relief
    EXPECT_EQ(name(70), "grass");          // 4
    EXPECT_EQ(name(85), "rock");           // 9.5 is above the snow line (9.1) but steep
    EXPECT_EQ(name(95), "snow");           // the plateau
    desc.rockSlope = 40.0f;
    EXPECT_EQ(p.surfaces[size_t(autoZones(field, p, desc).at(85, 10))].name, "snow");
    desc.grassName = "meadow";
    EXPECT_THROW(autoZones(field, p, desc), Error);
}

TEST(ZonesTiles, DeterministicSeamlessWithHeights) {
    for (const std::string& name : tileNames()) {
        SCOPED_TRACE(name);
        TileImage a = generateTile(name, 64, 7), b = generateTile(name, 64, 7),
                  c = generateTile(name, 64, 8);
        EXPECT_EQ(a.rgba, b.rgba);
        EXPECT_NE(a.rgba, c.rgba);
        // Seamless: the step across the wrap (last column to first) is no
        // larger than a typical step between neighbouring columns.
        auto step = [&](int x0, int x1) {
            double sum = 0;
            for (int y = 0; y < 64; ++y)
                for (int ch = 0; ch < 4; ++ch)
                    sum += std::abs(int(a.rgba[size_t(y * 64 + x0) * 4 + ch]) -
                                    int(a.rgba[size_t(y * 64 + x1) * 4 + ch]));
            return sum;
        };
        auto stepY = [&](int y0, int y1) {
            double sum = 0;
            for (int x = 0; x < 64; ++x)
                for (int ch = 0; ch < 4; ++ch)
                    sum += std::abs(int(a.rgba[size_t(y0 * 64 + x) * 4 + ch]) -
                                    int(a.rgba[size_t(y1 * 64 + x) * 4 + ch]));
            return sum;
        };
        double typical = 0, typicalY = 0;
        for (int x = 0; x + 1 < 64; ++x) typical += step(x, x + 1) / 63;
        for (int y = 0; y + 1 < 64; ++y) typicalY += stepY(y, y + 1) / 63;
        EXPECT_LE(step(63, 0), 2.5 * typical + 64);
        EXPECT_LE(stepY(63, 0), 2.5 * typicalY + 64);
        uint8_t lo = 255, hi = 0;
        for (size_t k = 3; k < a.rgba.size(); k += 4)
            lo = std::min(lo, a.rgba[k]), hi = std::max(hi, a.rgba[k]);
        EXPECT_GT(hi - lo, 8) << "the height channel varies";
    }
    EXPECT_THROW(generateTile("lava"), Error);
    EXPECT_THROW(generateTile("grass", 100), Error);
}

}  // namespace
}  // namespace sierra::zones
