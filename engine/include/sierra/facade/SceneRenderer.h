#pragma once
// One object that turns a Scene (sierra/scene) into what a program needs:
// frames, depth images and their timings. It owns the whole set-up every
// renderer of a scene does (the EGL context, the terrain loaded and padded,
// the terrain's GPU data, its surface, TIN and overlays, the frame target and
// the scene's cameras), so an embedding program writes none of it:
//
//   sierra::scene::Scene scene;
//   scene.terrain.heightmap = "dem.tif";
//   auto renderer = sierra::facade::SceneRenderer::create(scene);
//   sierra::render::writePng("frame.png", renderer.frame());
//
// Each call makes the renderer's context current on the calling thread, so a
// renderer can be used from any thread, one call at a time (the caller keeps
// it to one: nothing here locks).

#include <sierra/facade/Dataset.h>
#include <sierra/facade/SceneView.h>
#include <sierra/gpu/EglContext.h>
#include <sierra/gpu/ReadBack.h>
#include <sierra/render/Camera.h>
#include <sierra/render/FrameTarget.h>
#include <sierra/render/TerrainRenderer.h>
#include <sierra/scene/Scene.h>
#include <sierra/terrain/Heightfield.h>

#include <functional>
#include <memory>
#include <optional>
#include <string>

namespace sierra::facade {

// What create() says as it works, for programs that log their set-up.
struct SetupHooks {
    // Called with each line on what was loaded and built, in order:
    // "terrain: ...", the surface and the TIN when the scene has them, then
    // "terrain on the GPU: ...". Nothing is called when it is empty.
    std::function<void(const std::string&)> report;
    // Says where the sun stands (describeSceneSun) once the terrain is loaded
    // and before its GPU data is built, so a sun time without a place fails
    // before that work.
    bool describeSun = false;
};

class SceneRenderer {
  public:
    // Creates the context (on the device SIERRA_EGL_DEVICE picks) and loads
    // and uploads the scene's terrain. Throws sierra::Error for a bad terrain,
    // surface or mesh, and when no GL 4.5 context can be made.
    static SceneRenderer create(const scene::Scene& scene);
    // The same on a context the caller shares between renderers (frames larger
    // than its pbuffer are drawn into an offscreen target), and, when `grid` is
    // given, for that grid instead of the scene's terrain source: heights as
    // read, with their spacing and no-data mask, prepared as
    // scene::prepareTerrain does (scene.terrain.heightmap names it).
    static SceneRenderer create(const scene::Scene& scene, std::shared_ptr<gpu::EglContext> context,
                                const terrain::Heightfield* grid = nullptr,
                                const SetupHooks& hooks = {});

    // Frame k of the scene's sequence (0 .. frameCount() - 1), RGBA8, top row
    // first. Blocks until the frame is read back.
    gpu::Image frame(int k = 0);
    // Linear eye-space depth of frame k (world units, NaN where no terrain).
    render::DepthImage depth(int k = 0);
    // The dataset labels of frame k (render::LabelPass): unit normals in
    // world axes, or with `cameraSpace` in the camera's OpenCV axes (x right,
    // y down, z forward: R times the world normal), the terrain mask, and
    // zone ids when the scene has zones. One pass renders all three.
    render::LabelImage labels(int k = 0, bool cameraSpace = false);
    // Frame k's camera for dataset outputs: K, R|t, GL matrices, georeference.
    scene::CameraRecord cameraRecord(int k = 0) const;
    // Writes every dataset output the scene asks for of frame k
    // (scene.output: depth, normals, zone ids, mask, camera JSON;
    // DatasetWriter), and finishDataset() the transforms.json of the frames
    // written.
    void writeDataset(int k);
    void finishDataset();

    // Frame k drawn into the frame target and resolved, its read-back started
    // through pixel-buffer objects (frame k is copied while frame k + 1 is
    // drawn). Returns true with the frame submitted before it in `ready`;
    // lastStats() are frame k's. Frames come back in the order submitted.
    bool submitFrame(int k, gpu::Image& ready);
    // The last frame submitted, if one is still in flight (end of a sequence).
    bool finishFrames(gpu::Image& ready);
    // Binds the frame target, clears it and draws `camera` with `options`
    // (not resolved: target().resolve() or read() follow). The renderer's
    // context must be current on this thread (create, frame and depth make
    // it so).
    render::DrawStats drawFrame(const render::Camera& camera, const render::DrawOptions& options);

    int frameCount() const { return cameras_->frames(); }
    // Frame k's camera, O(1) (SceneCameraPath): 0 <= k < frameCount().
    render::Camera camera(int k) const;
    // The draw options of frame k: drawOptions() with that frame's sun.
    render::DrawOptions drawOptions(int k) const;
    // The statistics of the last frame drawn by frame() or submitFrame()
    // (triangles, stage times).
    const render::DrawStats& lastStats() const { return stats_; }
    // One line on what was loaded and built (terrain, surface, mesh).
    const std::string& description() const { return description_; }
    // What the terrain loader said it loaded (the first part of description()).
    const std::string& terrainDescription() const { return loaded_; }
    // What addOverlayPasses added for the scene's style.
    const OverlayInfo& overlays() const { return overlays_; }

    const scene::Scene& scene() const { return scene_; }
    const terrain::Heightfield& field() const { return field_; }
    render::TerrainRenderer& terrain() { return *terrain_; }
    gpu::EglContext& context() { return *context_; }
    const render::DrawOptions& drawOptions() const { return draw_; }
    render::FrameTarget& target() { return target_; }

  private:
    SceneRenderer(scene::Scene scene, std::shared_ptr<gpu::EglContext> context);

    scene::Scene scene_;
    std::shared_ptr<gpu::EglContext> context_;
    terrain::Heightfield field_;
    std::unique_ptr<render::TerrainRenderer> terrain_;
    render::FrameTarget target_;
    std::optional<SceneCameraPath> cameras_;
    render::DrawOptions draw_;
    render::DrawStats stats_;
    std::string description_, loaded_;
    OverlayInfo overlays_;
    MapLayers layers_;                                      // labels and furniture over each frame
    std::unique_ptr<render::AnnotationOverlay> furniture_;  // made by the first frame drawing them
    std::unique_ptr<gpu::PixelReader> reader_;              // made by the first submitFrame
    std::unique_ptr<DatasetWriter> dataset_;                // made by the first writeDataset
};

}  // namespace sierra::facade
