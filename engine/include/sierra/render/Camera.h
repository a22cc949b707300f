#pragma once
// Look-at cameras (perspective or orthographic), framing a terrain, and camera
// paths over it.
//
// Directions are compass bearings: azimuth in degrees clockwise from north,
// north is -z (row 0 of a heightmap), east is +x; elevation in degrees above
// the horizon. The same convention gives the camera's place around its target
// and the sun's direction.

#include <glm/glm.hpp>

#include <array>
#include <vector>

namespace sierra::render {

enum class Projection { Perspective, Orthographic };

// Where the SBT measures distance from, and its lambda (pixels per unit of
// object-space error at unit distance).
struct LodView {
    glm::vec3 eye{0.0f};
    float lambda = 1.0f;
};

struct Camera {
    glm::vec3 position{0.0f, 100.0f, 0.0f};  // world units
    glm::vec3 target{0.0f};
    float fovYDegrees = 45.0f;  // vertical field of view (perspective)
    Projection projection = Projection::Perspective;
    float orthoHeight = 1.0f;  // world units seen from bottom to top of the frame (orthographic)
    float nearPlane = 1.0f;    // world units along the view direction; > 0 for perspective
    float farPlane = 1.0e5f;

    glm::vec3 forward() const;  // unit vector from position towards target
    // World up, or north (-z) when looking (nearly) straight up or down, so a
    // nadir view has a well-defined up: north at the top of the frame.
    glm::vec3 up() const;
    glm::mat4 view() const;
    glm::mat4 projectionMatrix(float aspect) const;
    glm::mat4 viewProjection(float aspect) const { return projectionMatrix(aspect) * view(); }

    // The 6 frustum planes (a, b, c, d), normalised, with a*x + b*y + c*z + d >= 0
    // inside: left, right, bottom, top, near, far.
    std::array<glm::vec4, 6> frustumPlanes(float aspect) const;

    // Perspective: pixels per unit of screen-space error at unit distance,
    // viewportHeight / (2 tan(fovY / 2)). Orthographic: pixels per world unit,
    // viewportHeight / orthoHeight.
    float lambda(int viewportHeight) const;
    // The SBT's view: perspective uses the camera itself. Orthographic error
    // does not shrink with distance, so the SBT sees a virtual eye
    // kOrthoLodDistance times the terrain's scale behind the camera with lambda
    // scaled by that distance: lambda e / d stays the orthographic lambda e to
    // within the terrain's depth over that distance (0.1%), and tau still
    // means pixels.
    LodView lodView(int viewportHeight) const;
    static constexpr float kOrthoLodDistance = 1000.0f;
};

// Extent of the scene a path moves over: the terrain's bounding box, and
// optionally a closer outline of its surface for framing.
struct SceneBounds {
    glm::vec3 min{0.0f};
    glm::vec3 max{1.0f};
    // Points whose convex hull holds every real sample (see outlineOf); empty =
    // the box's corners. Framing fits these, so a terrain fills the frame
    // instead of its box.
    std::vector<glm::vec3> outline;
    glm::vec3 centre() const { return 0.5f * (min + max); }
    glm::vec3 size() const { return max - min; }
    std::array<glm::vec3, 8> corners() const;
    // outline, or the corners when there is none.
    std::vector<glm::vec3> framePoints() const;
};

// Unit vector towards compass `azimuthDeg` at `elevationDeg` above the horizon.
glm::vec3 compassDirection(float azimuthDeg, float elevationDeg);

// Sets near and far from the terrain's box seen from the camera, so that no
// camera distance empties the frame (near: just before the nearest corner,
// at most 1e-4 of far when the camera is inside the box).
void fitClipPlanes(Camera& camera, const SceneBounds& bounds);

// Share of the frame's half-size left free around a framed terrain.
inline constexpr float kFrameMargin = 0.05f;

struct FramingDesc {
    glm::vec3 target{0.0f};
    float azimuthDeg = 225.0f;   // compass bearing from the target to the camera
    float elevationDeg = 30.0f;  // above the horizon
    float fovYDegrees = 45.0f;
    Projection projection = Projection::Perspective;
    float aspect = 16.0f / 9.0f;  // frame width / height
    float distance = 0.0f;        // from the target; 0 = the smallest that frames the terrain
};

// A camera that sees every corner of `bounds` inside the frame with
// kFrameMargin to spare (orthographic: the view height fitted likewise), near
// and far fitted.
Camera framedCamera(const SceneBounds& bounds, const FramingDesc& desc);

// The default target: the centre of the terrain at a quarter of its relief.
glm::vec3 defaultTarget(const SceneBounds& bounds);

// The default view: from the south-west, 30 degrees up, framing the terrain.
Camera defaultCamera(const SceneBounds& bounds, float aspect, float fovYDegrees = 45.0f);

// `frames` cameras circling the target once (azimuth 225 degrees first,
// turning towards the west) at one distance that frames the terrain from every
// azimuth of the path.
std::vector<Camera> orbitPath(const SceneBounds& bounds, int frames, float aspect,
                              float fovYDegrees = 45.0f, float elevationDeg = 30.0f);

// The one distance of orbitPath: the largest any of its frames' azimuths
// needs to frame the terrain. Paths of more than kOrbitExactFrames frames
// take the largest over that many evenly spaced azimuths, 1e-4 larger (the
// distance is a maximum of smooth functions of the azimuth, so between
// samples it exceeds them by far less), so the cost stays bounded.
inline constexpr int kOrbitExactFrames = 4096;
float orbitDistance(const SceneBounds& bounds, int frames, float aspect, float fovYDegrees = 45.0f,
                    float elevationDeg = 30.0f);
// Frame k (0-based) of orbitPath at `distance` (orbitDistance's), alone.
Camera orbitCamera(const SceneBounds& bounds, int k, int frames, float distance, float aspect,
                   float fovYDegrees = 45.0f, float elevationDeg = 30.0f);

// `frames` cameras flying low across the terrain from the south edge towards
// the north, looking ahead and slightly down.
std::vector<Camera> flyoverPath(const SceneBounds& bounds, int frames, float fovYDegrees = 45.0f);
// Frame k (0-based) of flyoverPath, alone.
Camera flyoverCamera(const SceneBounds& bounds, int k, int frames, float fovYDegrees = 45.0f);

struct Keyframe {
    float time = 0.0f;  // seconds (any unit; only the ratios matter)
    glm::vec3 position{0.0f};
    glm::vec3 target{0.0f};
};

// `frames` cameras at evenly spaced times from the first keyframe's time to
// the last, positions and targets interpolated by Catmull-Rom splines through
// the keyframes (times strictly increasing; one keyframe gives a still camera).
std::vector<Camera> keyframePath(const SceneBounds& bounds, const std::vector<Keyframe>& keys,
                                 int frames, float fovYDegrees = 45.0f);
// Throws sierra::Error unless `keys` can make a path (at least one, times
// strictly increasing).
void checkKeyframes(const std::vector<Keyframe>& keys);
// Frame f (0-based) of keyframePath, alone, for checked keys: O(log keys).
Camera keyframeCamera(const SceneBounds& bounds, const std::vector<Keyframe>& keys, int f,
                      int frames, float fovYDegrees = 45.0f);

}  // namespace sierra::render
