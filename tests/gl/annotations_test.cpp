// Map furniture (render/Annotations.h): where labels, the scale bar and the
// north arrow go, and that the overlay draws them there.

#include "GlTest.h"
#include "GoldenCompare.h"

#include <sierra/core/Error.h>
#include <sierra/facade/MapLayers.h>
#include <sierra/render/Annotations.h>
#include <sierra/render/FrameTarget.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace sierra::test {
namespace {

using render::AnnotationDesc;
using render::Camera;
using render::Label;
using render::Projection;

// 8 pixels a character, 16 high: the layout's rules without a font.
glm::vec2 fixedMeasure(const std::string& text) {
    return {8.0f * float(text.size()), 16.0f};
}

// Straight down, orthographic, 1000 world units from the bottom of the frame
// to the top: north (-z) up, east (+x) right.
Camera nadir(float orthoHeight = 1000.0f) {
    Camera c;
    c.projection = Projection::Orthographic;
    c.position = {0.0f, 500.0f, 0.0f};
    c.target = {0.0f, 0.0f, 0.0f};
    c.orthoHeight = orthoHeight;
    c.nearPlane = 1.0f;
    c.farPlane = 1000.0f;
    return c;
}

TEST(AnnotationLayout, ScaleBarLengthsAreOneTwoOrFiveTimesAPowerOfTen) {
    auto bar = render::chooseScaleBar(3.7, 200.0f);  // at most 740 m fit
    EXPECT_DOUBLE_EQ(bar.groundLength, 500.0);
    EXPECT_NEAR(bar.pixels, 500.0 / 3.7, 1e-3);
    EXPECT_EQ(bar.text, "500 m");
    bar = render::chooseScaleBar(12.0, 200.0f);  // 2400 m fit
    EXPECT_DOUBLE_EQ(bar.groundLength, 2000.0);
    EXPECT_EQ(bar.text, "2 km");
    bar = render::chooseScaleBar(0.004, 200.0f);  // 0.8 m fit
    EXPECT_DOUBLE_EQ(bar.groundLength, 0.5);
    EXPECT_THROW(render::chooseScaleBar(0.0, 200.0f), Error);
}

TEST(AnnotationLayout, OrthographicScaleBarIsTheTrueGroundDistance) {
    const int width = 800, height = 500;  // 2 world units a pixel
    AnnotationDesc desc;
    desc.scaleBar = true;
    for (float unitsPerMetre : {1.0f, 0.5f, 3.0f}) {
        desc.unitsPerMetre = unitsPerMetre;
        auto layout =
            render::layoutAnnotations(desc, nadir(), width, height, nullptr, fixedMeasure);
        ASSERT_TRUE(layout.scaleBar);
        const double metres = layout.scaleBar->pixels * 2.0 / unitsPerMetre;
        EXPECT_NEAR(metres, layout.scaleBar->groundLength, 2.0 / unitsPerMetre)
            << "within one pixel, " << unitsPerMetre << " units a metre";
        EXPECT_LE(layout.scaleBar->pixels, 0.25f * width);
        EXPECT_FALSE(layout.scaleBar->atTarget);
        EXPECT_EQ(layout.scaleBar->text.find("target"), std::string::npos);
    }
}

TEST(AnnotationLayout, TheScenesCornersPlaceTheFurniture) {
    const int width = 800, height = 500;
    using scene::FrameCorner;
    const FrameCorner all[] = {FrameCorner::TopLeft, FrameCorner::TopRight, FrameCorner::BottomLeft,
                               FrameCorner::BottomRight};
    for (int shift = 0; shift < 4; ++shift) {
        scene::FurnitureDesc f;
        f.title = "Title";
        f.scaleBar = f.northArrow = true;
        f.titleCorner = all[shift];
        f.scaleBarCorner = all[(shift + 1) % 4];
        f.northArrowCorner = all[(shift + 2) % 4];
        const AnnotationDesc desc = facade::furnitureAnnotations(f);
        auto layout =
            render::layoutAnnotations(desc, nadir(), width, height, nullptr, fixedMeasure);
        ASSERT_TRUE(layout.titleOrigin && layout.scaleBar && layout.northArrow);
        // Each piece's point in the half of the frame its corner names.
        auto inCorner = [&](glm::vec2 p, FrameCorner c) {
            const bool right = c == FrameCorner::TopRight || c == FrameCorner::BottomRight;
            const bool bottom = c == FrameCorner::BottomLeft || c == FrameCorner::BottomRight;
            return (p.x > 0.5f * width) == right && (p.y > 0.5f * height) == bottom;
        };
        EXPECT_TRUE(inCorner(*layout.titleOrigin, f.titleCorner)) << scene::toString(f.titleCorner);
        EXPECT_TRUE(
            inCorner(layout.scaleBar->origin + glm::vec2(0.5f * layout.scaleBar->pixels, 0.0f),
                     f.scaleBarCorner))
            << scene::toString(f.scaleBarCorner);
        EXPECT_TRUE(inCorner(layout.northArrow->centre, f.northArrowCorner))
            << scene::toString(f.northArrowCorner);
    }
}

TEST(AnnotationLayout, PerspectiveScaleBarSaysItHoldsAtTheTarget) {
    Camera c;
    c.position = {0.0f, 300.0f, 400.0f};  // 500 from the target
    c.target = {0.0f, 0.0f, 0.0f};
    c.fovYDegrees = 60.0f;
    EXPECT_NEAR(render::worldUnitsPerPixel(c, 500), 2.0 * 500.0 * std::tan(M_PI / 6.0) / 500.0,
                1e-9);
    AnnotationDesc desc;
    desc.scaleBar = true;
    auto layout = render::layoutAnnotations(desc, c, 800, 500, nullptr, fixedMeasure);
    ASSERT_TRUE(layout.scaleBar);
    EXPECT_TRUE(layout.scaleBar->atTarget);
    EXPECT_NE(layout.scaleBar->text.find("at the target"), std::string::npos)
        << layout.scaleBar->text;
}

TEST(AnnotationLayout, NorthArrowPointsNorthFromEveryBearing) {
    auto from = [](float azimuth) {  // a camera south-west etc. of the target, 30 degrees up
        Camera c;
        c.target = {0.0f, 0.0f, 0.0f};
        c.position = 1000.0f * render::compassDirection(azimuth, 30.0f);
        return render::northOnFrame(c, 16.0f / 9.0f);
    };
    auto near = [](glm::vec2 a, glm::vec2 b) { return glm::length(a - b) < 1e-3f; };
    EXPECT_TRUE(near(from(180.0f), {0.0f, -1.0f}));  // from the south: north is up
    EXPECT_TRUE(near(from(0.0f), {0.0f, 1.0f}));     // from the north: down
    EXPECT_TRUE(near(from(90.0f), {1.0f, 0.0f}));    // from the east, facing west: right
    EXPECT_TRUE(near(from(270.0f), {-1.0f, 0.0f}));  // from the west: left
    EXPECT_TRUE(near(render::northOnFrame(nadir(), 1.6f), {0.0f, -1.0f}));
}

TEST(AnnotationLayout, LabelsAnchorWhereTheirPointsProject) {
    const int width = 800, height = 500;  // 2 units a pixel; x spans -800..800
    AnnotationDesc desc;
    desc.labels = {{"A", {100.0f, 0.0f, -200.0f}}, {"B", {-700.0f, 0.0f, 240.0f}}};
    auto layout = render::layoutAnnotations(desc, nadir(), width, height, nullptr, fixedMeasure);
    ASSERT_EQ(layout.labels.size(), 2u);
    EXPECT_NEAR(layout.labels[0].anchor.x, 400.0f + 50.0f, 0.01f);
    EXPECT_NEAR(layout.labels[0].anchor.y, 250.0f - 100.0f, 0.01f);
    EXPECT_NEAR(layout.labels[1].anchor.x, 400.0f - 350.0f, 0.01f);
    EXPECT_NEAR(layout.labels[1].anchor.y, 250.0f + 120.0f, 0.01f);
    for (const auto& l : layout.labels) {
        EXPECT_FALSE(l.leader);  // room beside the anchor: no leader
        // Beside the anchor: the box's nearest corner 6 px away on both axes.
        const glm::vec2 nearest = glm::clamp(l.anchor, l.boxMin, l.boxMax);
        EXPECT_NEAR(std::abs(nearest.x - l.anchor.x), 6.0f, 0.01f);
        EXPECT_NEAR(std::abs(nearest.y - l.anchor.y), 6.0f, 0.01f);
    }
    // Off the frame, or behind a perspective eye: not shown, and counted.
    desc.labels = {{"off", {5000.0f, 0.0f, 0.0f}}};
    layout = render::layoutAnnotations(desc, nadir(), width, height, nullptr, fixedMeasure);
    EXPECT_TRUE(layout.labels.empty());
    EXPECT_EQ(layout.outsideFrame, 1);
}

TEST(AnnotationLayout, NoTwoLabelsOverlapAndHigherPriorityWins) {
    const int width = 640, height = 360;
    std::mt19937 random(7);
    std::uniform_real_distribution<float> x(-550.0f, 550.0f), z(-480.0f, 480.0f);
    AnnotationDesc desc;
    desc.scaleBar = desc.northArrow = true;
    desc.title = "Crowded";
    for (int i = 0; i < 120; ++i)
        desc.labels.push_back(
            {"label " + std::to_string(i), {x(random), 0.0f, z(random)}, float(i % 5)});
    auto layout = render::layoutAnnotations(desc, nadir(), width, height, nullptr, fixedMeasure);
    EXPECT_EQ(int(layout.labels.size()) + layout.crowdedOut + layout.outsideFrame +
                  layout.hiddenBehindTerrain,
              120);
    EXPECT_GT(layout.labels.size(), 20u);
    EXPECT_GT(layout.crowdedOut, 0) << "120 labels do not all fit in 640x360";
    for (size_t a = 0; a < layout.labels.size(); ++a) {
        const auto& la = layout.labels[a];
        EXPECT_GE(la.boxMin.x, 0.0f);
        EXPECT_GE(la.boxMin.y, 0.0f);
        EXPECT_LE(la.boxMax.x, float(width));
        EXPECT_LE(la.boxMax.y, float(height));
        for (size_t b = a + 1; b < layout.labels.size(); ++b) {
            const auto& lb = layout.labels[b];
            const bool apart = la.boxMax.x <= lb.boxMin.x || lb.boxMax.x <= la.boxMin.x ||
                               la.boxMax.y <= lb.boxMin.y || lb.boxMax.y <= la.boxMin.y;
            EXPECT_TRUE(apart) << desc.labels[size_t(la.index)].text << " overlaps "
                               << desc.labels[size_t(lb.index)].text;
        }
    }
    // Placement order is by priority: no shown label follows one of a higher priority.
    for (size_t a = 1; a < layout.labels.size(); ++a)
        EXPECT_GE(desc.labels[size_t(layout.labels[a - 1].index)].priority,
                  desc.labels[size_t(layout.labels[a].index)].priority);

    // Two labels on one point: the higher priority takes the first place.
    desc = {};
    desc.labels = {{"low", {0.0f, 0.0f, 0.0f}, 1.0f}, {"high", {0.0f, 0.0f, 0.0f}, 2.0f}};
    layout = render::layoutAnnotations(desc, nadir(), width, height, nullptr, fixedMeasure);
    ASSERT_EQ(layout.labels.size(), 2u);
    EXPECT_EQ(layout.labels[0].index, 1);
    EXPECT_GT(layout.labels[0].boxMin.x, layout.labels[0].anchor.x);  // right and above
    EXPECT_LT(layout.labels[0].boxMax.y, layout.labels[0].anchor.y);
}

TEST(AnnotationLayout, LabelsBehindTerrainAreHidden) {
    const int width = 300, height = 100;
    Camera c;
    c.position = {0.0f, 0.0f, 100.0f};
    c.target = {0.0f, 0.0f, 0.0f};  // looking north along -z
    render::DepthImage depth{width, height, std::vector<float>(size_t(width * height), 60.0f)};
    // The left half of the frame is sky.
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width / 2; ++x) depth.depth[size_t(y * width + x)] = NAN;
    AnnotationDesc desc;
    desc.labels = {
        {"behind", {5.0f, 0.0f, 0.0f}},    // 100 away, terrain at 60
        {"on top", {5.0f, 5.0f, 40.2f}},   // 59.8 away: in front of it
        {"in sky", {-5.0f, 0.0f, -50.0f}}  // 150 away, no terrain there
    };
    auto layout = render::layoutAnnotations(desc, c, width, height, &depth, fixedMeasure);
    EXPECT_EQ(layout.hiddenBehindTerrain, 1);
    std::vector<int> shown;
    for (const auto& l : layout.labels) shown.push_back(l.index);
    std::sort(shown.begin(), shown.end());
    EXPECT_EQ(shown, (std::vector<int>{1, 2}));
}

