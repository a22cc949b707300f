// sierra-gen map --heightmap FILE [terrain options] --scheme NAME [scheme options]
//                [--cpt FILE.cpt] [--colour-bar] [--out FILE.png] [--values FILE.npy]
//
// One pixel (and one value) per sample of the terrain as loaded (padding
// removed), row 0 = the file's first row (north for a north-up GeoTIFF), as
// gdaldem writes its rasters. Height schemes colour the stored heights over
// their range (sea level from --sea-level, else the scene's automatic choice);
// --cpt colours them with a GMT table in absolute stored heights. The DEM
// schemes (terrain/DemMaps.h) and the lighting schemes (analysis/Relief.h) work
// in world units: heights times the vertical scale, the terrain's spacing.
// --values writes a scalar scheme's float32 field, NaN where gdaldem writes
// its no-data value. docs/maps.md has every scheme's formula and option.
// Labels and map furniture (--label, --title, --scale-bar, --north-arrow)
// are drawn over the map by sierra-gen-gpu, which this program runs for them
// (it links no GL); --legend is the colour bar.
#include "Commands.h"

#include "AppMain.h"
#include "MapOptions.h"
#include "MapSchemes.h"

#include <sierra/analysis/Relief.h>
#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/core/Log.h>
#include <sierra/core/Npy.h>
#include <sierra/scene/Options.h>
#include <sierra/scene/Terrain.h>
#include <sierra/terrain/Cpt.h>
#include <sierra/terrain/DemMaps.h>
#include <sierra/terrain/Maps.h>

