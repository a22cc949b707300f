#include <sierra/facade/SceneView.h>

#include <sierra/core/Error.h>
#include <sierra/core/Log.h>
#include <sierra/core/Progress.h>
#include <sierra/render/CurvatureGpu.h>
#include <sierra/render/ZoneSurface.h>
#include <sierra/render/passes/ContourPass.h>
#include <sierra/render/passes/HatchPass.h>
#include <sierra/render/passes/LinePass.h>
#include <sierra/scene/Assets.h>
#include <sierra/scene/PaletteJson.h>
#include <sierra/scene/Terrain.h>
#include <sierra/terrain/SunPosition.h>
#include <sierra/tin/Export.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

namespace sierra::facade {

using namespace sierra::render;

render::PngCompression pngCompression(scene::PngCompression compression) {
    switch (compression) {
        case scene::PngCompression::Default:
            return render::PngCompression::Default;
        case scene::PngCompression::Best:
            return render::PngCompression::Best;
        case scene::PngCompression::Fast:
            break;
    }
    return render::PngCompression::Fast;
}

ImageEncoding frameEncoding(const scene::OutputDesc& output) {
    return {.png = pngCompression(output.pngCompression),
            .jpegQuality = output.jpegQuality,
            .alpha = output.alpha};
}

glm::vec3 toGlm(const scene::Vec3& v) {
    return {v.x, v.y, v.z};
}

SceneCameraPath::SceneCameraPath(const scene::Scene& s, const SceneBounds& bounds)
    : type_(s.path.type),
      frames_(s.path.frames),
      bounds_(bounds),
      aspect_(float(s.output.width) / float(s.output.height)),
      fov_(s.camera.fov),
      elevation_(s.camera.elevation.value_or(30.0f)),
      projection_(s.camera.projection == scene::Projection::Orthographic
                      ? Projection::Orthographic
                      : Projection::Perspective) {
    const scene::CameraDesc& c = s.camera;
    SIERRA_CHECK(frames_ > 0, "a camera path needs at least one frame, got ", frames_);
    target_ = c.target ? toGlm(*c.target) : defaultTarget(bounds);
    switch (type_) {
        case scene::PathType::Orbit:
            SIERRA_CHECK(
                !c.position,
                "an orbit path sets the camera position itself: leave out the camera position");
            moveTarget_ = c.target.has_value();
            distance_ = c.distance;
            orbitDistance_ = orbitDistance(bounds, frames_, aspect_, fov_, elevation_);
            if (projection_ == Projection::Orthographic)
                orthoHeight_ = framedCamera(bounds, {.target = target_,
                                                     .fovYDegrees = fov_,
                                                     .projection = projection_,
                                                     .aspect = aspect_})
                                   .orthoHeight;
            break;
        case scene::PathType::Flyover:
            break;
        case scene::PathType::Keyframes:
            for (const scene::Keyframe& k : s.path.keyframes)
                keys_.push_back(
                    {.time = k.time, .position = toGlm(k.position), .target = toGlm(k.target)});
            checkKeyframes(keys_);
            break;
        case scene::PathType::None:
            if (c.position) {
                still_.position = toGlm(*c.position);
                still_.target = target_;
                still_.fovYDegrees = fov_;
                still_.projection = projection_;
                if (projection_ == Projection::Orthographic)
                    still_.orthoHeight = framedCamera(bounds, {.target = target_,
                                                               .projection = projection_,
                                                               .aspect = aspect_})
                                             .orthoHeight;
                fitClipPlanes(still_, bounds);
            } else {
                still_ = framedCamera(bounds, {.target = target_,
                                               .azimuthDeg = c.azimuth.value_or(225.0f),
                                               .elevationDeg = elevation_,
                                               .fovYDegrees = fov_,
                                               .projection = projection_,
                                               .aspect = aspect_,
                                               .distance = c.distance.value_or(0.0f)});
            }
            break;
    }
}

Camera SceneCameraPath::at(int k) const {
    SIERRA_CHECK(k >= 0 && k < frames_, "frame ", k, " is outside the sequence's ", frames_,
                 " frames");
    Camera cam;
    switch (type_) {
        case scene::PathType::Orbit:
            cam = orbitCamera(bounds_, k, frames_, orbitDistance_, aspect_, fov_, elevation_);
            if (moveTarget_) {
                cam.position += target_ - cam.target;
                cam.target = target_;
            }
            if (distance_)
                cam.position = cam.target + glm::normalize(cam.position - cam.target) * *distance_;
            cam.projection = projection_;
            if (projection_ == Projection::Orthographic) cam.orthoHeight = orthoHeight_;
            fitClipPlanes(cam, bounds_);
            break;
        case scene::PathType::Flyover:
            cam = flyoverCamera(bounds_, k, frames_, fov_);
            break;
        case scene::PathType::Keyframes:
            cam = keyframeCamera(bounds_, keys_, k, frames_, fov_);
            break;
        case scene::PathType::None:
            cam = still_;
            break;
    }
    cam.forward();  // throws for position == target
    return cam;
}

Camera sceneCamera(const scene::Scene& s, const SceneBounds& bounds, int k) {
    return SceneCameraPath(s, bounds).at(k);
}

std::vector<Camera> sceneCameras(const scene::Scene& s, const SceneBounds& bounds) {
    const SceneCameraPath path(s, bounds);
    std::vector<Camera> cameras;
    cameras.reserve(size_t(path.frames()));
    for (int k = 0; k < path.frames(); ++k) cameras.push_back(path.at(k));
    return cameras;
}

Lighting sceneLighting(const scene::LightingDesc& l, bool transparent) {
    Lighting out;
    out.sunDirection = compassDirection(l.sunAzimuth, l.sunAltitude);
    out.ambient = l.ambient;
    out.fogDensity = l.fog ? *l.fog : -1.0f;
    out.sky = {l.sky.r, l.sky.g, l.sky.b};
    out.transparent = transparent;
    out.shadows = l.shadows;
    out.skyLight = l.skyLight;
    out.sunSize = l.sunSize;
    out.horizonRadius = l.horizonRadius;
    return out;
}

namespace {

std::string describeSun(const scene::SunAngles& sun) {
    std::string where;
    if (sun.time)
        where = msg(terrain::formatUtcTime(*sun.time), " over ", fixed(std::abs(sun.latitude), 4),
                    sun.latitude >= 0.0 ? " N, " : " S, ", fixed(std::abs(sun.longitude), 4),
                    sun.longitude >= 0.0 ? " E" : " W", ": ");
    return msg(where, "azimuth ", fixed(sun.azimuth, 2), ", altitude ", fixed(sun.altitude, 2),
               " degrees");
}

}  // namespace

glm::vec3 sceneSunDirection(const scene::Scene& s, const terrain::Heightfield& field, int k) {
    const bool moving = s.lighting.sunTime && s.lighting.sunStep != 0.0f && s.path.frames > 1;
    const scene::SunAngles sun = scene::sceneSun(s, field, moving ? k : 0);
    return compassDirection(sun.azimuth, sun.altitude);
}

void describeSceneSun(const scene::Scene& s, const terrain::Heightfield& field) {
    const int frames = s.path.frames;
    const bool moving = s.lighting.sunTime && s.lighting.sunStep != 0.0f && frames > 1;
    const int looked = moving ? std::min(frames, kSunSurveyFrames) : 1;
    int below = 0, firstBelow = -1;
    for (int i = 0; i < looked; ++i) {
        // Every frame, or `looked` of them from the first to the last.
        const int k =
            looked == frames ? i : int(int64_t(i) * (frames - 1) / std::max(looked - 1, 1));
        const scene::SunAngles sun = scene::sceneSun(s, field, moving ? k : 0);
        if (i == 0 || (moving && i == looked - 1))
            log::info("sun", moving ? msg(" of frame ", k) : std::string(), ": ", describeSun(sun));
        if (sun.altitude + 0.5f * s.lighting.sunSize <= 0.0f && below++ == 0) firstBelow = k;
    }
    if (below == 0) return;
    std::string where = below == looked ? std::string("every frame")
                        : looked == frames
                            ? msg(below, " of ", frames, " frames")
                            : msg("about ", int64_t(below) * frames / looked, " of ", frames,
                                  " frames (", below, " of the ", looked, " looked at)");
    log::warn("the sun is below the horizon in ", where,
              below == looked ? std::string() : msg(" (from frame ", firstBelow, ")"),
              ": no direct light, those frames are lit by the sky alone");
}

std::vector<glm::vec3> sceneSunDirections(const scene::Scene& s,
                                          const terrain::Heightfield& field) {
    describeSceneSun(s, field);
    const int frames = s.path.frames;
    const bool moving = s.lighting.sunTime && s.lighting.sunStep != 0.0f && frames > 1;
    if (!moving) return std::vector<glm::vec3>(size_t(frames), sceneSunDirection(s, field, 0));
    std::vector<glm::vec3> directions;
    directions.reserve(size_t(frames));
    for (int k = 0; k < frames; ++k) directions.push_back(sceneSunDirection(s, field, k));
    return directions;
}

render::ZoneSurfaceDesc zoneSurfaceDesc(const scene::Scene& s, float seaLevel,
                                        const terrain::Heightfield& field) {
    const scene::ZonesDesc& z = s.zones;
    ZoneSurfaceDesc desc;
    desc.paletteName = z.palette.empty() ? scene::assetPath("palettes/default.json") : z.palette;
    desc.palette = scene::loadPalette(desc.paletteName);
    desc.map = z.map;
    desc.band = z.band;
    desc.epsilon = z.epsilon;
    desc.heightBlend = z.blend == "height";
    desc.triplanar = z.triplanar;
    desc.variation = z.variation;
    desc.debugView = z.debugView == "zones"   ? ZoneDebugView::Zones
                     : z.debugView == "bands" ? ZoneDebugView::Bands
                                              : ZoneDebugView::None;
    desc.autoZones = scene::autoZoneDesc(z, seaLevel, field);
    return desc;
}

std::string applySceneSurface(TerrainRenderer& renderer, const scene::Scene& s,
                              const terrain::Heightfield& field, float seaLevel,
                              MapLayers* layers) {
    const scene::ZonesDesc& z = s.zones;
    std::unique_ptr<Surface> surface;
    std::string description;
    if (!s.style.overlay.layers.shaded) {
        // Line and hatch styles without shading draw on plain paper, as the
        // curvature document's figures do.
        surface = makePaperSurface();
        description = "surface: paper (style without shaded)";
    } else if (!z.map.empty()) {
        const ZoneSurfaceDesc desc = zoneSurfaceDesc(s, seaLevel, field);
        ZoneSurfaceInfo info;
        surface = makeZoneSurface(renderer.terrain(), field, desc, &info);
        description =
            msg("zones: ", z.map == "auto" ? std::string("auto") : z.map, ", ", info.mapWidth, "x",
                info.mapHeight, ", ", info.zoneCount, " surface types, ", info.borderEdges,
                " borderline edges, band ", info.band, " px, field ", info.texelsPerPixel,
                " texel(s) per pixel, built in ", info.buildMs, " ms");
    }
    // The layers wrap the surface in their drapes and set it (or set it alone).
    MapLayers applied = applyMapLayers(renderer, s, field, std::move(surface));
    for (const std::string& line : applied.notes)
        description += (description.empty() ? "" : "; ") + line;
    if (layers) *layers = std::move(applied);
    return description;
}

TerrainDesc sceneTerrainDesc(const scene::Scene& s, const terrain::Heightfield& field,
                             float seaLevel) {
    return {.field = &field,
            .seaLevel = seaLevel,
            .threads = s.lod.threads,
            .metric = scene::metricHeights(s.terrain, field),
            .treeLine = s.style.treeLine,
            .snowLine = s.style.snowLine,
            .cpt = s.style.cpt};
}

SceneCameraPath snapshotCameraPath(const scene::Scene& s, const SceneBounds& bounds,
                                   int frameWidth) {
    scene::Scene narrow = s;
    narrow.output.width = frameWidth;
    return SceneCameraPath(narrow, bounds);
}

std::vector<Camera> snapshotCameras(const scene::Scene& s, const SceneBounds& bounds,
                                    int frameWidth) {
    scene::Scene narrow = s;
    narrow.output.width = frameWidth;
    return sceneCameras(narrow, bounds);
}

DrawOptions sceneDrawOptions(const scene::Scene& s) {
    return {.lod = !s.lod.mesh.empty()                  ? Lod::Mesh
                   : s.lod.mode == scene::LodMode::Full ? Lod::Full
                                                        : Lod::Sbt,
            .tau = s.lod.tau,
            .geomorph = s.lod.geomorph,
            .cull = s.lod.cull,
            .wireframe = s.style.wireframe,
            .polygons = s.style.polygons,
            .points = s.style.points,
            .colourBy = s.style.colourBy == "level"   ? 1
                        : s.style.colourBy == "error" ? 2
                                                      : 0,
            .threads = s.lod.threads,
            .lighting = sceneLighting(s.lighting, s.output.alpha)};
}

std::string applySceneMesh(TerrainRenderer& renderer, const scene::Scene& s,
                           const terrain::Heightfield& field) {
    if (s.lod.mesh.empty()) return {};
    const std::string& path = s.lod.mesh;
    const tin::ObjFile obj = tin::readObj(path);
    SIERRA_CHECK(!obj.faces.empty(), "mesh ", path, ": no triangles");
    TerrainGpu& terrain = renderer.terrain();
    const glm::vec2 spacing = terrain.spacing();
    const SceneBounds bounds = terrain.bounds();
    const int realW = int(std::lround(bounds.max.x / spacing.x)) + 1;
    const int realH = int(std::lround(bounds.max.z / spacing.y)) + 1;
    auto [lo, hi] = field.range();
    const double heightTolerance = 1e-3 * std::max(double(hi - lo) * field.verticalScale(), 1e-6);
    std::vector<uint32_t> linear(obj.positions.size());
    for (size_t v = 0; v < obj.positions.size(); ++v) {
        const auto& p = obj.positions[v];
        const double gi = double(p[0]) / spacing.x, gj = double(p[2]) / spacing.y;
        const long i = std::lround(gi), j = std::lround(gj);
        const bool onSample = std::abs(gi - double(i)) < 1e-3 && std::abs(gj - double(j)) < 1e-3 &&
                              i >= 0 && j >= 0 && i < realW && j < realH;
        if (!onSample)
            throw Error(msg("mesh ", path, ": vertex ", v + 1, " at (", p[0], ", ", p[2],
                            ") is not a sample of the terrain's ", realW, "x", realH,
                            " grid (spacing ", spacing.x,
                            "); make the mesh with sierra-tin and the same terrain options"));
        const double h = double(field.at(int(i), int(j))) * field.verticalScale();
        if (std::abs(double(p[1]) - h) > heightTolerance)
            throw Error(msg("mesh ", path, ": vertex ", v + 1, " has height ", p[1],
                            ", the terrain ", h, " at sample (", i, ", ", j,
                            "); make the mesh with sierra-tin and the same terrain options"));
        linear[v] = uint32_t(j) * uint32_t(terrain.side()) + uint32_t(i);
    }
    std::vector<uint32_t> triangles;
    triangles.reserve(obj.faces.size() * 3);
    for (const auto& f : obj.faces)
        for (int32_t v : f) triangles.push_back(linear[size_t(v)]);
    terrain.setMesh(triangles);
    return msg("mesh: ", path, ", ", obj.faces.size(), " triangles, ", obj.positions.size(),
               " vertices");
}

namespace {

// Curvature has world units (1 / length), so a style whose scale suits a grid
// of unit spacing draws next to nothing on metric data spaced tens of metres
// apart, or on smooth terrain: say so, with the scale that would show it,
// rather than render a blank overlay silently. `lines`: the polylines traced
// (lines on), so that a field some of whose samples pass the threshold but
// whose paths all fall short of the minimum length is reported too.
void warnIfFaint(const analysis::CurvatureField& values, const analysis::StyleParams& style,
                 const terrain::Heightfield& field, std::optional<size_t> lines) {
    std::vector<float> largest = analysis::largestMagnitudes(values);
    if (largest.empty()) return;
    // Hatch opacity is the value itself: below this a stroke is barely seen.
    constexpr float kFaintHatch = 0.1f;
    const float most = *std::max_element(largest.begin(), largest.end());
    // Lines that reach the threshold and trace something: nothing to say
    // (the usual case, decided before any of the work below).
    if (style.layers.lines && most >= style.lines.threshold && (!lines || *lines > 0)) return;
    // The top 5% of samples: the suggestion brings them to the threshold
    // (lines) or to full opacity (hatches).
    const float topValue = analysis::topFivePercent(largest);
    const float scale = style.curvature.scale;
    const float target = analysis::autoCurvatureTarget(style);
    const std::string suggestion =
        topValue > 0.0f && topValue < target && !style.curvature.levels.enabled
            ? msg(" (--curvature-scale ", analysis::scaleToReach(topValue, scale, target),
                  ", which 'auto' picks, brings the top 5% of samples to ", target, ")")
            : std::string();
    const std::string units =
        msg(". Curvature is in world units (1 / length) and this grid is spaced ", field.spacingX(),
            " x ", field.spacingZ(), " apart; raise the scale", suggestion);
    if (!style.layers.lines) {
        // Hatches: faint when 95% of the strokes are under kFaintHatch opacity.
        if (topValue >= kFaintHatch) return;
        log::warn(
            "overlays: the hatches are all but transparent: 95% of the samples' curvature is "
            "under ",
            kFaintHatch, " (their opacity) at a curvature scale of ", scale, ", the largest ", most,
            units);
        return;
    }
    const float needed = style.lines.threshold;
    if (most < needed) {
        log::warn("overlays: the curvature field's largest value is ", most,
                  " at a curvature scale of ", scale,
                  ", so no curvature line reaches the threshold ", needed, units);
        return;
    }
    const auto passing =
        std::count_if(largest.begin(), largest.end(), [&](float v) { return v >= needed; });
    log::warn("overlays: no curvature line: ", passing, " of ", largest.size(),
              " samples reach the threshold ", needed, " at a curvature scale of ", scale,
              ", but no path through them has the minimum length of ", style.lines.minLength,
              " vertices; raise the scale", suggestion,
              " or lower the minimum length (--min-length)");
}

}  // namespace

OverlayInfo addOverlayPasses(TerrainRenderer& renderer, const scene::Scene& s) {
    analysis::StyleParams style = s.style.overlay;  // with an automatic scale resolved
    // An automatic scale starts from the field at the scale the scene or its
    // preset holds (the same field a faint overlay's warning measures), or at
    // 1 where that is 0.
    if (style.autoScale && style.curvature.scale == 0.0f) style.curvature.scale = 1.0f;
    OverlayInfo info{.scale = style.curvature.scale};
    if (!style.layers.lines && !style.layers.hatch && !style.layers.contours) return info;
    const terrain::Heightfield& field = renderer.terrain().surface();
    if (style.layers.lines || style.layers.hatch) {
        auto curvature = std::make_shared<CurvatureGpu>(CurvatureGpu::create(field));
        curvature->compute(style.curvature, style.layers.hatch);
        // Read back once per terrain and style: the lines are traced from it,
        // and an overlay that would draw nothing is reported.
        analysis::CurvatureField values = curvature->read();
        if (style.autoScale) {
            // The field again at the scale its values ask for (exact, not the
            // values read back multiplied: the GPU field draws the hatches).
            const float scale = analysis::autoCurvatureScale(values, style);
            if (scale != style.curvature.scale) {
                style.curvature.scale = scale;
                curvature->compute(style.curvature, style.layers.hatch);
                values = curvature->read();
            }
            info.scale = scale;
            log::info("overlays: curvature scale auto: ", scale, " (the top 5% of samples at ",
                      style.layers.lines ? msg("the line threshold ", style.lines.threshold)
                                         : std::string("full hatch opacity"),
                      ")");
        }
        if (style.layers.hatch) {
            // One automatic scale serves both layers, chosen for the lines
            // (the top 5% at the line threshold): the hatches' opacity is
            // brought to what a scale chosen for them alone gives (the top 5%
            // opaque).
            const float gain = style.autoScale && style.layers.lines && style.lines.threshold > 0.0f
                                   ? 1.0f / style.lines.threshold
                                   : 1.0f;
            renderer.addPass(HatchPass::create(curvature, {.length = style.hatch.length,
                                                           .width = style.hatch.width,
                                                           .direction = style.hatch.direction,
                                                           .opacityGain = gain}));
        }
        if (style.layers.lines) {
            // Traced once per terrain and style, from the GPU field read back.
            analysis::LineSet lines = analysis::traceLines(values, analysis::lineOptions(style));
            info.lines = lines.polylineCount();
            auto pass = LinePass::create(lines, {.width = style.lines.width});
            info.segments = pass->segmentCount();
            renderer.addPass(std::move(pass));
        }
        warnIfFaint(values, style, field,
                    style.layers.lines ? std::optional<size_t>(info.lines) : std::nullopt);
    }
    if (style.layers.contours) renderer.addPass(ContourPass::create());
    log::info("overlays: ", style.layers.hatch ? "hatches, " : "",
              style.layers.lines ? msg(info.lines, " lines (", info.segments, " segments), ")
                                 : std::string(),
              style.layers.contours ? "contour edges, " : "",
              analysis::curvatureMethodName(style.curvature.method), " curvature on the GPU");
    return info;
}

}  // namespace sierra::facade