class AnnotationDraw : public GlTest {};

// Dark ink (any channel below 100) in a rectangle of an RGBA image.
int inkIn(const gpu::Image& image, glm::vec2 min, glm::vec2 max) {
    int count = 0;
    for (int y = std::max(0, int(min.y)); y < std::min(image.height, int(std::ceil(max.y))); ++y)
        for (int x = std::max(0, int(min.x)); x < std::min(image.width, int(std::ceil(max.x)));
             ++x) {
            const uint8_t* p = &image.rgba[size_t(y * image.width + x) * 4];
            if (p[0] < 100 && p[1] < 100 && p[2] < 100) ++count;
        }
    return count;
}

TEST_F(AnnotationDraw, InkLandsOnTheLayoutAndNowhereElse) {
    render::AnnotationOverlay overlay(16.0f);
    AnnotationDesc desc;
    desc.labels = {{"Summit", {100.0f, 0.0f, -200.0f}, 2.0f},
                   {"Lake", {-500.0f, 0.0f, 200.0f}, 1.0f},
                   // Where Summit is: three take the places left beside it, the
                   // fourth goes a leader's length away.
                   {"Col", {100.0f, 0.0f, -200.0f}},
                   {"Hut", {100.0f, 0.0f, -200.0f}},
                   {"Tarn", {100.0f, 0.0f, -200.0f}},
                   {"Cairn", {100.0f, 0.0f, -200.0f}}};
    desc.scaleBar = true;
    const Camera camera = nadir(720.0f);  // 2 units a pixel on 640x360
    auto layout = render::layoutAnnotations(desc, camera, 640, 360, nullptr, overlay.measurer());
    ASSERT_EQ(layout.labels.size(), 6u);
    auto target = render::FrameTarget::create({.width = 640, .height = 360});
    target.begin({0.7f, 0.8f, 0.7f, 1.0f});
    overlay.draw(desc, layout);
    const gpu::Image image = target.read();
    std::vector<std::pair<glm::vec2, glm::vec2>> drawn;  // where ink may be
    for (const auto& l : layout.labels) {
        EXPECT_GT(inkIn(image, l.boxMin, l.boxMax), 20)
            << desc.labels[size_t(l.index)].text << " has no text in its box";
        EXPECT_GT(inkIn(image, l.anchor - 2.0f, l.anchor + 2.0f), 4) << "the anchor's dot";
        drawn.push_back({l.boxMin, l.boxMax});
        drawn.push_back({l.anchor - 4.0f, l.anchor + 4.0f});
        if (l.leader) {  // the line from the anchor to the box's nearest point
            const glm::vec2 end = glm::clamp(l.anchor, l.boxMin, l.boxMax);
            drawn.push_back({glm::min(l.anchor, end) - 2.0f, glm::max(l.anchor, end) + 2.0f});
        }
    }
    for (int k = 0; k < 5; ++k) EXPECT_FALSE(layout.labels[size_t(k)].leader) << k;
    EXPECT_TRUE(layout.labels[5].leader) << "Cairn's places beside its point are taken";
    // The scale bar: its dark half is exactly half the bar, along its row.
    const auto& bar = *layout.scaleBar;
    const int row = int(bar.origin.y);
    int first = -1, last = -1;
    for (int x = 0; x < 640; ++x) {
        const uint8_t* p = &image.rgba[size_t(row * 640 + x) * 4];
        if (p[0] < 100) {
            if (first < 0) first = x;
            last = x;
        }
    }
    EXPECT_NEAR(first, bar.origin.x, 1.0);
    EXPECT_NEAR(last + 1 - first, bar.pixels, 1.5) << "the outlined bar spans its length";
    drawn.push_back(
        {bar.origin - glm::vec2(2.0f, 40.0f), bar.origin + glm::vec2(bar.pixels + 2.0f, 6.0f)});
    // Everything dark is a label, its dot or the bar.
    int stray = 0;
    for (int y = 0; y < 360; ++y)
        for (int x = 0; x < 640; ++x) {
            const glm::vec2 p(float(x) + 0.5f, float(y) + 0.5f);
            const bool allowed = std::any_of(drawn.begin(), drawn.end(), [&](const auto& r) {
                return p.x >= r.first.x && p.y >= r.first.y && p.x <= r.second.x &&
                       p.y <= r.second.y;
            });
            if (!allowed && inkIn(image, {float(x), float(y)}, {float(x + 1), float(y + 1)}) > 0) {
                if (++stray < 5) ADD_FAILURE() << "ink at " << x << ", " << y;
            }
        }
    EXPECT_EQ(stray, 0);
    render::writePng(testOutputPath("annotations_labels.png"), image);
    target.begin({0.7f, 0.8f, 0.7f, 1.0f});
    overlay.draw({}, render::layoutAnnotations({}, camera, 640, 360, nullptr, overlay.measurer()));
    EXPECT_EQ(inkIn(target.read(), {0.0f, 0.0f}, {640.0f, 360.0f}), 0)
        << "nothing asked, nothing drawn";
}

