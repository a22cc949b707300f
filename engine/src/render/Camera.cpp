#include <sierra/render/Camera.h>

#include <sierra/core/Error.h>

#include <sierra/sbt/Refiner.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>

namespace sierra::render {

glm::vec3 Camera::forward() const {
    glm::vec3 d = target - position;
    float len = glm::length(d);
    SIERRA_CHECK(len > 0.0f && std::isfinite(len),
                 "the camera position and target must differ, got (", position.x, ", ", position.y,
                 ", ", position.z, ") for both");
    return d / len;
}

glm::vec3 Camera::up() const {
    glm::vec3 f = forward();
    // Within about 2.5 degrees of vertical the world up is too close to the
    // view direction for lookAt: use north, which puts north at the top.
    return std::abs(f.y) > 0.999f ? glm::vec3(0.0f, 0.0f, -1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
}

glm::mat4 Camera::view() const {
    return glm::lookAt(position, target, up());
}

glm::mat4 Camera::projectionMatrix(float aspect) const {
    if (projection == Projection::Orthographic) {
        float h = 0.5f * orthoHeight, w = h * aspect;
        return glm::ortho(-w, w, -h, h, nearPlane, farPlane);
    }
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
    if (projection == Projection::Orthographic) return float(viewportHeight) / orthoHeight;
    return float(viewportHeight) / (2.0f * std::tan(glm::radians(fovYDegrees) * 0.5f));
}

LodView Camera::lodView(int viewportHeight) const {
    if (projection == Projection::Perspective) return {position, lambda(viewportHeight)};
    float distance = kOrthoLodDistance * std::max(farPlane, orthoHeight);
    return {position - forward() * distance, lambda(viewportHeight) * distance};
}

std::array<glm::vec3, 8> SceneBounds::corners() const {
    std::array<glm::vec3, 8> c;
    for (int k = 0; k < 8; ++k)
        c[size_t(k)] = {k & 1 ? max.x : min.x, k & 2 ? max.y : min.y, k & 4 ? max.z : min.z};
    return c;
}

std::vector<glm::vec3> SceneBounds::framePoints() const {
    if (!outline.empty()) return outline;
    std::array<glm::vec3, 8> c = corners();
    return {c.begin(), c.end()};
}

glm::vec3 compassDirection(float azimuthDeg, float elevationDeg) {
    float a = glm::radians(azimuthDeg), e = glm::radians(elevationDeg);
    return {std::sin(a) * std::cos(e), std::sin(e), -std::cos(a) * std::cos(e)};
}

void fitClipPlanes(Camera& camera, const SceneBounds& bounds) {
    glm::vec3 f = camera.forward();
    float nearest = std::numeric_limits<float>::max(), farthest = -nearest;
    for (const glm::vec3& c : bounds.corners()) {
        float depth = glm::dot(c - camera.position, f);
        nearest = std::min(nearest, depth);
        farthest = std::max(farthest, depth);
    }
    float extent = std::max({bounds.size().x, bounds.size().y, bounds.size().z, 1e-3f});
    // Margins of 1% keep the box's own faces inside the clip volume.
    camera.farPlane = std::max(farthest, 0.0f) + 0.01f * extent + 1e-3f;
    float minNear = camera.farPlane * 1e-4f;
    camera.nearPlane = std::max(nearest - 0.01f * extent, minNear);
    if (camera.projection == Projection::Orthographic) camera.nearPlane = nearest - 0.01f * extent;
}

glm::vec3 defaultTarget(const SceneBounds& bounds) {
    glm::vec3 centre = bounds.centre();
    return {centre.x, bounds.min.y + 0.25f * bounds.size().y, centre.z};
}

namespace {

// The camera's basis looking along -dir (dir points from the target to the camera).
struct Basis {
    glm::vec3 forward, right, up;
};

Basis basisFor(glm::vec3 dir) {
    Camera probe;
    probe.target = glm::vec3(0.0f);
    probe.position = dir;
    glm::vec3 f = probe.forward();
    glm::vec3 r = glm::normalize(glm::cross(f, probe.up()));
    return {f, r, glm::cross(r, f)};
}

// The smallest distance from the target along dir at which every corner lies
// inside the frame with the margin.
float fitDistance(const SceneBounds& b, glm::vec3 target, const Basis& basis, float fovY,
                  float aspect) {
    float tanY = std::tan(glm::radians(fovY) * 0.5f) * (1.0f - kFrameMargin);
    float tanX = tanY * aspect;
    float distance = 0.0f;
    for (const glm::vec3& c : b.framePoints()) {
        glm::vec3 q = c - target;
        float z = glm::dot(q, basis.forward);
        distance = std::max({distance, std::abs(glm::dot(q, basis.right)) / tanX - z,
                             std::abs(glm::dot(q, basis.up)) / tanY - z});
    }
    return distance;
}

// The orthographic view height that holds every corner with the margin.
float fitOrthoHeight(const SceneBounds& b, glm::vec3 target, const Basis& basis, float aspect) {
    float half = 0.0f;
    for (const glm::vec3& c : b.framePoints()) {
        glm::vec3 q = c - target;
        half = std::max(
            {half, std::abs(glm::dot(q, basis.up)), std::abs(glm::dot(q, basis.right)) / aspect});
    }
    return std::max(2.0f * half / (1.0f - kFrameMargin), 1e-3f);
}

}  // namespace

Camera framedCamera(const SceneBounds& bounds, const FramingDesc& desc) {
    SIERRA_CHECK(desc.aspect > 0.0f, "frame aspect ratio must be positive");
    SIERRA_CHECK(desc.fovYDegrees > 0.0f && desc.fovYDegrees < 180.0f,
                 "field of view must be in (0, 180) degrees, got ", desc.fovYDegrees);
    glm::vec3 dir = compassDirection(desc.azimuthDeg, desc.elevationDeg);
    Basis basis = basisFor(dir);
    Camera c;
    c.target = desc.target;
    c.fovYDegrees = desc.fovYDegrees;
    c.projection = desc.projection;
    float extent = std::max({bounds.size().x, bounds.size().y, bounds.size().z, 1e-3f});
    float distance = desc.distance;
    if (desc.projection == Projection::Orthographic) {
        c.orthoHeight = fitOrthoHeight(bounds, desc.target, basis, desc.aspect);
        // Far enough to have the whole box in front; the distance does not change the picture.
        if (distance <= 0.0f) distance = 2.0f * extent;
    } else if (distance <= 0.0f) {
        distance = std::max(fitDistance(bounds, desc.target, basis, desc.fovYDegrees, desc.aspect),
                            1e-3f * extent);
    }
    c.position = desc.target + dir * distance;
    fitClipPlanes(c, bounds);
    return c;
}

Camera defaultCamera(const SceneBounds& bounds, float aspect, float fovYDegrees) {
    return orbitPath(bounds, 1, aspect, fovYDegrees).front();
}

namespace {

void checkFrame(int k, int frames) {
    SIERRA_CHECK(frames > 0, "a camera path needs at least one frame, got ", frames);
    SIERRA_CHECK(k >= 0 && k < frames, "frame ", k, " is outside the path's ", frames, " frames");
}

// Frame k's compass bearing: 225 degrees first, a full turn over the frames,
// kept in [0, 360) so that long paths keep float precision.
float orbitAzimuth(int64_t k, int64_t frames) {
    return float(std::fmod(225.0 + 360.0 * double(k) / double(frames), 360.0));
}

// t from 0 (first frame) to 1 (last).
float pathShare(int k, int frames) {
    return frames == 1 ? 0.0f : float(double(k) / double(frames - 1));
}

}  // namespace

float orbitDistance(const SceneBounds& bounds, int frames, float aspect, float fovYDegrees,
                    float elevationDeg) {
    SIERRA_CHECK(frames > 0, "a camera path needs at least one frame, got ", frames);
    const glm::vec3 target = defaultTarget(bounds);
    const int samples = std::min(frames, kOrbitExactFrames);
    float distance = 0.0f;
    for (int k = 0; k < samples; ++k) {
        Camera c = framedCamera(bounds, {.target = target,
                                         .azimuthDeg = orbitAzimuth(k, samples),
                                         .elevationDeg = elevationDeg,
                                         .fovYDegrees = fovYDegrees,
                                         .aspect = aspect});
        distance = std::max(distance, glm::distance(c.position, c.target));
    }
    return samples < frames ? distance * (1.0f + 1e-4f) : distance;
}

Camera orbitCamera(const SceneBounds& bounds, int k, int frames, float distance, float aspect,
                   float fovYDegrees, float elevationDeg) {
    checkFrame(k, frames);
    return framedCamera(bounds, {.target = defaultTarget(bounds),
                                 .azimuthDeg = orbitAzimuth(k, frames),
                                 .elevationDeg = elevationDeg,
                                 .fovYDegrees = fovYDegrees,
                                 .aspect = aspect,
                                 .distance = distance});
}

std::vector<Camera> orbitPath(const SceneBounds& bounds, int frames, float aspect,
                              float fovYDegrees, float elevationDeg) {
    const float distance = orbitDistance(bounds, frames, aspect, fovYDegrees, elevationDeg);
    std::vector<Camera> path;
    path.reserve(size_t(frames));
    for (int k = 0; k < frames; ++k)
        path.push_back(orbitCamera(bounds, k, frames, distance, aspect, fovYDegrees, elevationDeg));
    return path;
}

Camera flyoverCamera(const SceneBounds& bounds, int k, int frames, float fovYDegrees) {
    checkFrame(k, frames);
    glm::vec3 s = bounds.size();
    float height = bounds.max.y + 0.04f * std::max(s.x, s.z);
    float t = pathShare(k, frames);
    float z = bounds.max.z - (0.05f + 0.75f * t) * s.z;
    float x = bounds.min.x + (0.35f + 0.3f * t) * s.x;
    Camera c;
    c.position = {x, height, z};
    c.target = {x + 0.05f * s.x, bounds.min.y + 0.3f * s.y, z - 0.3f * s.z};
    c.fovYDegrees = fovYDegrees;
    fitClipPlanes(c, bounds);
    return c;
}

std::vector<Camera> flyoverPath(const SceneBounds& bounds, int frames, float fovYDegrees) {
    SIERRA_CHECK(frames > 0, "a camera path needs at least one frame, got ", frames);
    std::vector<Camera> path;
    path.reserve(size_t(frames));
    for (int k = 0; k < frames; ++k) path.push_back(flyoverCamera(bounds, k, frames, fovYDegrees));
    return path;
}

namespace {
// Centripetal-free uniform Catmull-Rom between p1 and p2 at t in [0, 1].
glm::vec3 catmullRom(glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, glm::vec3 p3, float t) {
    float t2 = t * t, t3 = t2 * t;
    return 0.5f * ((2.0f * p1) + (-p0 + p2) * t + (2.0f * p0 - 5.0f * p1 + 4.0f * p2 - p3) * t2 +
                   (-p0 + 3.0f * p1 - 3.0f * p2 + p3) * t3);
}
}  // namespace

void checkKeyframes(const std::vector<Keyframe>& keys) {
    SIERRA_CHECK(!keys.empty(), "a keyframe path needs at least one keyframe");
    for (size_t k = 1; k < keys.size(); ++k)
        SIERRA_CHECK(keys[k].time > keys[k - 1].time, "keyframe times must increase: keyframe ", k,
                     " at ", keys[k].time, " follows ", keys[k - 1].time);
}

Camera keyframeCamera(const SceneBounds& bounds, const std::vector<Keyframe>& keys, int f,
                      int frames, float fovYDegrees) {
    checkFrame(f, frames);
    SIERRA_CHECK(!keys.empty(), "a keyframe path needs at least one keyframe");
    float u = pathShare(f, frames);
    float time = keys.front().time + u * (keys.back().time - keys.front().time);
    const size_t last = keys.size() - 1;
    Camera c;
    c.fovYDegrees = fovYDegrees;
    if (keys.size() == 1) {
        c.position = keys[0].position;
        c.target = keys[0].target;
    } else {
        // The segment [i, i + 1] holding `time`: the last key at or before it,
        // but never the last key itself.
        auto after = std::upper_bound(keys.begin() + 1, keys.begin() + long(last), time,
                                      [](float t, const Keyframe& k) { return t < k.time; });
        size_t i = size_t(after - keys.begin()) - 1;
        float t = std::clamp((time - keys[i].time) / (keys[i + 1].time - keys[i].time), 0.0f, 1.0f);
        const Keyframe& k0 = keys[i == 0 ? 0 : i - 1];
        const Keyframe& k3 = keys[std::min(i + 2, last)];
        c.position =
            catmullRom(k0.position, keys[i].position, keys[i + 1].position, k3.position, t);
        c.target = catmullRom(k0.target, keys[i].target, keys[i + 1].target, k3.target, t);
    }
    fitClipPlanes(c, bounds);
    return c;
}

std::vector<Camera> keyframePath(const SceneBounds& bounds, const std::vector<Keyframe>& keys,
                                 int frames, float fovYDegrees) {
    SIERRA_CHECK(frames > 0, "a camera path needs at least one frame, got ", frames);
    checkKeyframes(keys);
    std::vector<Camera> path;
    path.reserve(size_t(frames));
    for (int f = 0; f < frames; ++f)
        path.push_back(keyframeCamera(bounds, keys, f, frames, fovYDegrees));
    return path;
}

}  // namespace sierra::render
