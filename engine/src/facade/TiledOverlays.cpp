#include <sierra/facade/TiledOverlays.h>

#include <sierra/core/Log.h>
#include <sierra/core/Progress.h>
#include <sierra/core/Timer.h>
#include <sierra/terrain/Padding.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace sierra::facade {

SampleWindow nearWindow(const sbt::TileFileInfo& info, const render::Camera& camera, int maxSide) {
    SampleWindow w;
    w.width = int(std::min<int64_t>(maxSide, info.width));
    w.height = int(std::min<int64_t>(maxSide, info.height));
    const glm::vec2 spacing{info.spacingX, info.spacingZ};
    const glm::vec2 eye{camera.position.x, camera.position.z};
    const glm::vec2 towards = glm::vec2(camera.target.x, camera.target.z) - eye;
    const float reach = 0.5f * float(maxSide - 1) * std::min(spacing.x, spacing.y);
    const float along = glm::length(towards);
    const glm::vec2 focus = along > reach ? eye + towards * (reach / along) : eye + towards;
    const glm::vec2 centre = focus / spacing;  // samples
    auto origin = [](float c, int side, int64_t total) {
        const double start = std::floor(double(c) - 0.5 * double(side - 1) + 0.5);
        return std::clamp<int64_t>(int64_t(std::clamp(start, -1e18, 1e18)), 0, total - side);
    };
    w.i0 = origin(centre.x, w.width, info.width);
    w.j0 = origin(centre.y, w.height, info.height);
    return w;
}

std::unique_ptr<TiledOverlays> TiledOverlays::create(const sbt::TileFile& file,
                                                     const scene::Scene& scene, int maxSide) {
    const analysis::StyleLayers& layers = scene.style.overlay.layers;
    if (!layers.lines && !layers.hatch) return nullptr;
    SIERRA_CHECK(maxSide >= 3, "the overlays' window needs at least 3 samples a side, got ",
                 maxSide);
    return std::unique_ptr<TiledOverlays>(new TiledOverlays(file, scene, maxSide));
}

TiledOverlays::TiledOverlays(const sbt::TileFile& file, const scene::Scene& scene, int maxSide)
    : file_(file), scene_(scene), maxSide_(maxSide) {
    // The window draws the overlays alone: contour edges are the tiled
    // terrain's own.
    scene_.style.overlay.layers.contours = false;
}

TiledOverlays::~TiledOverlays() = default;

void TiledOverlays::readWindow(const SampleWindow& w) {
    Stopwatch watch;
    renderer_.reset();  // it holds field_: the old window goes before the new is read
    field_ = terrain::padToPowerOfTwoPlusOne(
        sbt::readWindow(file_, w.i0, w.j0, w.width, w.height, scene_.lod.threads));
    renderer_ = std::make_unique<render::TerrainRenderer>(
        render::TerrainRenderer::create({.field = &field_, .threads = scene_.lod.threads}));
    info_ = addOverlayPasses(*renderer_, scene_);
    window_ = w;
    ++windowsRead_;
    log::info("overlays: near the camera, samples ", w.i0, "..", w.i0 + w.width - 1, " x ", w.j0,
              "..", w.j0 + w.height - 1, " of the tiled terrain, read and built in ",
              fixed(watch.ms(), 1), " ms");
}

void TiledOverlays::draw(const render::Camera& camera, int width, int height, float tau) {
    const SampleWindow wanted = nearWindow(file_.info(), camera, maxSide_);
    const bool moved = std::llabs(wanted.i0 - window_.i0) * 4 >= window_.width ||
                       std::llabs(wanted.j0 - window_.j0) * 4 >= window_.height;
    if (!renderer_ || moved) readWindow(wanted);
    // The same view in the window's coordinates: its sample (0, 0) is the
    // terrain's (i0, j0).
    const sbt::TileFileInfo& info = file_.info();
    const glm::vec3 offset{float(double(window_.i0) * info.spacingX), 0.0f,
                           float(double(window_.j0) * info.spacingZ)};
    render::Camera local = camera;
    local.position -= offset;
    local.target -= offset;
    render::DrawOptions options;
    options.tau = tau;
    options.geomorph = false;  // the tiled mesh does not morph
    options.polygons = false;  // the tiled terrain is drawn already
    renderer_->draw(local, width, height, options);
}

}  // namespace sierra::facade
