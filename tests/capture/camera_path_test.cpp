// facade::SceneCameraPath: frame k's camera alone is the camera the whole
// list holds, and a path of a billion frames is set up and walked in
// constant time per frame.
#include <sierra/core/Error.h>
#include <sierra/core/Timer.h>
#include <sierra/facade/SceneView.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace sierra;

namespace {

const render::SceneBounds kBounds{{0.0f, -20.0f, 0.0f}, {1024.0f, 180.0f, 1024.0f}};

scene::Scene pathScene(scene::PathType type, int frames) {
    scene::Scene s;
    s.path.type = type;
    s.path.frames = frames;
    if (type == scene::PathType::Keyframes)
        s.path.keyframes = {{0.0f, {0, 300, 1200}, {512, 0, 512}},
                            {1.0f, {1200, 250, 512}, {512, 0, 512}},
                            {3.0f, {512, 400, -200}, {500, 10, 500}}};
    return s;
}

void expectSame(const render::Camera& a, const render::Camera& b, float tolerance = 1e-4f) {
    EXPECT_NEAR(glm::distance(a.position, b.position), 0.0f, tolerance);
    EXPECT_NEAR(glm::distance(a.target, b.target), 0.0f, tolerance);
    EXPECT_NEAR(a.nearPlane, b.nearPlane, tolerance * std::max(1.0f, a.nearPlane));
    EXPECT_NEAR(a.farPlane, b.farPlane, tolerance * a.farPlane);
    EXPECT_EQ(a.orthoHeight, b.orthoHeight);
}

// Compass bearing (degrees, 0..360) from the target to the camera.
float bearing(const render::Camera& c) {
    glm::vec3 d = c.position - c.target;
    float a = std::atan2(d.x, -d.z) * 180.0f / 3.14159265f;
    return a < 0.0f ? a + 360.0f : a;
}

}  // namespace

TEST(SceneCameraPath, EachFrameIsTheListsCamera) {
    for (auto type : {scene::PathType::None, scene::PathType::Orbit, scene::PathType::Flyover,
                      scene::PathType::Keyframes}) {
        for (bool ortho : {false, true}) {
            scene::Scene s = pathScene(type, 37);
            if (ortho) s.camera.projection = scene::Projection::Orthographic;
            if (type == scene::PathType::Orbit) s.camera.target = scene::Vec3{400, 10, 600};
            const std::vector<render::Camera> list = facade::sceneCameras(s, kBounds);
            const facade::SceneCameraPath path(s, kBounds);
            ASSERT_EQ(path.frames(), 37);
            ASSERT_EQ(list.size(), 37u);
            for (int k : {0, 1, 18, 36}) {
                SCOPED_TRACE(msg(scene::toString(type), ortho ? " ortho" : "", " frame ", k));
                expectSame(path.at(k), list[size_t(k)]);
                expectSame(facade::sceneCamera(s, kBounds, k), list[size_t(k)]);
            }
            EXPECT_THROW(path.at(37), Error);
            EXPECT_THROW(path.at(-1), Error);
        }
    }
}

TEST(SceneCameraPath, ABillionFrameOrbitIsConstantTimePerFrame) {
    const int frames = 1000000000;
    Stopwatch clock;
    const facade::SceneCameraPath path(pathScene(scene::PathType::Orbit, frames), kBounds);
    int64_t steps = 0;
    for (int k = 0; k < frames; k += frames / 1000, ++steps) (void)path.at(k);
    const render::Camera lastFrame = path.at(frames - 1);
    // 4096 framings and 1000 frames take milliseconds; building every camera
    // (the list) would take many minutes.
    EXPECT_LT(clock.ms(), 5000.0);
    EXPECT_EQ(steps, 1000);
    // The turn is spread over the frames: a quarter of the way, a quarter turn.
    EXPECT_NEAR(bearing(path.at(0)), 225.0f, 1e-3f);
    EXPECT_NEAR(bearing(path.at(frames / 4)), 315.0f, 1e-3f);
    EXPECT_NEAR(bearing(lastFrame), 225.0f, 1e-3f);
    // The sampled distance still frames the terrain at every azimuth: not
    // closer than an exact orbit's (4096 azimuths) nor more than 1e-4 beyond.
    const float exact = render::orbitDistance(kBounds, render::kOrbitExactFrames, 16.0f / 9.0f);
    const float sampled = render::orbitDistance(kBounds, frames, 16.0f / 9.0f);
    EXPECT_GE(sampled, exact);
    EXPECT_LE(sampled, exact * 1.00011f);
}

TEST(SceneCameraPath, SampledOrbitDistanceFramesEveryFrame) {
    // 10007 frames (more than kOrbitExactFrames, prime, so most azimuths
    // are not sampled): no frame needs more than the distance taken.
    const int frames = 10007;
    const float aspect = 16.0f / 9.0f;
    const float distance = render::orbitDistance(kBounds, frames, aspect);
    const glm::vec3 target = render::defaultTarget(kBounds);
    for (int k = 0; k < frames; ++k) {
        const float azimuth = float(std::fmod(225.0 + 360.0 * k / frames, 360.0));
        const render::Camera fitted = render::framedCamera(
            kBounds, {.target = target, .azimuthDeg = azimuth, .aspect = aspect});
        ASSERT_LE(glm::distance(fitted.position, fitted.target), distance) << "frame " << k;
    }
}

TEST(SceneCameraPath, KeyframesAreCheckedOnce) {
    scene::Scene s = pathScene(scene::PathType::Keyframes, 10);
    s.path.keyframes[2].time = 0.5f;  // goes back in time
    EXPECT_THROW(facade::SceneCameraPath(s, kBounds), Error);
}

namespace {

// The scene's output settings become the render module's image encoding.
TEST(FrameEncoding, FollowsTheSceneOutput) {
    scene::OutputDesc output;
    const std::pair<scene::PngCompression, render::PngCompression> levels[] = {
        {scene::PngCompression::Fast, render::PngCompression::Fast},
        {scene::PngCompression::Default, render::PngCompression::Default},
        {scene::PngCompression::Best, render::PngCompression::Best}};
    for (auto [from, to] : levels) {
        output.pngCompression = from;
        EXPECT_EQ(facade::frameEncoding(output).png, to);
    }
    output.jpegQuality = 37;
    output.alpha = true;
    const render::ImageEncoding encoding = facade::frameEncoding(output);
    EXPECT_EQ(encoding.jpegQuality, 37);
    EXPECT_TRUE(encoding.alpha);
}

}  // namespace
