// sierra-gen map --heightmap FILE [terrain options] --scheme
// plasma|atlas|hypsometric|hillshade|slope
//                [--cpt FILE.cpt] [--colour-bar] [--sun-azimuth A --sun-altitude B] --out FILE.png
//
// One pixel per sample of the terrain as loaded (padding removed), row 0 =
// north. Height schemes colour the stored heights over their range (sea level
// from --sea-level, else the scene's automatic choice); --cpt colours them with
// a GMT table in absolute stored heights (metres for DEMs). Hillshade and slope
// use the world gradient (vertical scale and spacing). The colour bar is
// labelled in world height units (stored height times the vertical scale:
// metres for metric DEMs), slope's in degrees.
#include "Commands.h"

#include "AppMain.h"

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/core/Log.h>
#include <sierra/scene/Options.h>
#include <sierra/scene/Terrain.h>
#include <sierra/terrain/Cpt.h>
#include <sierra/terrain/Maps.h>

#include <cmath>
#include <memory>
#include <optional>
#include <string>

namespace sierra::apps {
namespace {

struct MapOptions {
    scene::Scene scene;  // only its terrain is used
    std::string scheme = "hypsometric";
    std::string cpt;
    bool colourBar = false;
    terrain::Sun sun;
    std::string out;
};

void runMap(const MapOptions& o) {
    const terrain::MapScheme scheme = [&] {
        try {
            return terrain::parseMapScheme(o.scheme);
        } catch (const Error& e) {
            throw UsageError(msg("map: --scheme: ", e.what()));
        }
    }();
    const bool shaded =
        scheme == terrain::MapScheme::Hillshade || scheme == terrain::MapScheme::Slope;
    if (!o.cpt.empty() && shaded)
        throw UsageError(
            msg("map: --cpt colours heights; it cannot be combined with --scheme ", o.scheme));
    if (o.colourBar && scheme == terrain::MapScheme::Hillshade)
        throw UsageError(
            "map: --colour-bar has nothing to label on a hillshade (use it with a height scheme or "
            "slope)");

    // The output location and the table are checked before the work.
    if (lowerExtension(o.out) != ".png")
        throw UsageError(
            msg("map: --out must name a .png file (maps are written as PNG), got '", o.out, "'"));
    ensureWritableLocation(o.out);
    std::optional<terrain::CptTable> cpt;
    if (!o.cpt.empty()) cpt = terrain::readCpt(o.cpt);
    std::string source;
    terrain::Heightfield field = scene::loadTerrain(o.scene.terrain, &source, scene::Padding::None);
    log::info("terrain: ", source, "; map ", field.width(), "x", field.height());
    // Plain variables, not a structured binding: the ramp's lambda captures
    // them (Clang before 16 cannot capture a binding).
    const std::pair<float, float> range = field.range();
    float lo = range.first, hi = range.second;
    if (!(hi > lo)) hi = lo + 1.0f;
    float sea = scene::resolveSeaLevel(o.scene.terrain, field);
    if (!std::isfinite(sea)) sea = lo - (hi - lo);  // no water: below every sample

    terrain::ColourRamp ramp = [&] {
        if (cpt) return cpt->ramp(lo, hi);
        if (scheme == terrain::MapScheme::Slope)  // the bar of slope: white flat to black vertical
            return terrain::ColourRamp({{0.0f, {255, 255, 255}}, {90.0f, {0, 0, 0}}}, 0.0f, 90.0f);
        const terrain::RampScheme rs =
            scheme == terrain::MapScheme::Plasma  ? terrain::RampScheme::Plasma
            : scheme == terrain::MapScheme::Atlas ? terrain::RampScheme::Atlas
                                                  : terrain::RampScheme::Hypsometric;
        return terrain::ColourRamp(
            {.scheme = rs, .minHeight = lo, .maxHeight = hi, .seaLevel = sea});
    }();
    terrain::RgbImage image = terrain::renderMap(field, scheme, ramp, o.sun);
    if (o.colourBar) {
        const bool metres = scene::metricHeights(o.scene.terrain, field);
        if (scheme == terrain::MapScheme::Slope)
            terrain::addColourBar(image, ramp, 1.0f, "deg");
        else
            terrain::addColourBar(image, ramp, field.verticalScale(), metres ? "m" : "");
    }
    terrain::writeRgbPng(o.out, image);
    log::info("wrote ", o.out, " (", image.width, "x", image.height, ")");
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
        "map", "2D map PNG of a heightfield: height colours, hillshade or slope");
    state->sceneOptions =
        std::make_unique<scene::SceneOptions>(*cmd, o.scene, scene::kTerrainOptions);
    cmd->add_option("--scheme", o.scheme, "plasma (grey), atlas, hypsometric, hillshade or slope")
        ->capture_default_str();
    cmd->add_option("--cpt", o.cpt,
                    "GMT .cpt colour table for the heights (absolute stored heights)");
    cmd->add_flag("--colour-bar", o.colourBar,
                  "Add a legend with ticks and numbers in height units");
    cmd->add_option("--sun-azimuth", o.sun.azimuth,
                    "Hillshade sun, degrees clockwise from north (up)")
        ->capture_default_str();
    cmd->add_option("--sun-altitude", o.sun.altitude,
                    "Hillshade sun, degrees above the horizon, 0..90")
        ->capture_default_str();
    cmd->add_option("--out", o.out, "Output PNG; required")->required();
    cmd->callback([state] {
        asUsage([&] { state->sceneOptions->apply(); });
        if (state->sceneOptions->printConfigRequested()) return;
        const terrain::Sun& sun = state->options.sun;
        if (!std::isfinite(sun.azimuth) || !(sun.altitude >= 0.0f && sun.altitude <= 90.0f))
            throw UsageError(
                msg("map: --sun-altitude must be 0..90 degrees and --sun-azimuth finite, got ",
                    sun.altitude, " and ", sun.azimuth));
        runMap(state->options);
    });
}

}  // namespace sierra::apps
