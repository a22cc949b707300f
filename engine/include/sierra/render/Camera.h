#pragma once
// Perspective look-at camera and camera paths over a terrain.

#include <glm/glm.hpp>

#include <array>
#include <vector>

namespace sierra::render {

struct Camera {
    glm::vec3 position{0.0f, 100.0f, 0.0f};  // world units
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fovYDegrees = 45.0f;  // vertical field of view
    float nearPlane = 1.0f;     // world units; > 0
    float farPlane = 1.0e5f;

    glm::mat4 view() const;
    glm::mat4 projection(float aspect) const;
    glm::mat4 viewProjection(float aspect) const { return projection(aspect) * view(); }

    // The 6 frustum planes (a, b, c, d), normalised, with a*x + b*y + c*z + d >= 0
    // inside: left, right, bottom, top, near, far.
    std::array<glm::vec4, 6> frustumPlanes(float aspect) const;

    // Pixels per unit of screen-space error at unit distance:
    // viewportHeight / (2 tan(fovY / 2)).
    float lambda(int viewportHeight) const;
};

// Extent of the scene a path moves over: the terrain's bounding box.
struct SceneBounds {
    glm::vec3 min{0.0f};
    glm::vec3 max{1.0f};
    glm::vec3 centre() const { return 0.5f * (min + max); }
    glm::vec3 size() const { return max - min; }
};

// The default view of a terrain: from the south-west corner, above the
// highest point, looking at the centre.
Camera defaultCamera(const SceneBounds& bounds);

// `frames` cameras circling the centre once at the default camera's distance and
// height (frame 0 = defaultCamera()).
std::vector<Camera> orbitPath(const SceneBounds& bounds, int frames);

// `frames` cameras flying low across the terrain from the south edge to the
// north edge, looking ahead and slightly down.
std::vector<Camera> flyoverPath(const SceneBounds& bounds, int frames);

}  // namespace sierra::render
