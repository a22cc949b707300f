// facade::SceneRenderer: the pipelined read-back gives the frames frame(k)
// gives, the set-up is reported line by line, each frame has its own sun and
// camera, and frames outside the sequence are refused.
#include <sierra/core/Error.h>
#include <sierra/facade/SceneRenderer.h>
#include <sierra/facade/SceneView.h>

#include "GlTest.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

using namespace sierra;

namespace {

constexpr int kWidth = 96, kHeight = 64;

scene::Scene orbitScene(int frames) {
    scene::Scene s;
    s.terrain.generateSize = 65;
    s.output.width = kWidth;
    s.output.height = kHeight;
    s.output.msaa = 0;
    s.path.type = scene::PathType::Orbit;
    s.path.frames = frames;
    return s;
}

std::shared_ptr<gpu::EglContext> debugContext() {
    auto context = std::make_shared<gpu::EglContext>(
        gpu::EglContext::create({.width = kWidth, .height = kHeight, .debug = true}));
    test::keepGlDriverLoaded();
    return context;
}

TEST(SceneRendererFacade, SubmittedFramesAreTheFramesOfFrame) {
    facade::SceneRenderer r = facade::SceneRenderer::create(orbitScene(3), debugContext());
    ASSERT_EQ(r.frameCount(), 3);
    std::vector<gpu::Image> direct;
    for (int k = 0; k < 3; ++k) direct.push_back(r.frame(k));
    // An orbit's frames differ, so a frame handed back out of turn would show.
    EXPECT_NE(direct[0].rgba, direct[1].rgba);

    std::vector<gpu::Image> piped;
    gpu::Image image;
    EXPECT_FALSE(r.submitFrame(0, image));  // nothing was in flight before frame 0
    EXPECT_GT(r.lastStats().triangles, 0u);
    for (int k = 1; k < 3; ++k) {
        ASSERT_TRUE(r.submitFrame(k, image));
        piped.push_back(std::move(image));
    }
    ASSERT_TRUE(r.finishFrames(image));
    piped.push_back(std::move(image));
    EXPECT_FALSE(r.finishFrames(image));
    ASSERT_EQ(piped.size(), 3u);
    for (int k = 0; k < 3; ++k) {
        SCOPED_TRACE(k);
        EXPECT_EQ(piped[size_t(k)].width, kWidth);
        EXPECT_EQ(piped[size_t(k)].height, kHeight);
        EXPECT_EQ(piped[size_t(k)].rgba, direct[size_t(k)].rgba);
    }
}

TEST(SceneRendererFacade, SetUpIsReportedInOrder) {
    scene::Scene s = orbitScene(1);
    s.zones.map = "auto";
    std::vector<std::string> lines;
    facade::SceneRenderer r = facade::SceneRenderer::create(
        s, debugContext(), nullptr,
        {.report = [&](const std::string& line) { lines.push_back(line); }});
    ASSERT_EQ(lines.size(), 3u);  // terrain, the zone surface, the GPU data
    EXPECT_EQ(lines[0], "terrain: " + r.terrainDescription());
    EXPECT_NE(lines[1].find("zone"), std::string::npos) << lines[1];
    EXPECT_EQ(lines[2].rfind("terrain on the GPU: ", 0), 0u) << lines[2];
    EXPECT_EQ(r.description(), lines[0] + "; " + lines[1]);
}

TEST(SceneRendererFacade, EachFrameHasItsOwnSun) {
    scene::Scene s = orbitScene(3);
    s.lighting.sunTime = "2024-06-01T06:00:00Z";
    s.lighting.latitude = 46.0f;
    s.lighting.longitude = 7.0f;
    s.lighting.sunStep = 3600.0f;
    facade::SceneRenderer r = facade::SceneRenderer::create(s, debugContext());
    for (int k = 0; k < 3; ++k) {
        SCOPED_TRACE(k);
        const glm::vec3 sun = r.drawOptions(k).lighting.sunDirection;
        const glm::vec3 expected = facade::sceneSunDirection(s, r.field(), k);
        EXPECT_EQ(sun.x, expected.x);
        EXPECT_EQ(sun.y, expected.y);
        EXPECT_EQ(sun.z, expected.z);
    }
    // An hour apart in the morning the sun has climbed.
    EXPECT_GT(r.drawOptions(2).lighting.sunDirection.y, r.drawOptions(0).lighting.sunDirection.y);
    EXPECT_EQ(r.drawOptions(1).lod, r.drawOptions().lod);
}

TEST(SceneRendererFacade, SunWithoutAPlaceFailsBeforeTheGpuWorkWhenAsked) {
    scene::Scene s = orbitScene(1);
    s.lighting.sunTime = "2024-06-01T06:00:00Z";  // a generated terrain has no place
    EXPECT_THROW(facade::SceneRenderer::create(s, debugContext(), nullptr, {.describeSun = true}),
                 Error);
    facade::SceneRenderer r = facade::SceneRenderer::create(s, debugContext());
    EXPECT_THROW(r.frame(0), Error);
}

TEST(SceneRendererFacade, FramesOutsideTheSequenceAreRefused) {
    facade::SceneRenderer r = facade::SceneRenderer::create(orbitScene(2), debugContext());
    const render::Camera last = r.camera(1);
    EXPECT_NE(last.position, r.camera(0).position);
    gpu::Image image;
    EXPECT_THROW(r.camera(2), Error);
    EXPECT_THROW(r.frame(-1), Error);
    EXPECT_THROW(r.depth(2), Error);
    EXPECT_THROW(r.submitFrame(2, image), Error);
}

}  // namespace
