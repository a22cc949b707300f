#pragma once
// How a scene (the GL-free description of a render job, sierra/scene) becomes
// what the renderer draws: the cameras of its frames, the draw options and
// lighting.

#include <sierra/facade/MapLayers.h>
#include <sierra/render/Camera.h>
#include <sierra/render/Capture.h>
#include <sierra/render/TerrainRenderer.h>
#include <sierra/render/ZoneSurface.h>
#include <sierra/scene/Scene.h>

#include <optional>
#include <string>
#include <vector>

namespace sierra::facade {

// The cameras of the scene's sequence (path.frames of them; the range, if
// any, is the caller's to pick), for a terrain with `bounds`, one frame at a
// time:
//   - path none: the scene's camera (position, or azimuth / elevation /
//     distance around the target; absent values from the default camera,
//     which frames the whole terrain for the frame's aspect ratio);
//   - orbit: a full turn around the target at the camera's elevation;
//   - flyover: low across the terrain from south to north;
//   - keyframes: the scene's keyframes, interpolated.
// Construction checks the scene's camera and does the work shared by every
// frame (an orbit's distance: at most kOrbitExactFrames framings); at(k) is
// then O(1) (keyframes: O(log keyframes)), so a sequence of any length starts
// at once.
class SceneCameraPath {
  public:
    SceneCameraPath(const scene::Scene& scene, const render::SceneBounds& bounds);
    int frames() const { return frames_; }
    // Frame k, 0 <= k < frames(); throws sierra::Error for a camera whose
    // position is its target.
    render::Camera at(int k) const;

  private:
    scene::PathType type_;
    int frames_;
    render::SceneBounds bounds_;
    float aspect_, fov_, elevation_;
    render::Projection projection_;
    glm::vec3 target_;
    bool moveTarget_ = false;        // orbit: around the scene's target, not the default
    std::optional<float> distance_;  // orbit: the scene's distance
    float orbitDistance_ = 0.0f;     // orbit: the framing distance of the whole path
    float orthoHeight_ = 0.0f;       // orbit, orthographic: the framed view height
    std::vector<render::Keyframe> keys_;
    render::Camera still_;  // path none
};

// Frame k's camera alone (a SceneCameraPath made for it).
render::Camera sceneCamera(const scene::Scene& scene, const render::SceneBounds& bounds, int k);
// Every camera of the sequence, SceneCameraPath's for each frame.
std::vector<render::Camera> sceneCameras(const scene::Scene& scene,
                                         const render::SceneBounds& bounds);

// The cameras of a debug snapshot, whose frame is `frameWidth` pixels wide
// beside the panel column: sceneCameras for that narrower frame, so a camera
// framed automatically keeps the whole terrain in view; a fixed one is unchanged.
std::vector<render::Camera> snapshotCameras(const scene::Scene& scene,
                                            const render::SceneBounds& bounds, int frameWidth);
SceneCameraPath snapshotCameraPath(const scene::Scene& scene, const render::SceneBounds& bounds,
                                   int frameWidth);

// The draw options of the scene; lighting.sunDirection is the scene's fixed
// sun (lighting.sun_azimuth / sun_altitude): with a sun time, set each
// frame's from sceneSunDirections.
render::DrawOptions sceneDrawOptions(const scene::Scene& scene);

// The direction towards the sun in frame k of the scene's sequence
// (scene::sceneSun) over `field` as loaded: O(1). Throws sierra::Error as
// sceneSun does.
glm::vec3 sceneSunDirection(const scene::Scene& scene, const terrain::Heightfield& field, int k);
// Says where the sun stands (with a time: when and from where, for the first
// and the last frame of a moving sun) and warns when a frame's sun is below
// the horizon (that frame is then lit by the sky alone). A moving sun is
// looked at in every frame up to kSunSurveyFrames frames, in that many evenly
// spaced frames beyond. Throws sierra::Error as sceneSun does.
inline constexpr int kSunSurveyFrames = 100000;
void describeSceneSun(const scene::Scene& scene, const terrain::Heightfield& field);
// The direction towards the sun in every frame of the scene's sequence
// (path.frames of them), after describeSceneSun.
std::vector<glm::vec3> sceneSunDirections(const scene::Scene& scene,
                                          const terrain::Heightfield& field);

// The renderer's description of the scene's terrain: `field` as loaded by
// scene::loadTerrain, the sea level from scene::resolveSeaLevel, metric
// colouring when its heights are metres.
render::TerrainDesc sceneTerrainDesc(const scene::Scene& scene, const terrain::Heightfield& field,
                                     float seaLevel);
render::Lighting sceneLighting(const scene::LightingDesc& lighting, bool transparent);

glm::vec3 toGlm(const scene::Vec3& v);

// The encoding of a scene's frames (output.png_compression, jpeg_quality, alpha).
render::ImageEncoding frameEncoding(const scene::OutputDesc& output);
render::PngCompression pngCompression(scene::PngCompression compression);

// The scene's zone options (--zones and the rest) as a zone surface's, with
// the palette read; `field` and `seaLevel` for the auto zones' sea level.
// Throws sierra::Error for a palette that cannot be read.
render::ZoneSurfaceDesc zoneSurfaceDesc(const scene::Scene& scene, float seaLevel,
                                        const terrain::Heightfield& field);

// Gives the renderer the scene's surface when it is not the default colour
// ramp (zone tiles, paper), with the scene's layers over it (applyMapLayers:
// drapes, vector lines and fills; their labels and furniture go to `layers`
// when given), and returns one line saying what was built ("" for none).
// `field` and `seaLevel` as for sceneTerrainDesc.
std::string applySceneSurface(render::TerrainRenderer& renderer, const scene::Scene& scene,
                              const terrain::Heightfield& field, float seaLevel,
                              MapLayers* layers = nullptr);
// Gives the renderer the scene's TIN (lod.mesh, an OBJ from sierra-tin) and
// returns one line saying what was loaded ("" for none; sceneDrawOptions then
// picks Lod::Mesh). Every OBJ vertex must be a real sample of `field` (x =
// i * spacing, z = j * spacing, within 1e-3 of a sample) with its height
// (within 1e-3 of the height range): a mesh made for another terrain is
// refused with sierra::Error naming the file.
std::string applySceneMesh(render::TerrainRenderer& renderer, const scene::Scene& scene,
                           const terrain::Heightfield& field);

// What addOverlayPasses added.
struct OverlayInfo {
    size_t lines = 0;     // polylines traced
    size_t segments = 0;  // their segments
    float scale = 1.0f;   // the curvature scale drawn (the automatic one with "auto")
};

// Adds the scene's overlay passes (style.overlay: hatches, then lines, then
// contour edges, over the terrain) to `renderer`: the curvature field of its
// drawn surface (TerrainGpu::surface: water flat at sea level, so no stroke
// or line stands for ground under water, and the coast is a crease) computed
// on the GPU once (twice with an automatic scale, StyleParams::autoScale: the
// second at the scale the first asks for), the lines traced once from it.
// Nothing when the style has no overlay layer.
OverlayInfo addOverlayPasses(render::TerrainRenderer& renderer, const scene::Scene& scene);

}  // namespace sierra::facade