TEST_F(AnnotationDraw, FurnitureSitsInItsCornersAndLabelsAvoidIt) {
    render::AnnotationOverlay overlay(14.0f);
    AnnotationDesc desc;
    desc.title = "Sierra test range";
    desc.scaleBar = desc.northArrow = true;
    desc.legend = render::Legend{
        "Elevation",
        "m",
        {{0.0f, {0.1f, 0.4f, 0.1f}}, {500.0f, {0.8f, 0.7f, 0.4f}}, {1200.0f, {1.0f, 1.0f, 1.0f}}},
        {},
        render::Corner::BottomRight};
    Camera camera;
    camera.target = {0.0f, 0.0f, 0.0f};
    camera.position = 1500.0f * render::compassDirection(135.0f, 35.0f);  // from the south-east
    for (int i = 0; i < 40; ++i)
        desc.labels.push_back({"peak " + std::to_string(i),
                               {-600.0f + 30.0f * float(i), 0.0f, -300.0f + 15.0f * float(i)}});
    auto layout = render::layoutAnnotations(desc, camera, 640, 360, nullptr, overlay.measurer());
    ASSERT_TRUE(layout.titleOrigin && layout.legendOrigin && layout.northArrow && layout.scaleBar);
    auto target = render::FrameTarget::create({.width = 640, .height = 360});
    target.begin({0.7f, 0.8f, 0.7f, 1.0f});
    overlay.draw(desc, layout);
    const gpu::Image image = target.read();
    render::writePng(testOutputPath("annotations_furniture.png"), image);
    EXPECT_GT(inkIn(image, {0.0f, 0.0f}, {320.0f, 60.0f}), 100) << "the title, top left";
    EXPECT_GT(inkIn(image, {560.0f, 0.0f}, {640.0f, 100.0f}), 30) << "the north arrow, top right";
    EXPECT_GT(inkIn(image, {440.0f, 200.0f}, {640.0f, 360.0f}), 100) << "the legend, bottom right";
    EXPECT_GT(inkIn(image, {0.0f, 300.0f}, {200.0f, 360.0f}), 50) << "the scale bar, bottom left";
    // From the south-east, facing north-west: north is ahead and to the right.
    EXPECT_GT(layout.northArrow->direction.x, 0.3f);
    EXPECT_LT(layout.northArrow->direction.y, -0.3f);
    const glm::vec2 legendMax = *layout.legendOrigin + layout.legendSize;
    for (const auto& l : layout.labels) {
        const bool apart = l.boxMax.x <= layout.legendOrigin->x || l.boxMin.x >= legendMax.x ||
                           l.boxMax.y <= layout.legendOrigin->y || l.boxMin.y >= legendMax.y;
        EXPECT_TRUE(apart) << "a label over the legend";
    }
}

TEST_F(AnnotationDraw, AMissingOrWrongFontIsAClearError) {
    try {
        render::AnnotationOverlay overlay(16.0f, "/nonexistent/font.ttf");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent/font.ttf"), std::string::npos);
    }
    EXPECT_THROW(render::AnnotationOverlay(16.0f, "/etc/hostname"), Error);
    EXPECT_THROW(render::AnnotationOverlay(1.0f), Error);
}

}  // namespace
}  // namespace sierra::test
