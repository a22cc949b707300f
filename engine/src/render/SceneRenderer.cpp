#include <sierra/render/SceneRenderer.h>

#include <sierra/core/Log.h>
#include <sierra/render/CameraRecord.h>
#include <sierra/render/SceneView.h>
#include <sierra/render/TerrainGpu.h>
#include <sierra/scene/Terrain.h>

namespace sierra::render {

SceneRenderer::SceneRenderer(scene::Scene scene, std::shared_ptr<gpu::EglContext> context)
    : scene_(std::move(scene)),
      context_((context->makeCurrent(), std::move(context))),
      target_(FrameTarget::create({.width = scene_.output.width,
                                   .height = scene_.output.height,
                                   .samples = scene_.output.msaa,
                                   .offscreen = context_->width() != scene_.output.width ||
                                                context_->height() != scene_.output.height})) {}

SceneRenderer SceneRenderer::create(const scene::Scene& scene) {
    return create(scene, std::make_shared<gpu::EglContext>(gpu::EglContext::create(
                             {.width = scene.output.width, .height = scene.output.height})));
}

SceneRenderer SceneRenderer::create(const scene::Scene& scene,
                                    std::shared_ptr<gpu::EglContext> context,
                                    const terrain::Heightfield* grid) {
    SIERRA_CHECK(context, "SceneRenderer::create needs a context");
    SceneRenderer r(scene, std::move(context));
    // The context comes first: its texture limit bounds the grid the loader takes.
    std::string loaded;
    r.field_ =
        grid ? scene::prepareTerrain(*grid, scene.terrain, &loaded,
                                     scene::Padding::PowerOfTwoPlusOne, TerrainGpu::maxGridSide())
             : scene::loadTerrain(scene.terrain, &loaded, scene::Padding::PowerOfTwoPlusOne,
                                  TerrainGpu::maxGridSide());
    const float seaLevel = scene::resolveSeaLevel(scene.terrain, r.field_);
    r.terrain_ = std::make_unique<TerrainRenderer>(
        TerrainRenderer::create(sceneTerrainDesc(scene, r.field_, seaLevel)));
    r.description_ = "terrain: " + loaded;
    for (const std::string& line : {applySceneSurface(*r.terrain_, scene, r.field_, seaLevel),
                                    applySceneMesh(*r.terrain_, scene, r.field_)})
        if (!line.empty()) r.description_ += "; " + line;
    addOverlayPasses(*r.terrain_, scene);
    r.cameras_ = sceneCameras(scene, r.terrain_->bounds());
    r.draw_ = sceneDrawOptions(scene);
    return r;
}

gpu::Image SceneRenderer::frame(int k) {
    SIERRA_CHECK(k >= 0 && k < frameCount(), "frame ", k, " is outside the scene's 0..",
                 frameCount() - 1);
    context_->makeCurrent();
    target_.begin(TerrainRenderer::clearColour(draw_.lighting));
    stats_ = terrain_->draw(cameras_[size_t(k)], target_.width(), target_.height(), draw_);
    gpu::Image image = target_.read();
    terrain_->collectGpuTime(stats_);
    return image;
}

DepthImage SceneRenderer::depth(int k) {
    SIERRA_CHECK(k >= 0 && k < frameCount(), "frame ", k, " is outside the scene's 0..",
                 frameCount() - 1);
    context_->makeCurrent();
    return terrain_->renderDepth(cameras_[size_t(k)], target_.width(), target_.height(), draw_);
}

LabelImage SceneRenderer::labels(int k, bool cameraSpace) {
    SIERRA_CHECK(k >= 0 && k < frameCount(), "frame ", k, " is outside the scene's 0..",
                 frameCount() - 1);
    context_->makeCurrent();
    const Camera& camera = cameras_[size_t(k)];
    return terrain_->renderLabels(camera, target_.width(), target_.height(), draw_,
                                  cameraSpace ? openCvRotation(camera) : glm::mat3(1.0f));
}

scene::CameraRecord SceneRenderer::cameraRecord(int k) const {
    SIERRA_CHECK(k >= 0 && k < frameCount(), "frame ", k, " is outside the scene's 0..",
                 frameCount() - 1);
    return render::cameraRecord(cameras_[size_t(k)], target_.width(), target_.height(), field_);
}

void SceneRenderer::writeDataset(int k) {
    SIERRA_CHECK(k >= 0 && k < frameCount(), "frame ", k, " is outside the scene's 0..",
                 frameCount() - 1);
    if (!dataset_) {
        dataset_ = std::make_unique<DatasetWriter>(scene_, frameCount() > 1);
        dataset_->checkLocations();
    }
    context_->makeCurrent();
    dataset_->write(*terrain_, field_, k, cameras_[size_t(k)], target_.width(), target_.height(),
                    draw_);
}

void SceneRenderer::finishDataset() {
    if (dataset_) dataset_->finish();
}

}  // namespace sierra::render
