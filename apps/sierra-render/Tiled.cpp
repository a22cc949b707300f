// sierra-render on a tiled terrain (--heightmap T.sierra, from sierra-tile
// build): render::TiledTerrain draws each frame from the tiles that have
// arrived, never waiting for a read; a single frame waits for the tiles it
// asked for (up to --tile-wait seconds) so the picture is the finished one.
// Its surface is the in-memory renderer's ramp (or auto zones, or paper),
// under the scene's drapes, with contour edges and, near the camera, the
// curvature lines and hatches (facade/TiledOverlays.h); the options that
// need the whole grid in memory are refused by name.
#include "Tiled.h"

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/core/Log.h>
#include <sierra/core/Progress.h>
#include <sierra/core/Timer.h>
#include <sierra/facade/MapLayers.h>
#include <sierra/facade/SceneView.h>
#include <sierra/facade/TiledOverlays.h>
#include <sierra/gpu/EglContext.h>
#include <sierra/render/Capture.h>
#include <sierra/render/FrameTarget.h>
#include <sierra/render/TiledTerrain.h>
#include <sierra/render/Video.h>
#include <sierra/render/ZoneSurface.h>
#include <sierra/render/passes/ContourPass.h>
#include <sierra/sbt/TileFile.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>

namespace sierra::apps {
namespace {

// The first option of `s` that needs the grid in memory, or "".
std::string needsGrid(const scene::Scene& s) {
    const scene::Scene d;
    if (!s.zones.map.empty() && s.zones.map != "auto") return "--zones with a zone map";
    if (!s.layers.vectors.empty()) return "vector layers";
    if (!s.layers.labels.empty()) return "labels";
    if (!(s.layers.furniture == d.layers.furniture)) return "map furniture";
    if (s.lod.mode != scene::LodMode::Sbt) return "--lod full";
    if (!s.lod.mesh.empty()) return "--mesh";
    if (!s.output.depth.empty()) return "--depth";
    if (s.output.alpha) return "--alpha";
    if (scene::isVideoOutput(s.output.frame)) return "video output";
    if (s.camera.projection != scene::Projection::Perspective) return "--projection orthographic";
    if (s.lighting.sunTime) return "--sun-time";
    // The ramp's options and the curvature overlays work; the debug views
    // of the mesh do not.
    const scene::StyleDesc& style = s.style;
    if (style.wireframe || style.points || !style.polygons) return "--display";
    if (style.colourBy != d.style.colourBy) return "--colour-by";
    return "";
}

// Where the file's real samples lie, for drapes.
facade::TerrainPlacement tiledPlacement(const sbt::TileFileInfo& info) {
    facade::TerrainPlacement p;
    p.width = int(info.width);
    p.height = int(info.height);
    if (const auto& g = info.georeference)
        p.placement = terrain::GridPlacement{g->geoTransform, g->crsWkt, p.width, p.height};
    return p;
}

// Auto zones of the terrain's overview (at most kZoneMaxSide a side): the
// zone map, its borderlines and distance field are the in-memory renderer's
// at the overview's resolution, the tiles keep their size in grid samples.
constexpr int kZoneMaxSide = 2049;

std::unique_ptr<render::Surface> autoZoneSurface(const render::TiledTerrain& terrain,
                                                 const scene::Scene& s) {
    int stride = 1;
    terrain::Heightfield overview = sbt::readOverview(terrain.file(), kZoneMaxSide, 0, &stride);
    // A tiled terrain has no water: the sea lies below its lowest height.
    render::ZoneSurfaceDesc desc = facade::zoneSurfaceDesc(s, NAN, overview);
    desc.samplesPerPixel = stride;
    render::ZoneSurfaceInfo info;
    auto surface = render::makeZoneSurface(overview, desc, &info);
    log::info("zones: auto on an overview of ", info.mapWidth, "x", info.mapHeight,
              " samples (stride ", stride, "), ", info.zoneCount, " surface types, ",
              info.borderEdges, " borderline edges, band ", info.band, " px, built in ",
              fixed(info.buildMs, 1), " ms");
    return surface;
}

// The scene's surface on the tiled terrain: paper, auto zones or the ramp
// (its style's tree and snow lines or .cpt), under the scene's drapes.
void applySurface(render::TiledTerrain& terrain, const scene::Scene& s) {
    const render::RampSurfaceDesc ramp{.metric = terrain.info().metres,
                                       .treeLine = s.style.treeLine,
                                       .snowLine = s.style.snowLine,
                                       .cpt = s.style.cpt};
    // Line and hatch styles without shading draw on paper, as in memory.
    std::unique_ptr<render::Surface> surface =
        !s.style.overlay.layers.shaded ? render::makePaperSurface()
        : s.zones.map == "auto"        ? autoZoneSurface(terrain, s)
                                       : render::makeRampSurface(terrain.surfaceRamp(ramp));
    if (!s.layers.drapes.empty()) {
        std::vector<std::string> notes;
        surface = facade::drapeSurface(s, tiledPlacement(terrain.info()), std::move(surface), {},
                                       nullptr, notes);
        std::string description;  // as the in-memory renderer's: the notes on one line
        for (const std::string& line : notes)
            description += (description.empty() ? "" : "; ") + line;
        log::info(description);
    }
    terrain.setSurface(std::move(surface));
}

// A still's wait for its tiles: refinement, streaming and uploads without
// drawing, until no tile is coarse, nothing more arrives, the coarse count
// stops falling (a view wanting more than the GPU cache holds), or
// `seconds` pass (the relief's first computation not counted). Returns the
// relief's milliseconds.
double waitForStill(render::TiledTerrain& terrain, const render::Camera& camera, int width,
                    int height, render::TiledFrameOptions options, double seconds) {
    options.uploadsPerFrame = 1 << 30;
    Stopwatch waited;
    double reliefMs = 0.0;
    int64_t lastRead = -1;
    int fewest = INT_MAX, sinceFewer = 0;
    for (int pass = 0;; ++pass) {
        const render::TiledFrameStats stats = terrain.prepare(camera, width, height, options);
        reliefMs += stats.reliefMs;
        const bool stalled =
            pass > 0 && stats.uploadedTiles == 0 && stats.cache.tilesRead == lastRead;
        lastRead = stats.cache.tilesRead;
        sinceFewer = stats.coarseTiles < fewest ? 0 : sinceFewer + 1;
        fewest = std::min(fewest, stats.coarseTiles);
        if (stats.coarseTiles == 0 || stalled || sinceFewer >= 8 ||
            waited.ms() - reliefMs > seconds * 1000.0)
            return reliefMs;
        terrain.waitForTiles();
    }
}

}  // namespace

bool isTiledTerrain(const scene::Scene& s) {
    return lowerExtension(s.terrain.heightmap) == ".sierra";
}

int runTiled(const scene::Scene& s, const TiledRenderOptions& o) {
    if (const std::string option = needsGrid(s); !option.empty())
        throw Error(
            msg(s.terrain.heightmap, " is a tiled terrain: ", option,
                " needs a heightmap in memory (give the grid itself, not its .sierra file)"));
    if (s.terrain.verticalScale > 0.0f || s.terrain.spacing > 0.0f)
        throw Error(msg(s.terrain.heightmap,
                        " is a tiled terrain: its spacing and vertical scale were fixed when it "
                        "was built (sierra-tile build --vertical-scale); --vertical-scale and "
                        "--spacing do not apply"));
    const int width = s.output.width, height = s.output.height;
    const int frames = s.path.frames;
    const int first = s.path.range ? s.path.range->first : 0;
    const int last = s.path.range ? s.path.range->last : frames - 1;
    ensureWritableLocation(s.output.frame);
    Stopwatch total;
    auto context = gpu::EglContext::create({.width = width, .height = height});
    log::info("OpenGL ", context.version(), " on ", context.renderer(), " (", context.platform(),
              ")");
    auto terrain = render::TiledTerrain::open(
        {.path = s.terrain.heightmap, .memoryBudget = o.memoryBudget, .loaderThreads = o.loaders});
    applySurface(*terrain, s);
    const render::SceneBounds bounds = terrain->bounds();
    render::FrameTarget target = render::FrameTarget::create(
        {.width = width, .height = height, .samples = s.output.msaa >= 2 ? s.output.msaa : 0});
    render::TiledFrameOptions options;
    options.tau = s.lod.tau;
    options.cull = s.lod.cull;
    const scene::Vec3 sun =
        scene::directionFromAngles(s.lighting.sunAzimuth, s.lighting.sunAltitude);
    options.sunDirection = {sun.x, sun.y, sun.z};
    options.sky = {s.lighting.sky.r, s.lighting.sky.g, s.lighting.sky.b};
    options.fogDensity = s.lighting.fog ? *s.lighting.fog : -1.0f;
    options.ambient = s.lighting.ambient;
    // Shadows and sky light from the terrain's overview, once (the first frame).
    options.shadows = s.lighting.shadows;
    options.skyLight = s.lighting.skyLight;
    options.sunSize = s.lighting.sunSize;
    options.horizonRadius = s.lighting.horizonRadius;
    options.frameSeconds = 1.0f / float(s.output.fps);
    if (s.style.overlay.layers.contours) {
        const render::ContourPassDesc contours;  // the in-memory renderer's
        options.contourWidth = contours.width;
        options.contourColour = contours.colour;
    }
    const auto overlays = facade::TiledOverlays::create(terrain->file(), s);
    const bool still = first == last;
    for (int k = first; k <= last; ++k) {
        const render::Camera camera = facade::sceneCamera(s, bounds, k);
        const double waitReliefMs =
            still ? waitForStill(*terrain, camera, width, height, options, o.tileWaitSeconds) : 0.0;
        target.begin({options.sky, 1.0f});
        const render::TiledFrameStats stats = terrain->draw(camera, width, height, options);
        if (overlays) overlays->draw(camera, width, height, options.tau);
        const double reliefMs = waitReliefMs + stats.reliefMs;
        const std::string path = sequenceFrame(s, k);
        render::writePng(path, target.read());
        log::info("frame ", k, ": ", stats.triangles, " triangles, refine + strip ",
                  fixed(stats.refineMs), " ms, relief ", fixed(reliefMs, 1), " ms, ",
                  stats.coarseTiles, " tiles drawn coarse, ", stats.uploadedTiles,
                  " uploaded; tiles ", stats.cache.residentTiles, " in memory (",
                  fixed(double(stats.cache.residentBytes) / 1048576.0, 1), " MiB), ",
                  stats.gpuTiles, " on the GPU; wrote ", path);
    }
    log::info("done in ", fixed(total.ms(), 1), " ms");
    return 0;
}

}  // namespace sierra::apps