#include <cmath>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sierra::apps {
namespace {

using map::Kind;
using map::MapOptions;
using map::Scheme;

// The lighting fields of analysis/Relief.h for a scheme.
std::vector<float> lightingField(const terrain::Heightfield& field, const Scheme& s,
                                 const MapOptions& o) {
    const analysis::HorizonOptions horizons{.directions = o.directions, .radius = o.horizonRadius};
    switch (s.kind) {
        case Kind::Shadow:
            return analysis::sunVisibility(
                field, {.azimuth = o.azimuth, .altitude = o.altitude, .diameter = o.sunSize},
                horizons);
        case Kind::OpennessPositive:
            return analysis::opennessPositive(field, horizons);
        case Kind::OpennessNegative:
            return analysis::opennessNegative(field, horizons);
        default:
            return analysis::skyViewFactor(field, horizons);
    }
}

terrain::ColourRamp heightRamp(const Scheme& s, const std::optional<terrain::CptTable>& cpt,
                               const terrain::Heightfield& field, const MapOptions& o) {
    const std::pair<float, float> range = field.range();
    float lo = range.first, hi = range.second;
    if (!(hi > lo)) hi = lo + 1.0f;
    if (cpt) return cpt->ramp(lo, hi);
    float sea = scene::resolveSeaLevel(o.scene.terrain, field);
    if (s.kind == Kind::Relief) return map::reliefTints(lo, hi, sea);
    if (!std::isfinite(sea)) sea = lo - (hi - lo);  // no water: below every sample
    const terrain::RampScheme rs =
        s.kind == Kind::Relief                   ? terrain::RampScheme::Hypsometric
        : s.height == terrain::MapScheme::Plasma ? terrain::RampScheme::Plasma
        : s.height == terrain::MapScheme::Atlas  ? terrain::RampScheme::Atlas
                                                 : terrain::RampScheme::Hypsometric;
    return terrain::ColourRamp({.scheme = rs, .minHeight = lo, .maxHeight = hi, .seaLevel = sea});
}

void runMap(const CLI::App& cmd, const MapOptions& o) {
    const Scheme s = map::parseScheme(o.scheme);
    map::checkMapOptions(cmd, s, o);
    const scene::MapLayersDesc& layers = o.scene.layers;
    const bool furniture = !layers.labels.empty() || layers.furniture.scaleBar ||
                           layers.furniture.northArrow || !layers.furniture.title.empty();
    if (furniture && o.out.empty())
        throw UsageError("map: labels and map furniture need --out FILE.png to draw on");
#ifndef SIERRA_GEN_GPU
    if (furniture) execBeside("sierra-gen-gpu");
#endif
    const bool colourBar = o.colourBar || layers.furniture.legend;
    const terrain::DemFieldDesc desc = map::demFieldDesc(s, o);

    // The outputs and the table are checked before the work.
    if (!o.out.empty()) ensureWritableLocation(o.out);
    if (!o.values.empty()) ensureWritableLocation(o.values);
    std::optional<terrain::CptTable> cpt;
    if (!o.cpt.empty()) cpt = terrain::readCpt(o.cpt);
    std::string source;
    terrain::Heightfield field = scene::loadTerrain(o.scene.terrain, &source, scene::Padding::None);
    log::info("terrain: ", source, "; map ", field.width(), "x", field.height());
    const bool metres = scene::metricHeights(o.scene.terrain, field);

    terrain::RgbImage image;
    // The colour bar widens the image: it goes on after the furniture, which
    // takes the map's pixels for its samples.
    std::function<void(terrain::RgbImage&)> addBar;
    if (s.kind == Kind::Height || s.kind == Kind::Relief) {
        const terrain::ColourRamp ramp = heightRamp(s, cpt, field, o);
        if (s.kind == Kind::Height) {
            image = terrain::renderMap(field, ramp);
            if (colourBar)
                addBar = [ramp, &field, metres](terrain::RgbImage& m) {
                    terrain::addColourBar(m, ramp, field.verticalScale(), metres ? "m" : "");
                };
        } else {
            const std::vector<float> shade = terrain::demField(field, desc);
            const std::vector<float> sky = lightingField(field, s, o);
            const float flat = desc.shade == terrain::ShadeStyle::Igor ||
                                       desc.shade == terrain::ShadeStyle::Combined
                                   ? 255.0f
                                   : 1.0f + 254.0f * float(std::sin(o.altitude * M_PI / 180.0));
            image = terrain::shadedRelief(
                field, ramp, shade, sky,
                {.flatShade = flat,
                 .skyFloor = std::min(terrain::finiteQuantile(sky, 0.01), 0.99f)});
        }
    } else {
        const std::vector<float> values =
            s.kind == Kind::Dem ? terrain::demField(field, desc) : lightingField(field, s, o);
        if (!o.values.empty()) {
            writeFileAtomic(o.values, encodeNpyFloat32(field.height(), field.width(), values));
            log::info("wrote ", o.values, " (", field.height(), "x", field.width(), " float32)");
        }
        if (!o.out.empty()) {
            const map::FieldRamp ramp = map::fieldRamp(s, desc, values, metres);
            image = terrain::colourField(field.width(), field.height(), values, ramp.ramp);
            if (colourBar)
                addBar = [ramp](terrain::RgbImage& m) {
                    terrain::addColourBar(m, ramp.ramp, 1.0f, ramp.units);
                };
        }
    }
#ifdef SIERRA_GEN_GPU
    if (furniture) drawMapFurniture(image, o.scene, field);
#endif
    if (addBar) addBar(image);
    if (!o.out.empty()) {
        // Grey maps (hillshade, sky-view, ...) as grey PNGs: a third of the data.
        bool grey = true;
        for (size_t k = 0; grey && k < image.rgb.size(); k += 3)
            grey = image.rgb[k] == image.rgb[k + 1] && image.rgb[k] == image.rgb[k + 2];
        if (grey) {
            std::vector<uint8_t> g(image.rgb.size() / 3);
            for (size_t k = 0; k < g.size(); ++k) g[k] = image.rgb[3 * k];
            terrain::writeGreyPng(o.out, image.width, image.height, g);
        } else {
            terrain::writeRgbPng(o.out, image);
        }
        log::info("wrote ", o.out, " (", image.width, "x", image.height, ")");
    }
}

}  // namespace

void addMapCommand(CLI::App& app) {
    // The options and the scene registrar live as long as the app: the callback
    // runs inside app.parse().
    struct State {
        MapOptions options;
        std::unique_ptr<scene::SceneOptions> sceneOptions;
    };
    auto state = std::make_shared<State>();
    MapOptions& o = state->options;
    CLI::App* cmd = app.add_subcommand(
        "map",
        "2D map PNG (and float32 .npy field) of a heightfield: height colours, hillshade, "
        "slope, aspect, TRI, TPI, roughness, curvatures, shadow, sky-view, openness, relief");
    state->sceneOptions = std::make_unique<scene::SceneOptions>(
        *cmd, o.scene, scene::kTerrainOptions | scene::kFurnitureOptions);
    map::addMapOptions(*cmd, o);
    cmd->footer(
        "Curvatures (1/world unit) follow Florinsky's sign convention: positive = convex "
        "(hilltops, ridges, slope shoulders), negative = concave (valleys, hollows, slope feet). "
        "Formulas: docs/maps.md.");
    cmd->callback([state, cmd] {
        asUsage([&] { state->sceneOptions->apply(); });
        if (state->sceneOptions->printConfigRequested()) return;
        runMap(*cmd, state->options);
    });
}

}  // namespace sierra::apps
