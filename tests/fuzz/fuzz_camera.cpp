// libFuzzer target: a scene file's cameras. The JSON is read and checked as
// the apps do (parseJson, sceneFromJson, validateScene); a scene that passes
// then gives every camera of its sequence (facade::sceneCameras over a fixed
// terrain box), and each must be usable: finite position and target, clip
// planes with 0 < near < far for perspective, finite view and projection
// matrices and frustum planes. fuzz_scene stops at validateScene; this one
// follows the camera part (paths, keyframe splines, framing) to the matrices.
// A sierra::Error is an accepted answer; anything else is a finding.

#include <sierra/core/Error.h>
#include <sierra/facade/SceneView.h>
#include <sierra/scene/Scene.h>
#include <sierra/scene/SceneJson.h>

#include <glm/glm.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

namespace {

// The default terrain's box (257^2 samples, unit spacing, relief 40) with a
// flat outline: framing runs on the box's corners.
const sierra::render::SceneBounds kBounds{.min = {0.0f, -5.0f, 0.0f},
                                          .max = {256.0f, 35.0f, 256.0f}};

// A sequence this long already walks every branch of the paths; longer ones
// would only make each run slower.
constexpr int kMaxFrames = 1024;

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
bool finite(const glm::vec4& v) {
    return finite(glm::vec3(v)) && std::isfinite(v.w);
}
bool finite(const glm::mat4& m) {
    for (int c = 0; c < 4; ++c)
        if (!finite(m[c])) return false;
    return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        const sierra::scene::Scene scene =
            sierra::scene::sceneFromJson(sierra::scene::parseJson(text, "fuzz.json"), "fuzz.json");
        sierra::scene::validateScene(scene);
        if (scene.path.frames > kMaxFrames) return 0;
        const float aspect = float(scene.output.width) / float(scene.output.height);
        for (const sierra::render::Camera& camera : sierra::facade::sceneCameras(scene, kBounds)) {
            if (!finite(camera.position) || !finite(camera.target)) __builtin_trap();
            if (camera.projection == sierra::render::Projection::Perspective &&
                !(camera.nearPlane > 0.0f && camera.nearPlane < camera.farPlane))
                __builtin_trap();
            if (!finite(camera.view()) || !finite(camera.projectionMatrix(aspect)))
                __builtin_trap();
            for (const glm::vec4& plane : camera.frustumPlanes(aspect))
                if (!finite(plane)) __builtin_trap();
        }
    } catch (const sierra::Error&) {
    }
    return 0;
}
