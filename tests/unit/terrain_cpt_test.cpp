// GMT .cpt colour tables: good files (comments, B/F/N, continuous and
// discrete slices, absolute heights) and bad files (a message with the line).

#include <sierra/terrain/Cpt.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace sierra::terrain {
namespace {

using ::testing::HasSubstr;

bool same(Rgb a, Rgb b) {
    return a.r == b.r && a.g == b.g && a.b == b.b;
}

TEST(Cpt, ContinuousTableWithCommentsAndBfn) {
    const std::string text =
        "# a topographic table\n"
        "# COLOR_MODEL = RGB\n"
        "\n"
        "-100  0 0 255   0  0 128 255  ; sea\n"
        "0     0 128 0   1000  200 200 0 L\n"
        "1000  200/200/0 2000 255/255/255 # upper slope\n"
        "B 10 10 10\n"
        "F 250/0/0\n"
        "N 128\n";
    CptTable t = parseCpt(text, "topo.cpt");
    ASSERT_EQ(t.stops.size(), 6u);
    EXPECT_EQ(t.minHeight(), -100.0f);
    EXPECT_EQ(t.maxHeight(), 2000.0f);
    ColourRamp ramp = t.ramp(-500.0f, 3000.0f);
    EXPECT_TRUE(same(ramp.colourAt(-50.0f), Rgb{0, 64, 255}));  // interpolated
    EXPECT_TRUE(same(ramp.colourAt(500.0f), Rgb{100, 164, 0}));
    EXPECT_TRUE(same(ramp.colourAt(1500.0f), Rgb{228, 228, 128}));
    EXPECT_TRUE(same(ramp.colourAt(-200.0f), Rgb{10, 10, 10}));  // B
    EXPECT_TRUE(same(ramp.colourAt(2500.0f), Rgb{250, 0, 0}));   // F
    EXPECT_TRUE(same(ramp.noDataColour(), Rgb{128, 128, 128}));  // N
    EXPECT_TRUE(same(ramp.colourAt(std::nanf("")), Rgb{128, 128, 128}));
    // Absolute heights: a second field's range does not move the colours.
    ColourRamp other = t.ramp(0.0f, 1200.0f);
    EXPECT_TRUE(same(other.colourAt(500.0f), ramp.colourAt(500.0f)));
    // The 1D table over the field range samples the same colours.
    std::vector<uint8_t> table = other.table(13);  // entry k at 100 * k
    EXPECT_EQ(table[4 * 5 + 0], 100);
    EXPECT_EQ(table[4 * 5 + 1], 164);
}

TEST(Cpt, DiscreteTableHasHardEdges) {
    const std::string text =
        "0 #204080 100 #204080\n"
        "100 50 50 50 200 50 50 50\n"
        "200 white 300 white\n";
    CptTable t = parseCpt(text, "steps.cpt");
    ColourRamp ramp = t.ramp();
    EXPECT_TRUE(same(ramp.colourAt(10.0f), Rgb{0x20, 0x40, 0x80}));
    EXPECT_TRUE(same(ramp.colourAt(99.9f), Rgb{0x20, 0x40, 0x80}));
    EXPECT_TRUE(same(ramp.colourAt(100.0f), Rgb{50, 50, 50}));  // the upper slice wins at the edge
    EXPECT_TRUE(same(ramp.colourAt(150.0f), Rgb{50, 50, 50}));
    EXPECT_TRUE(same(ramp.colourAt(250.0f), Rgb{255, 255, 255}));
    // No B/F lines: outside heights clamp to the end colours.
    ColourRamp wide = t.ramp(-50.0f, 400.0f);
    EXPECT_TRUE(same(wide.colourAt(-20.0f), Rgb{0x20, 0x40, 0x80}));
    EXPECT_TRUE(same(wide.colourAt(390.0f), Rgb{255, 255, 255}));
}

void expectBad(const std::string& text, const std::string& lineText, const std::string& what) {
    try {
        parseCpt(text, "bad.cpt");
        ADD_FAILURE() << "no error for:\n" << text;
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("bad.cpt " + lineText)) << text;
        EXPECT_THAT(e.what(), HasSubstr(what)) << text;
    }
}

TEST(Cpt, BadFilesNameTheLine) {
    expectBad("# ok\n0 0 0 0 10 255 255 255\n10 0 0 0 5 1 1 1\n", "line 3", "does not ascend");
    expectBad("0 0 0 0 10 255 255 300\n", "line 1", "0..255");
    expectBad("\n\n0 red 10 blue\n", "line 3", "colour 'red'");
    expectBad("0 0 0 0 10 1 1 1\n5 0 0 0 20 1 1 1\n", "line 2",
              "below the end of the previous slice");
    expectBad("# COLOR_MODEL = HSV\n0 0 1 1 10 100 1 1\n", "line 1", "HSV");
    expectBad("0 0 0 0 10 1 1 1\nX 1 2 3\n", "line 2", "neither a height");
    expectBad("0 0 0 0 10 1 1 1\nB 1/2\n", "line 2", "r/g/b");
    expectBad("0 0 0 0\n", "line 1", "");
    try {
        parseCpt("# only comments\n\n", "empty.cpt");
        ADD_FAILURE();
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("no colour slices"));
    }
}

}  // namespace
}  // namespace sierra::terrain
