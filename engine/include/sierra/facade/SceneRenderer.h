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

#include <sierra/gpu/EglContext.h>
#include <sierra/gpu/ReadBack.h>
#include <sierra/render/Camera.h>
#include <sierra/render/FrameTarget.h>
#include <sierra/render/TerrainRenderer.h>
#include <sierra/scene/Scene.h>
#include <sierra/terrain/Heightfield.h>

#include <memory>
#include <string>
#include <vector>

namespace sierra::facade {

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
    render::DepthImage depth(int k = 0);

    int frameCount() const { return int(cameras_.size()); }
    const render::Camera& camera(int k) const { return cameras_.at(size_t(k)); }
    // The statistics of the last frame drawn (triangles, stage times).
    const render::DrawStats& lastStats() const { return stats_; }
    // One line on what was loaded and built (terrain, surface, mesh).
    const std::string& description() const { return description_; }

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
    std::vector<render::Camera> cameras_;
    render::DrawOptions draw_;
    render::DrawStats stats_;
    std::string description_;
};

}  // namespace sierra::facade
