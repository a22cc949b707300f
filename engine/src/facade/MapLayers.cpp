#include <sierra/facade/MapLayers.h>

#include <sierra/core/Error.h>
#include <sierra/core/Log.h>
#include <sierra/render/DrapeSurface.h>
#include <sierra/render/TerrainGpu.h>
#include <sierra/render/VectorOverlay.h>
#include <sierra/render/passes/LinePass.h>
#include <sierra/scene/Assets.h>
#include <sierra/scene/PaletteJson.h>
#include <sierra/scene/Terrain.h>
#include <sierra/terrain/Drape.h>

#include <algorithm>
#include <cmath>

namespace sierra::facade {

using namespace sierra::render;

namespace {

render::Corner frameCorner(scene::FrameCorner c) {
    switch (c) {
        case scene::FrameCorner::TopRight:
            return render::Corner::TopRight;
        case scene::FrameCorner::BottomLeft:
            return render::Corner::BottomLeft;
        case scene::FrameCorner::BottomRight:
            return render::Corner::BottomRight;
        default:
            return render::Corner::TopLeft;
    }
}

}  // namespace

AnnotationDesc furnitureAnnotations(const scene::FurnitureDesc& f) {
    AnnotationDesc a;
    a.textPixels = f.textPixels;
    a.scaleBar = f.scaleBar;
    a.scaleBarCorner = frameCorner(f.scaleBarCorner);
    a.northArrow = f.northArrow;
    a.northArrowCorner = frameCorner(f.northArrowCorner);
    a.title = f.title;
    a.titleCorner = frameCorner(f.titleCorner);
    return a;
}

std::vector<LabelSample> labelSamples(const scene::Scene& s, const terrain::Heightfield& field,
                                      const TerrainPlacement& place) {
    std::vector<LabelSample> out;
    for (const scene::LabelDesc& l : s.layers.labels) {
        double i = l.x / field.spacingX(), j = l.z / field.spacingZ();
        if (l.geographic) {
            if (!place.placement)
                throw Error(msg("label \"", l.text, "\" at ", l.x, "E, ", l.z,
                                "N needs a georeferenced terrain; give world x, z instead"));
            const terrain::GridPoint p = terrain::geographicToSamples(*place.placement, l.x, l.z);
            i = p.i, j = p.j;
        }
        if (!(i >= 0.0 && j >= 0.0 && i <= place.width - 1.0 && j <= place.height - 1.0))
            throw Error(msg("label \"", l.text, "\" lies outside the terrain (sample ", i, ", ", j,
                            " of ", place.width, "x", place.height, ")"));
        out.push_back({l.text, i, j});
    }
    return out;
}

TerrainPlacement terrainPlacement(const terrain::Heightfield& field, int width, int height) {
    TerrainPlacement p;
    p.width = width;
    p.height = height;
    if (const auto& g = field.georeference())
        p.placement = terrain::GridPlacement{g->geoTransform, g->crsWkt, p.width, p.height};
    return p;
}

TerrainPlacement terrainPlacement(const TerrainRenderer& renderer,
                                  const terrain::Heightfield& field) {
    const SceneBounds b = renderer.bounds();
    return terrainPlacement(
        field, std::clamp(int(std::lround(b.max.x / field.spacingX())) + 1, 1, field.width()),
        std::clamp(int(std::lround(b.max.z / field.spacingZ())) + 1, 1, field.height()));
}

namespace {

void note(MapLayers& layers, const std::string& line, bool warning = false) {
    if (warning) log::warn(line);
    layers.notes.push_back(line);
}

render::RampSurfaceDesc rampDesc(const scene::Scene& s, const terrain::Heightfield& field) {
    return {.metric = scene::metricHeights(s.terrain, field),
            .treeLine = s.style.treeLine,
            .snowLine = s.style.snowLine,
            .cpt = s.style.cpt};
}

terrain::DrapeOptions drapeOptions(const scene::DrapeDesc& d, const TerrainPlacement& place) {
    terrain::DrapeOptions o{
        .placement = place.placement, .width = place.width, .height = place.height};
    if (d.bounds)
        o.bounds =
            terrain::DrapeBounds{d.boundsUnits == "crs" ? terrain::DrapeBounds::Units::Crs
                                                        : terrain::DrapeBounds::Units::Samples,
                                 (*d.bounds)[0], (*d.bounds)[1], (*d.bounds)[2], (*d.bounds)[3]};
    o.resampling =
        d.resampling == "cubic" ? terrain::Resampling::Cubic : terrain::Resampling::Bilinear;
    o.maxTexels = maxTextureSide();
    return o;
}

void describeDrape(MapLayers& layers, const std::string& image, const terrain::DrapeImage& d) {
    note(layers, msg("drape: ", image, ", ", d.width, "x", d.height, " texels, ",
                     int(std::lround(d.coverage * 100.0)), "% of the terrain",
                     d.reprojected ? ", reprojected" : ""));
    if (d.stretched)
        note(layers, "drape " + image + " has no georeference to go by: stretched over the terrain",
             true);
    if (d.reducedFrom[0] > 0)
        note(layers,
             msg("drape ", image, " reduced from ", d.reducedFrom[0], "x", d.reducedFrom[1], " to ",
                 d.width, "x", d.height, " texels (this GPU's texture limit)"),
             true);
}

// Vector layers: lines into `lineTexture` for the far field and as passes
// near the camera, fills as drape layers, labels for the frames.
void addVectors(TerrainRenderer& renderer, const scene::Scene& s, const terrain::Heightfield& field,
                const TerrainPlacement& place, std::vector<terrain::DrapeImage>& fills,
                std::vector<DrapeLayer>& fillLayers, std::optional<LinePyramid>& lineTexture,
                MapLayers& layers) {
    std::vector<analysis::LineSet> lineSets;
    std::vector<LineStyle> styles;
    for (const scene::VectorDesc& v : s.layers.vectors) {
        const terrain::VectorLayer layer =
            terrain::readVectorLayer(v.file, {.placement = place.placement,
                                              .width = place.width,
                                              .height = place.height,
                                              .where = v.where,
                                              .labelField = v.labelField});
        note(layers, msg("vector: ", v.file, ", ", layer.features.size(), " features, ",
                         layer.vertices, " vertices", layer.reprojected ? ", reprojected" : ""));
        if (layer.assumedGridSystem)
            note(layers, v.file + " has no reference system: the terrain's is assumed", true);
        if (layer.outside > 0)
            note(layers,
                 msg(v.file, ": ", layer.outside, " of ", layer.read,
                     " features lie outside the terrain",
                     layer.features.empty() ? " (all of them: nothing is drawn)"
                                            : " and are dropped"),
                 true);
        const glm::vec4 colour(v.colour[0], v.colour[1], v.colour[2], v.opacity);
        analysis::LineSet lines = vectorLines(layer, true, 1.0f);
        if (lines.polylineCount() > 0) {
            lineSets.push_back(std::move(lines));
            styles.push_back(
                {.colour = colour, .width = v.width, .dashOn = v.dashOn, .dashOff = v.dashOff});
        }
        if (v.fillOpacity > 0.0f) {
            terrain::DrapeImage fill =
                polygonDrape(layer, place.width, place.height, colour, v.fillOpacity);
            if (fill.coverage > 0.0) fills.push_back(std::move(fill));
        }
        for (Label label : vectorLabels(layer, field))
            layers.annotations.labels.push_back(std::move(label));
    }
    for (const terrain::DrapeImage& fill : fills) fillLayers.push_back({&fill});
    if (lineSets.empty()) return;
    std::vector<LineLayer> lineLayers;
    for (size_t k = 0; k < lineSets.size(); ++k) lineLayers.push_back({&lineSets[k], styles[k]});
    lineTexture =
        rasteriseLines(lineLayers, place.width, place.height, std::min(4096, maxTextureSide()));
    const float texel = std::max(field.spacingX(), field.spacingZ()) / lineTexture->texelsPerSample;
    for (size_t k = 0; k < lineSets.size(); ++k)
        renderer.addPass(LinePass::create(lineSets[k], {.width = styles[k].width,
                                                        .colour = styles[k].colour,
                                                        .thin = false,
                                                        .nearTexelSize = texel}));
}

std::vector<Label> sceneLabels(const scene::Scene& s, const terrain::Heightfield& field,
                               const TerrainPlacement& place) {
    std::vector<Label> labels;
    for (const LabelSample& l : labelSamples(s, field, place))  // before the layers' labels
        labels.push_back({l.text, surfacePoint(field, l.i, l.j), 2.0f});
    return labels;
}

}  // namespace

std::unique_ptr<Surface> drapeSurface(const scene::Scene& s, const TerrainPlacement& place,
                                      std::unique_ptr<Surface> surface,
                                      std::span<const DrapeLayer> fills, const LinePyramid* lines,
                                      std::vector<std::string>& notes) {
    MapLayers said;
    const auto& drapes = s.layers.drapes;
    if (drapes.size() == 1 && drapes[0].blend == "replace" && fills.empty()) {
        // One image: streamed into its texture, never held whole.
        terrain::DrapeImage header;
        surface = makeStreamedDrapeSurface(std::move(surface), drapes[0].image,
                                           drapeOptions(drapes[0], place), drapes[0].opacity,
                                           &header, lines);
        describeDrape(said, drapes[0].image, header);
    } else {
        std::vector<terrain::DrapeImage> images;
        images.reserve(drapes.size());
        std::vector<DrapeLayer> stack;
        for (const scene::DrapeDesc& d : drapes) {
            images.push_back(terrain::readDrape(d.image, drapeOptions(d, place)));
            describeDrape(said, d.image, images.back());
        }
        for (size_t k = 0; k < drapes.size(); ++k)
            stack.push_back(
                {&images[k], drapes[k].opacity,
                 drapes[k].blend == "multiply" ? DrapeBlend::Multiply : DrapeBlend::Replace});
        stack.insert(stack.end(), fills.begin(), fills.end());
        surface = makeDrapeSurface(std::move(surface), stack, lines);
    }
    notes.insert(notes.end(), said.notes.begin(), said.notes.end());
    return surface;
}

MapLayers applyMapLayers(TerrainRenderer& renderer, const scene::Scene& s,
                         const terrain::Heightfield& field, std::unique_ptr<Surface> surface) {
    MapLayers layers;
    const TerrainPlacement place = terrainPlacement(renderer, field);
    std::vector<terrain::DrapeImage> fills;
    std::vector<DrapeLayer> fillLayers;
    std::optional<LinePyramid> lineTexture;
    layers.annotations.labels = sceneLabels(s, field, place);
    addVectors(renderer, s, field, place, fills, fillLayers, lineTexture, layers);
    const LinePyramid* lines = lineTexture ? &*lineTexture : nullptr;

    if (!s.layers.drapes.empty() || !fillLayers.empty() || lines) {
        if (!surface) surface = makeRampSurface(renderer.terrain(), rampDesc(s, field));
        surface = drapeSurface(s, place, std::move(surface), fillLayers, lines, layers.notes);
    }
    if (surface) renderer.setSurface(std::move(surface));

    const scene::FurnitureDesc& f = s.layers.furniture;
    AnnotationDesc& a = layers.annotations;
    std::vector<Label> labels = std::move(a.labels);
    a = furnitureAnnotations(f);
    a.labels = std::move(labels);
    a.unitsPerMetre = scene::metricHeights(s.terrain, field) ? 1.0f : 0.0f;
    if (f.legend) {
        a.legend = sceneLegend(renderer, s, field);
        a.legend->corner = frameCorner(f.legendCorner);
    }
    layers.labelsNeedDepth = !a.labels.empty();
    return layers;
}

Legend sceneLegend(TerrainRenderer& renderer, const scene::Scene& s,
                   const terrain::Heightfield& field) {
    Legend legend;
    if (!s.zones.map.empty()) {
        legend.title = "Zones";
        const zones::Palette palette = scene::loadPalette(
            s.zones.palette.empty() ? scene::assetPath("palettes/default.json") : s.zones.palette,
            false);
        for (const zones::SurfaceType& t : palette.surfaces)
            legend.swatches.push_back(
                {{float((t.colour >> 16) & 255) / 255.0f, float((t.colour >> 8) & 255) / 255.0f,
                  float(t.colour & 255) / 255.0f},
                 t.name});
        return legend;
    }
    const bool metric = scene::metricHeights(s.terrain, field);
    legend.title = "Elevation";
    legend.units = metric ? "m" : "";
    const TerrainGpu& gpu = renderer.terrain();
    const terrain::ColourRamp ramp = surfaceRamp(gpu, rampDesc(s, field));
    const glm::vec2 range = gpu.worldRange() / gpu.verticalScale();  // stored units, as the ramp
    const float lo = range.x, hi = range.y;
    for (int k = 0; k <= 5; ++k) {
        // Round values: the legend reads 0, 250, 500 rather than 3.7, 251.3.
        const float raw = lo + (hi - lo) * float(k) / 5.0f;
        const float step = std::pow(10.0f, std::floor(std::log10(std::max(hi - lo, 1e-6f))) - 1.0f);
        const float value = k == 0 ? lo : k == 5 ? hi : std::round(raw / step) * step;
        const terrain::Rgb c = ramp.colourAt(value);
        legend.ramp.push_back(
            {std::round(value * 100.0f) / 100.0f, {c.r / 255.0f, c.g / 255.0f, c.b / 255.0f}});
    }
    return legend;
}

void drawMapLayers(AnnotationOverlay& overlay, const MapLayers& layers, const Camera& camera,
                   int width, int height, const DepthImage* depth) {
    if (!layers.drawsOver()) return;
    const AnnotationLayout layout =
        layoutAnnotations(layers.annotations, camera, width, height, depth, overlay.measurer());
    overlay.draw(layers.annotations, layout);
}

}  // namespace sierra::facade
