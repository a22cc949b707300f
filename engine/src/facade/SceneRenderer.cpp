#include <sierra/facade/SceneRenderer.h>

#include <sierra/core/Log.h>
#include <sierra/facade/CameraRecord.h>
#include <sierra/facade/SceneView.h>
#include <sierra/render/TerrainGpu.h>
#include <sierra/scene/Terrain.h>

namespace sierra::facade {

using namespace sierra::render;

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
                                    const terrain::Heightfield* grid, const SetupHooks& hooks) {
    SIERRA_CHECK(context, "SceneRenderer::create needs a context");
    auto report = [&](const std::string& line) {
        if (hooks.report && !line.empty()) hooks.report(line);
    };
    SceneRenderer r(scene, std::move(context));
    // The context comes first: its texture limit bounds the grid the loader takes.
    r.field_ =
        grid ? scene::prepareTerrain(*grid, scene.terrain, &r.loaded_,
                                     scene::Padding::PowerOfTwoPlusOne, TerrainGpu::maxGridSide())
             : scene::loadTerrain(scene.terrain, &r.loaded_, scene::Padding::PowerOfTwoPlusOne,
                                  TerrainGpu::maxGridSide());
    report("terrain: " + r.loaded_);
    if (hooks.describeSun) describeSceneSun(scene, r.field_);
    const float seaLevel = scene::resolveSeaLevel(scene.terrain, r.field_);
    r.terrain_ = std::make_unique<TerrainRenderer>(
        TerrainRenderer::create(sceneTerrainDesc(scene, r.field_, seaLevel)));
    r.description_ = "terrain: " + r.loaded_;
    for (const std::string& line :
         {applySceneSurface(*r.terrain_, scene, r.field_, seaLevel, &r.layers_),
          applySceneMesh(*r.terrain_, scene, r.field_)}) {
        report(line);
        if (!line.empty()) r.description_ += "; " + line;
    }
    report("terrain on the GPU: " + r.terrain_->summary());
    r.overlays_ = addOverlayPasses(*r.terrain_, scene);
    r.cameras_.emplace(scene, r.terrain_->bounds());
    r.draw_ = sceneDrawOptions(scene);
    return r;
}

Camera SceneRenderer::camera(int k) const {
    SIERRA_CHECK(k >= 0 && k < frameCount(), "frame ", k, " is outside the scene's 0..",
                 frameCount() - 1);
    return cameras_->at(k);
}

DrawOptions SceneRenderer::drawOptions(int k) const {
    DrawOptions options = draw_;
    options.lighting.sunDirection = sceneSunDirection(scene_, field_, k);
    return options;
}

DrawStats SceneRenderer::drawFrame(const Camera& camera, const DrawOptions& options) {
    const int width = target_.width(), height = target_.height();
    // Labels hide behind terrain by its depth, drawn first into a target of its own.
    std::optional<DepthImage> depth;
    if (layers_.drawsOver() && layers_.labelsNeedDepth)
        depth = terrain_->renderDepth(camera, width, height, options);
    target_.begin(TerrainRenderer::clearColour(options.lighting));
    DrawStats stats = terrain_->draw(camera, width, height, options);
    if (layers_.drawsOver()) {
        if (!furniture_)
            furniture_ = std::make_unique<AnnotationOverlay>(layers_.annotations.textPixels);
        drawMapLayers(*furniture_, layers_, camera, width, height, depth ? &*depth : nullptr);
    }
    return stats;
}

gpu::Image SceneRenderer::frame(int k) {
    const Camera view = camera(k);
    context_->makeCurrent();
    stats_ = drawFrame(view, drawOptions(k));
    gpu::Image image = target_.read();
    terrain_->collectGpuTime(stats_);
    return image;
}

bool SceneRenderer::submitFrame(int k, gpu::Image& ready) {
    const Camera view = camera(k);
    context_->makeCurrent();
    if (!reader_) reader_ = std::make_unique<gpu::PixelReader>(target_.width(), target_.height());
    stats_ = drawFrame(view, drawOptions(k));
    target_.resolve();
    const bool done = reader_->start(ready);
    terrain_->collectGpuTime(stats_);
    return done;
}

bool SceneRenderer::finishFrames(gpu::Image& ready) {
    if (!reader_) return false;
    context_->makeCurrent();
    return reader_->finish(ready);
}

DepthImage SceneRenderer::depth(int k) {
    const Camera view = camera(k);
    context_->makeCurrent();
    return terrain_->renderDepth(view, target_.width(), target_.height(), drawOptions(k));
}

render::LabelImage SceneRenderer::labels(int k, bool cameraSpace) {
    const Camera view = camera(k);
    context_->makeCurrent();
    return terrain_->renderLabels(view, target_.width(), target_.height(), drawOptions(k),
                                  cameraSpace ? openCvRotation(view) : glm::mat3(1.0f));
}

scene::CameraRecord SceneRenderer::cameraRecord(int k) const {
    return facade::cameraRecord(camera(k), target_.width(), target_.height(), field_);
}

void SceneRenderer::writeDataset(int k) {
    const Camera view = camera(k);
    if (!dataset_) {
        dataset_ = std::make_unique<DatasetWriter>(scene_, frameCount() > 1);
        dataset_->checkLocations();
    }
    context_->makeCurrent();
    dataset_->write(*terrain_, field_, k, view, target_.width(), target_.height(), drawOptions(k));
}

void SceneRenderer::finishDataset() {
    if (dataset_) dataset_->finish();
}

}  // namespace sierra::facade
