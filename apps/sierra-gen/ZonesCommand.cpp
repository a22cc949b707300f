// sierra-gen zones --zones MAP.png|auto --palette P.json [--epsilon E] [--band W]
//                  --json OUT.json [--svg OUT.svg] [--svg-href REF]
//                  [--heightmap FILE | --generate N [--seed S]] [--borderlines] [--write-map OUT.png]
//
// Reads a zone map through a palette (or derives one from a heightfield by
// height and slope bands with --zones auto), vectorises its borderlines
// (rules 1-3, per arc with junctions pinned; epsilon in zone-map pixels),
// optionally doubles them into transition bands of width W pixels, and writes
// the result as JSON (vertices, edges with left/right zones, zones) and as an
// SVG of the arcs over the map. Prints counts and timings.
#include "Commands.h"

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/terrain/DiamondSquare.h>
#include <sierra/terrain/HeightfieldIO.h>
#include <sierra/zones/BorderField.h>
#include <sierra/zones/Borderlines.h>

#include <chrono>
#include <cstdio>
#include <memory>

namespace sierra::apps {
namespace {

struct ZonesOptions {
    std::string zones;
    std::string palette;
    double epsilon = 0.0;
    double band = -1.0;  // < 0: the palette's bandWidth
    std::string json;
    std::string svg;
    std::string svgHref;
    std::string heightmap;
    int generate = 0;
    uint64_t seed = 1;
    zones::AutoZoneDesc autoDesc;
    bool borderlines = false;
    std::string writeMap;
};

double msSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void runZones(const ZonesOptions& o) {
    zones::Palette palette = zones::loadPalette(o.palette);
    zones::ZoneMap map;
    std::string source;
    if (o.zones == "auto") {
        if (o.heightmap.empty() == (o.generate == 0))
            throw Error("zones: --zones auto needs exactly one of --heightmap FILE or --generate N");
        terrain::Heightfield field = o.heightmap.empty()
                                         ? terrain::generateDiamondSquare({.size = o.generate, .seed = o.seed})
                                         : terrain::loadHeightfield(o.heightmap);
        // Slopes as the renderer shows them: its automatic vertical scale makes
        // the relief 20% of the horizontal extent.
        auto [lo, hi] = field.range();
        if (hi > lo) field.setVerticalScale(0.2f * float(field.width() - 1) * field.spacingX() / (hi - lo));
        map = zones::autoZones(field, palette, o.autoDesc);
        source = o.heightmap.empty() ? msg("auto-zoning of a ", o.generate, "^2 diamond-square terrain, seed ", o.seed)
                                     : msg("auto-zoning of ", o.heightmap);
    } else {
        if (!o.heightmap.empty() || o.generate) throw Error("zones: --heightmap and --generate only go with --zones auto");
        map = zones::loadZoneMap(o.zones, palette);
        source = o.zones;
    }
    if (o.borderlines) {
        if (map.layout == zones::ZoneLayout::Touching) map = zones::drawBorderlines(map);
    }
    std::vector<uint8_t> mapPng;
    if (!o.writeMap.empty() || (!o.svg.empty() && o.svgHref.empty())) mapPng = zones::encodeZoneMapPng(map, palette);
    if (!o.writeMap.empty()) writeFileAtomic(o.writeMap, mapPng);

    const double band = o.band >= 0 ? o.band : palette.bandWidth;
    auto t0 = std::chrono::steady_clock::now();
    zones::Borderlines lines = zones::buildBorderlines(map, palette, {.epsilon = o.epsilon});
    double vectoriseMs = msSince(t0);
    t0 = std::chrono::steady_clock::now();
    zones::BorderField field = zones::buildBorderField(lines);
    double fieldMs = msSince(t0);
    zones::doubleBorderlines(lines, band);

    writeFileAtomic(o.json, std::string_view(zones::borderlinesToJson(lines)));
    if (!o.svg.empty())
        writeFileAtomic(o.svg, std::string_view(zones::borderlinesToSvg(lines, o.svgHref.empty() ? zones::pngDataUri(mapPng) : o.svgHref)));

    size_t borderEdges = 0;
    for (const auto& e : lines.edges) borderEdges += e.left >= 0 && e.right >= 0;
    std::printf("zone map: %s, %dx%d, %s layout\n", source.c_str(), map.width, map.height,
                map.layout == zones::ZoneLayout::Touching ? "touching" : "Figure 1 borderline");
    std::printf("borderlines: %zu vertices, %zu edges (%zu between zones, the rest frame), %zu zones (%zu bands)\n",
                lines.vertices.size(), lines.edges.size(), borderEdges, lines.zones.size(),
                lines.zones.size() - palette.surfaces.size());
    std::printf("epsilon %.3g px, band %.3g px; vectorise %.1f ms, distance field %dx%d %.1f ms (one core)\n", o.epsilon,
                band, vectoriseMs, field.width, field.height, fieldMs);
    auto areas = zones::zoneAreas(lines);
    for (const auto& z : lines.zones)
        std::printf("  zone %d %-28s %s  area %.1f px^2\n", z.id, z.name.c_str(), zones::colourHex(z.colour).c_str(),
                    areas[size_t(z.id)]);
}

}  // namespace

void addZonesCommand(CLI::App& app) {
    auto opts = std::make_shared<ZonesOptions>();
    CLI::App* cmd = app.add_subcommand("zones", "Vectorise a zone map's borderlines (JSON, SVG)");
    cmd->add_option("--zones", opts->zones, "Zone map image (PNG; colours from the palette), or 'auto'")->required();
    cmd->add_option("--palette", opts->palette, "Palette JSON (zone colours, names, tiles)")->required();
    cmd->add_option("--epsilon", opts->epsilon, "Rule 3 tolerance in zone-map pixels (default 0: rules 1-2 only)")
        ->check(CLI::NonNegativeNumber);
    cmd->add_option("--band", opts->band, "Transition band width in zone-map pixels (default: the palette's bandWidth)")
        ->check(CLI::NonNegativeNumber);
    cmd->add_option("--json", opts->json, "Write vertices, edges [from, to, left, right] and zones as JSON")->required();
    cmd->add_option("--svg", opts->svg, "Write an SVG of the borderlines over the map");
    cmd->add_option("--svg-href", opts->svgHref, "Reference this image in the SVG instead of embedding the map");
    auto* hm = cmd->add_option("--heightmap", opts->heightmap, "With --zones auto: the heightfield file");
    auto* gen = cmd->add_option("--generate", opts->generate, "With --zones auto: a diamond-square terrain of N x N (2^n + 1)");
    hm->excludes(gen);
    cmd->add_option("--seed", opts->seed, "Seed of --generate (default 1)");
    cmd->add_option("--sea-level", opts->autoDesc.seaLevel, "Auto-zoning: sea level, stored height (default 0)");
    cmd->add_option("--deep-water", opts->autoDesc.deepWater, "Auto-zoning: deep below this fraction of the depth range")
        ->check(CLI::Range(0.0, 1.0));
    cmd->add_option("--sand-top", opts->autoDesc.sandTop, "Auto-zoning: sand up to this fraction of the land relief")
        ->check(CLI::Range(0.0, 1.0));
    cmd->add_option("--snow-line", opts->autoDesc.snowLine, "Auto-zoning: snow above this fraction of the land relief")
        ->check(CLI::Range(0.0, 1.0));
    cmd->add_option("--rock-slope", opts->autoDesc.rockSlope, "Auto-zoning: rock steeper than this (degrees)")
        ->check(CLI::Range(0.001, 90.0));
    cmd->add_flag("--borderlines", opts->borderlines,
                  "Draw 1-pixel borderlines between the zones first (the Figure 1 layout)");
    cmd->add_option("--write-map", opts->writeMap, "Write the zone map used (after --borderlines) as a PNG");
    cmd->callback([opts] { runZones(*opts); });
}

}  // namespace sierra::apps
