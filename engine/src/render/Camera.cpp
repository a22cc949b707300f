#include <sierra/render/Camera.h>

#include <sierra/core/Error.h>

#include <sierra/sbt/Refiner.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>

namespace sierra::render {

glm::mat4 Camera::view() const { return glm::lookAt(position, target, up); }

glm::mat4 Camera::projection(float aspect) const {
    return glm::perspective(glm::radians(fovYDegrees), aspect, nearPlane, farPlane);
}

std::array<glm::vec4, 6> Camera::frustumPlanes(float aspect) const {
    // The SBT's extraction (Gribb-Hartmann, same plane order), so the planes the
    // renderer reasons with are exactly the ones refinement culls by.
    glm::mat4 m = viewProjection(aspect);
    std::array<sbt::Plane, 6> sbtPlanes = sbt::frustumPlanes(glm::value_ptr(m));
    std::array<glm::vec4, 6> planes;
    for (size_t k = 0; k < 6; ++k)
        planes[k] = {sbtPlanes[k].a, sbtPlanes[k].b, sbtPlanes[k].c, sbtPlanes[k].d};
    return planes;
}

float Camera::lambda(int viewportHeight) const {
    return float(viewportHeight) / (2.0f * std::tan(glm::radians(fovYDegrees) * 0.5f));
}

namespace {

// Camera distance from the centre and height above the top for the default view.
struct OrbitShape {
    float radius;
    float height;
};

OrbitShape orbitShape(const SceneBounds& b) {
    glm::vec3 s = b.size();
    float extent = std::max(s.x, s.z);
    return {0.9f * extent, b.max.y + 0.3f * extent};
}

Camera cameraAt(const SceneBounds& b, glm::vec3 position, glm::vec3 target) {
    Camera c;
    c.position = position;
    c.target = target;
    float extent = std::max({b.size().x, b.size().z, 1.0f});
    c.nearPlane = extent * 1e-3f;
    c.farPlane = extent * 4.0f;
    return c;
}

}  // namespace

Camera defaultCamera(const SceneBounds& bounds) { return orbitPath(bounds, 1).front(); }

std::vector<Camera> orbitPath(const SceneBounds& bounds, int frames) {
    SIERRA_CHECK(frames > 0, "a camera path needs at least one frame, got ", frames);
    OrbitShape shape = orbitShape(bounds);
    glm::vec3 centre = bounds.centre();
    glm::vec3 target{centre.x, bounds.min.y + 0.25f * bounds.size().y, centre.z};
    std::vector<Camera> path;
    path.reserve(size_t(frames));
    // Start at the south-west (angle 225 degrees: -x, +z) and turn anticlockwise.
    const float start = glm::radians(135.0f);
    for (int k = 0; k < frames; ++k) {
        float a = start + 2.0f * glm::pi<float>() * float(k) / float(frames);
        glm::vec3 pos{centre.x + shape.radius * std::cos(a), shape.height,
                      centre.z + shape.radius * std::sin(a)};
        path.push_back(cameraAt(bounds, pos, target));
    }
    return path;
}

std::vector<Camera> flyoverPath(const SceneBounds& bounds, int frames) {
    SIERRA_CHECK(frames > 0, "a camera path needs at least one frame, got ", frames);
    glm::vec3 s = bounds.size();
    float height = bounds.max.y + 0.04f * std::max(s.x, s.z);
    std::vector<Camera> path;
    path.reserve(size_t(frames));
    for (int k = 0; k < frames; ++k) {
        float t = frames == 1 ? 0.0f : float(k) / float(frames - 1);
        float z = bounds.max.z - (0.05f + 0.75f * t) * s.z;
        float x = bounds.min.x + (0.35f + 0.3f * t) * s.x;
        glm::vec3 pos{x, height, z};
        glm::vec3 ahead{x + 0.05f * s.x, bounds.min.y + 0.3f * s.y, z - 0.3f * s.z};
        path.push_back(cameraAt(bounds, pos, ahead));
    }
    return path;
}

}  // namespace sierra::render
