#pragma once
// One object that turns a Scene (sierra/scene) into what a program needs:
// frames, depth images and their timings. It owns the whole set-up every
// renderer of a scene does (the EGL context, the terrain loaded and padded,
// the terrain's GPU data, its surface, TIN and overlays, the frame target and
// the scene's cameras), so an embedding program writes none of it:
//
//   sierra::scene::Scene scene;
//   scene.terrain.heightmap = "dem.tif";
//   auto renderer = sierra::render::SceneRenderer::create(scene);
//   sierra::render::writePng("frame.png", renderer.frame());
//
// Each call makes the renderer's context current on the calling thread, so a
// renderer can be used from any thread, one call at a time (the caller keeps
// it to one: nothing here locks).

#include <sierra/gpu/EglContext.h>
#include <sierra/gpu/ReadBack.h>
#include <sierra/render/Camera.h>
#include <sierra/render/Dataset.h>
#include <sierra/render/FrameTarget.h>
#include <sierra/render/TerrainRenderer.h>
#include <sierra/scene/Scene.h>
#include <sierra/terrain/Heightfield.h>

#include <memory>
#include <string>
#include <vector>

namespace sierra::render {

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
                                const terrain::Heightfield* grid = nullptr);

    // Frame k of the scene's sequence (0 .. frameCount() - 1), RGBA8, top row
    // first. Blocks until the frame is read back.
    gpu::Image frame(int k = 0);
    // Linear eye-space depth of frame k (world units, NaN where no terrain).
    DepthImage depth(int k = 0);
    // The dataset labels of frame k (LabelPass): unit normals in world axes,
    // or with `cameraSpace` in the camera's OpenCV axes (x right, y down, z
    // forward: R times the world normal), the terrain mask, and zone ids
    // when the scene has zones. One pass renders all three.
    LabelImage labels(int k = 0, bool cameraSpace = false);
    // Frame k's camera for dataset outputs: K, R|t, GL matrices, georeference.
    scene::CameraRecord cameraRecord(int k = 0) const;
    // Writes every dataset output the scene asks for of frame k
    // (scene.output: depth, normals, zone ids, mask, camera JSON; DatasetWriter),
    // and finishDataset() the transforms.json of the frames written.
    void writeDataset(int k);
    void finishDataset();

    int frameCount() const { return int(cameras_.size()); }
    const Camera& camera(int k) const { return cameras_.at(size_t(k)); }
    // The statistics of the last frame drawn (triangles, stage times).
    const DrawStats& lastStats() const { return stats_; }
    // One line on what was loaded and built (terrain, surface, mesh).
    const std::string& description() const { return description_; }

    const scene::Scene& scene() const { return scene_; }
    const terrain::Heightfield& field() const { return field_; }
    TerrainRenderer& terrain() { return *terrain_; }
    gpu::EglContext& context() { return *context_; }
    const DrawOptions& drawOptions() const { return draw_; }
    FrameTarget& target() { return target_; }

  private:
    SceneRenderer(scene::Scene scene, std::shared_ptr<gpu::EglContext> context);

    scene::Scene scene_;
    std::shared_ptr<gpu::EglContext> context_;
    terrain::Heightfield field_;
    std::unique_ptr<TerrainRenderer> terrain_;
    FrameTarget target_;
    std::vector<Camera> cameras_;
    DrawOptions draw_;
    DrawStats stats_;
    std::string description_;
    std::unique_ptr<DatasetWriter> dataset_;  // made by the first writeDataset()
};

}  // namespace sierra::render
