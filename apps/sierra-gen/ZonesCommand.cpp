// sierra-gen zones --zones MAP.png|auto [--palette P.json] [--zone-epsilon E] [--band W]
//                  --json OUT.json [--svg OUT.svg] [--svg-href REF] [--borderlines] [--write-map
//                  OUT.png] [terrain options] [--deep-water F --sand-top F --zone-snow-line F
//                  --rock-slope DEG]
//
// Reads a zone map through a palette (or derives one from a heightfield by
// height and slope bands with --zones auto), vectorises its borderlines
// (rules 1-3, per arc with junctions pinned; epsilon in zone-map pixels),
// optionally doubles them into transition bands of width W pixels, and writes
// the result as JSON (vertices, edges with left/right zones, zones) and as an
// SVG of the arcs over the map. Prints counts and timings.
//
// The zone and terrain options (and --config, --print-config) come from the
// scene registrar, with sierra-render's names and defaults, and --zones auto
// zones the terrain as sierra-render does: its real samples, with the loader's
// vertical scale and the scene's sea level.
#include "Commands.h"

#include "AppMain.h"

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/scene/Assets.h>
#include <sierra/scene/BorderlinesJson.h>
#include <sierra/scene/Options.h>
#include <sierra/scene/PaletteJson.h>
#include <sierra/scene/Terrain.h>
#include <sierra/zones/BorderField.h>
#include <sierra/zones/Borderlines.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

namespace sierra::apps {
namespace {

struct ZonesOptions {
    scene::Scene scene;  // its terrain and zones are used
    std::string json;
    std::string svg;
    std::string svgHref;
    bool borderlines = false;
    std::string writeMap;
};

double msSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void runZones(const ZonesOptions& o) {
    // Every output location is checked before the work, as every app does.
    for (const std::string* path : {&o.json, &o.svg, &o.writeMap})
        if (!path->empty()) ensureWritableLocation(*path);
    const scene::ZonesDesc& z = o.scene.zones;
    const std::string paletteFile =
        z.palette.empty() ? scene::assetPath("palettes/default.json") : z.palette;
    zones::Palette palette = scene::loadPalette(paletteFile);
    zones::ZoneMap map;
    std::string source;
    if (z.map == "auto") {
        std::string description;
        terrain::Heightfield field =
            scene::loadTerrain(o.scene.terrain, &description, scene::Padding::None);
        const zones::AutoZoneDesc desc =
            scene::autoZoneDesc(z, scene::resolveSeaLevel(o.scene.terrain, field), field);
        map = zones::autoZones(field, palette, desc);
        source = msg("auto-zoning of ", description);
    } else {
        map = zones::loadZoneMap(z.map, palette);
        source = z.map;
    }
    if (o.borderlines) {
        if (map.layout == zones::ZoneLayout::Touching) map = zones::drawBorderlines(map);
    }
    std::vector<uint8_t> mapPng;
    if (!o.writeMap.empty() || (!o.svg.empty() && o.svgHref.empty()))
        mapPng = zones::encodeZoneMapPng(map, palette);
    if (!o.writeMap.empty()) writeFileAtomic(o.writeMap, mapPng);

    const double band = z.band >= 0.0f ? double(z.band) : palette.bandWidth;
    const double epsilon = z.epsilon;
    auto t0 = std::chrono::steady_clock::now();
    zones::Borderlines lines = zones::buildBorderlines(map, palette, {.epsilon = epsilon});
    double vectoriseMs = msSince(t0);
    t0 = std::chrono::steady_clock::now();
    zones::BorderField field = zones::buildBorderField(lines);
    double fieldMs = msSince(t0);
    zones::doubleBorderlines(lines, band);

    writeFileAtomic(o.json, std::string_view(scene::borderlinesToJson(lines)));
    if (!o.svg.empty())
        writeFileAtomic(o.svg,
                        std::string_view(zones::borderlinesToSvg(
                            lines, o.svgHref.empty() ? zones::pngDataUri(mapPng) : o.svgHref)));

    size_t borderEdges = 0;
    for (const auto& e : lines.edges) borderEdges += e.left >= 0 && e.right >= 0;
    std::printf("zone map: %s, %dx%d, %s layout\n", source.c_str(), map.width, map.height,
                map.layout == zones::ZoneLayout::Touching ? "touching" : "Figure 1 borderline");
    std::printf(
        "borderlines: %zu vertices, %zu edges (%zu between zones, the rest frame), %zu zones (%zu "
        "bands)\n",
        lines.vertices.size(), lines.edges.size(), borderEdges, lines.zones.size(),
        lines.zones.size() - palette.surfaces.size());
    std::printf(
        "epsilon %.3g px, band %.3g px; vectorise %.1f ms, distance field %dx%d %.1f ms (one "
        "core)\n",
        epsilon, band, vectoriseMs, field.width, field.height, fieldMs);
    auto areas = zones::zoneAreas(lines);
    for (const auto& z : lines.zones)
        std::printf("  zone %d %-28s %s  area %.1f px^2\n", z.id, z.name.c_str(),
                    zones::colourHex(z.colour).c_str(), areas[size_t(z.id)]);
}

}  // namespace

void addZonesCommand(CLI::App& app) {
    // The options and the scene registrar live as long as the app: the callback
    // runs inside app.parse().
    struct State {
        ZonesOptions options;
        std::unique_ptr<scene::SceneOptions> sceneOptions;
    };
    auto state = std::make_shared<State>();
    ZonesOptions& o = state->options;
    CLI::App* cmd = app.add_subcommand("zones", "Vectorise a zone map's borderlines (JSON, SVG)");
    state->sceneOptions = std::make_unique<scene::SceneOptions>(
        *cmd, o.scene, scene::kTerrainOptions | scene::kZoneOptions);
    cmd->add_option("--json", o.json,
                    "Write vertices, edges [from, to, left, right] and zones as JSON")
        ->required();
    cmd->add_option("--svg", o.svg, "Write an SVG of the borderlines over the map");
    cmd->add_option("--svg-href", o.svgHref,
                    "Reference this image in the SVG instead of embedding the map");
    cmd->add_flag("--borderlines", o.borderlines,
                  "Draw 1-pixel borderlines between the zones first (the Figure 1 layout)");
    cmd->add_option("--write-map", o.writeMap,
                    "Write the zone map used (after --borderlines) as a PNG");
    cmd->callback([state, cmd] {
        asUsage([&] { state->sceneOptions->apply(); });
        if (state->sceneOptions->printConfigRequested()) return;
        const scene::Scene& s = state->options.scene;
        if (s.zones.map.empty())
            throw UsageError(
                "zones: say which zones: --zones auto (from the terrain) or --zones MAP.png");
        if (s.zones.map != "auto" && (cmd->count("--heightmap") || cmd->count("--generate")))
            throw UsageError("zones: --heightmap and --generate only go with --zones auto");
        runZones(state->options);
    });
}

}  // namespace sierra::apps
