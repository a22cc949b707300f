// sierra-tin: a triangulated irregular network of a heightfield by greedy
// insertion, written as OBJ (+MTL), PLY or STL. No GL.
//
//   sierra-tin [terrain options] [--zones MAP.png|auto [--palette P.json] [--band W] [--epsilon
//   PX]]
//              [stop options] [--budget-stop best-max|last] --out MESH.obj|.ply|.stl
//              [--json STATS]
//
// With a triangle or point budget, --budget-stop best-max (the default) keeps
// the mesh of smallest max error the run went through within the budget (the
// max error of a greedy mesh is not monotone in the insertions); last keeps
// the last one.
// The terrain options are the scene registrar's (the names and defaults of
// every Sierra app; no terrain option = the default scene's 1025^2 fractal);
// the grid is meshed as read, never padded. With --zones the zone map's
// borderlines (vectorised by the zones module, simplified by --epsilon,
// doubled into bands of --band pixels) are constrained edges of the mesh, and
// the OBJ gets one material per surface type and per band pair, textured with
// the palette's tiles (blended for bands).

#include "AppMain.h"

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/core/Timer.h>
#include <sierra/scene/Assets.h>
#include <sierra/scene/Options.h>
#include <sierra/scene/PaletteJson.h>
#include <sierra/scene/Terrain.h>
#include <sierra/tin/Export.h>
#include <sierra/tin/Tin.h>
#include <sierra/tin/ZoneTin.h>
#include <sierra/zones/Borderlines.h>
#include <sierra/zones/Palette.h>
#include <sierra/zones/ZoneMap.h>

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

using namespace sierra;

namespace {

// A finite number >= 0 (CLI11's NonNegativeNumber accepts NaN and names its upper
// bound, the largest double, in full).
const CLI::Validator kNonNegative(
    [](std::string& text) -> std::string {
        double v = 0.0;
        if (!CLI::detail::lexical_cast(text, v) || !std::isfinite(v) || v < 0.0)
            return "must be a finite number >= 0, got " + text;
        return {};
    },
    "");

struct Options {
    scene::Scene scene;  // its terrain, and its zones' map, palette, band and epsilon
    double maxError = 0.0;
    double maxErrorRel = 0.0;
    int64_t maxTriangles = 0;
    int64_t maxPoints = 0;
    std::string delaunay = "plain";
    std::string budgetStop = "best-max";
    double uvPeriod = 64.0;
    bool uvPeriodGiven = false;  // with --zones, replaces the tiles' own periods
    bool epsilonGiven = false;   // --epsilon on the command line: no automatic epsilon
    std::string out;
    std::string json;
};

struct ZoneInput {
    zones::Palette palette;
    zones::ZoneMap map;
    double band = 0.0;
    double ms = 0.0;
};

ZoneInput loadZones(const scene::Scene& s, const terrain::Heightfield& field) {
    Stopwatch clock;
    ZoneInput z;
    const scene::ZonesDesc& d = s.zones;
    z.palette = scene::loadPalette(d.palette.empty() ? scene::assetPath("palettes/default.json")
                                                     : d.palette);
    if (d.map == "auto") {
        const zones::AutoZoneDesc a =
            scene::autoZoneDesc(d, scene::resolveSeaLevel(s.terrain, field), field);
        z.map = zones::autoZones(field, z.palette, a);
    } else {
        z.map = zones::loadZoneMap(d.map, z.palette);
    }
    SIERRA_CHECK(z.map.width >= 2 && z.map.height >= 2, "zone map ", d.map, " is ", z.map.width,
                 "x", z.map.height, "; a TIN needs at least 2x2 pixels");
    z.band = d.band >= 0.0f ? double(d.band) : double(z.palette.bandWidth);
    z.ms = clock.ms();
    return z;
}

int run(const Options& o) {
    // Reject an unknown mesh format and an unwritable output before the work, not after it.
    const std::string ext = lowerExtension(o.out);
    if (ext != ".obj" && ext != ".ply" && ext != ".stl")
        throw Error(msg(o.out, ": unknown mesh format (use .obj, .ply or .stl)"));
    ensureWritableLocation(o.out);
    if (!o.json.empty()) ensureWritableLocation(o.json);
    const scene::Scene& s = o.scene;
    Stopwatch clock, total;
    nlohmann::json report;
    std::string source;
    const terrain::Heightfield field = scene::loadTerrain(s.terrain, &source, scene::Padding::None);
    report["input"] = source;
    const double loadMs = clock.ms();

    const bool zoned = !s.zones.map.empty();
    ZoneInput z;
    if (zoned) z = loadZones(s, field);

    tin::TinDesc desc{
        .maxError = o.maxError,
        .maxErrorRel = o.maxErrorRel,
        .maxTriangles = o.maxTriangles,
        .maxPoints = o.maxPoints,
        .budgetStop = o.budgetStop == "last" ? tin::BudgetStop::Last : tin::BudgetStop::BestMax,
        .triangulation = o.delaunay == "data" ? tin::Triangulation::DataDependent
                                              : tin::Triangulation::Delaunay};
    const bool errorTarget = o.maxError > 0.0 || o.maxErrorRel > 0.0;
    const bool budget = o.maxTriangles > 0 || o.maxPoints > 0;
    if (!errorTarget && !budget) desc.maxErrorRel = 0.001;
    // A progress line rewritten in place on a terminal, plain lines (fewer) when redirected.
    const bool terminal = ::isatty(fileno(stderr));
    desc.progressEvery = terminal ? 20000 : 200000;
    desc.progress = [&](const tin::TinProgress& p) {
        std::fprintf(stderr,
                     "%ssierra-tin: %lld points, %lld triangles, error %.6g (target %.6g)%s",
                     terminal ? "\r" : "", (long long)p.points, (long long)p.triangles,
                     p.worstError, p.targetError, terminal ? "   " : "\n");
    };
    // A budget alone and the default epsilon: the borderlines are simplified to
    // the budget's scale and back towards the default while the zone agreement
    // is below 99.5% (tin::buildZonedTin).
    tin::ZonedTin zt;
    if (zoned) {
        tin::ZonedTinDesc zd{
            .epsilon = s.zones.epsilon,
            .bandWidth = z.band,
            .autoEpsilon = !o.epsilonGiven && s.zones.epsilon == scene::ZonesDesc{}.epsilon,
            .retry = [&](double agreement, double epsilon, double next) {
                if (terminal) std::fprintf(stderr, "\n");
                std::fprintf(stderr,
                             "sierra-tin: zone agreement %.3f%% at epsilon "
                             "%.3g px; again at %.3g\n",
                             100.0 * agreement, epsilon, next);
            }};
        zt = tin::buildZonedTin(field, z.map, z.palette, desc, zd);
        z.ms += zt.borderlinesMs;
    } else {
        zt.result = tin::buildTin(field, {}, desc);
    }
    if (terminal) std::fprintf(stderr, "\n");
    clock.restart();
    const tin::TinResult& result = zt.result;
    const tin::ZoneAgreement& agreement = zt.agreement;
    const bool autoEpsilon = zt.autoEpsilon;
    const double epsilon = zt.epsilon;
    tin::ErrorStats error;
    // Constrained borderlines are inserted whole, before the budget counts: when
    // they alone exceed it the mesh does too, and the user has to know.
    const int64_t meshTriangles = int64_t(result.mesh.triangles.size());
    const int64_t meshVertices = int64_t(result.mesh.vertices.size());
    const bool overTriangles = o.maxTriangles > 0 && meshTriangles > o.maxTriangles;
    const bool overBudget = overTriangles || (o.maxPoints > 0 && meshVertices > o.maxPoints);
    if (overBudget) {
        const std::string limit = overTriangles ? msg("--max-triangles ", o.maxTriangles)
                                                : msg("--max-points ", o.maxPoints);
        std::fprintf(stderr,
                     "sierra-tin: warning: the zone borderlines alone need %lld triangles and %lld "
                     "vertices, over the budget (%s); the mesh keeps them all. Coarsen them with a "
                     "larger --epsilon (now %.3g px), or raise the budget\n",
                     (long long)meshTriangles, (long long)meshVertices, limit.c_str(), epsilon);
    }
    error = tin::measureError(result.mesh, field);
    const double measureMs = clock.ms();
    clock.restart();
    tin::ObjOptions objOptions{.uvPeriod = o.uvPeriod};
    if (zoned && ext == ".obj") {
        // Each material repeats with its tile's period, as the renderer draws it;
        // --uv-period given: one period for every material instead.
        objOptions = tin::zoneMaterials(o.out, result.mesh, z.palette, z.map.width, z.map.height);
        objOptions.uvPeriod = o.uvPeriod;
        if (o.uvPeriodGiven) {
            objOptions.surfacePeriods.clear();
            objOptions.uvOffset = {0.0, 0.0};
        }
    }
    tin::writeMesh(o.out, result.mesh, objOptions);
    const double writeMs = clock.ms();

    const auto& st = result.stats;
    const double pointsPerSecond =
        st.insertMs > 0 ? double(st.inserted) / (st.insertMs / 1000.0) : 0.0;
    std::printf("terrain: %s\n", source.c_str());
    std::printf("grid %d x %d, %s triangulation\n", field.width(), field.height(),
                o.delaunay == "data" ? "data-dependent" : "Delaunay");
    size_t borderSegments = 0;
    if (zoned) {
        for (const auto& e : zt.lines.edges) borderSegments += e.left >= 0 && e.right >= 0;
        std::printf(
            "zones: %s, %dx%d, %zu surface types, %zu zones (%zu bands), %zu borderline segments, "
            "epsilon %.3g px%s, %zu thin islands removed, band %.3g px\n",
            s.zones.map.c_str(), z.map.width, z.map.height, z.palette.surfaces.size(),
            zt.lines.zones.size(), zt.constraints.bands.size(), borderSegments, zt.epsilon,
            autoEpsilon ? " (automatic, from the budget)" : "", zt.islandsRemoved, z.band);
    }
    std::printf("triangles %zu, vertices %zu (%lld inserted, %.0f points/s), stopped by %s\n",
                result.mesh.triangles.size(), result.mesh.vertices.size(), (long long)st.inserted,
                pointsPerSecond, tin::toString(st.stop));
    const bool budgetStopped =
        st.stop == tin::StopReason::Triangles || st.stop == tin::StopReason::Points;
    if (budgetStopped)
        std::printf(
            "budget stop (%s): kept the mesh after %lld of %lld insertions, max error %.6g "
            "(%.6g at the last)\n",
            tin::toString(desc.budgetStop), (long long)st.inserted, (long long)st.budgetInserted,
            st.worstError, st.budgetWorstError);
    std::printf("vertical error: max %.6g, rms %.6g (target %.6g) over %lld samples\n",
                error.maxError, error.rmsError, st.targetError, (long long)error.samples);
    if (zoned)
        std::printf(
            "zone agreement: %.3f%% of %lld map pixels; %lld triangles claimed by two zones\n",
            100.0 * agreement.fraction(), (long long)agreement.pixels, (long long)st.zoneConflicts);
    std::printf(
        "time ms: load %.1f, borderlines %.1f, setup %.1f, insert %.1f, zones %.1f, measure %.1f, "
        "write %.1f, "
        "total %.1f\n",
        loadMs, z.ms, st.setupMs, st.insertMs, st.zonesMs, measureMs, writeMs, total.ms());
    std::printf("wrote %s\n", o.out.c_str());

    if (!o.json.empty()) {
        report["grid"] = {field.width(), field.height()};
        report["triangulation"] = o.delaunay;
        report["triangles"] = result.mesh.triangles.size();
        report["vertices"] = result.mesh.vertices.size();
        report["inserted"] = st.inserted;
        report["flips"] = st.flips;
        report["edge_splits"] = st.edgeSplits;
        report["snap_splits"] = st.snapSplits;
        report["stop"] = tin::toString(st.stop);
        report["over_budget"] = overBudget;
        report["target_error"] = st.targetError;
        report["worst_error_left"] = st.worstError;
        if (budgetStopped)
            report["budget_stop"] = {{"rule", tin::toString(desc.budgetStop)},
                                     {"kept_inserted", st.inserted},
                                     {"inserted_at_stop", st.budgetInserted},
                                     {"max_error_at_stop", st.budgetWorstError}};
        report["max_error"] = error.maxError;
        report["rms_error"] = error.rmsError;
        report["samples"] = error.samples;
        report["points_per_second"] = pointsPerSecond;
        if (zoned) {
            report["zones"] = {{"map", s.zones.map},
                               {"map_size", {z.map.width, z.map.height}},
                               {"surfaces", z.palette.surfaces.size()},
                               {"zones", zt.lines.zones.size()},
                               {"bands", zt.constraints.bands.size()},
                               {"borderline_segments", borderSegments},
                               {"epsilon", zt.epsilon},
                               {"epsilon_auto", autoEpsilon},
                               {"islands_removed", zt.islandsRemoved},
                               {"band", z.band},
                               {"agreement", agreement.fraction()},
                               {"agreement_pixels", agreement.pixels},
                               {"conflicts", st.zoneConflicts}};
        }
        report["time_ms"] = {{"load", loadMs},        {"borderlines", z.ms}, {"setup", st.setupMs},
                             {"insert", st.insertMs}, {"zones", st.zonesMs}, {"measure", measureMs},
                             {"write", writeMs},      {"total", total.ms()}};
        report["out"] = o.out;
        writeFileAtomic(o.json, report.dump(2) + "\n");
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    CLI::App app{
        "sierra-tin: a triangulated irregular network of a heightfield by greedy insertion\n"
        "(the grid sample of largest vertical error first), written as OBJ (+MTL), PLY or STL.\n"
        "With --zones the zone borderlines are constrained edges and the OBJ is textured with the\n"
        "palette's tiles. With no stop option: --max-error-rel 0.001.",
        "sierra-tin"};
    scene::SceneOptions sceneOptions(app, o.scene, scene::kTerrainOptions);
    const scene::ZonesDesc zoneDefaults;
    std::string zoneMap, palette;
    float band = zoneDefaults.band, epsilon = zoneDefaults.epsilon;
    const std::string zg = "Zones";
    app.add_option("--zones", zoneMap,
                   "Zone map PNG (colours from the palette) or 'auto' (height and slope bands); "
                   "its borderlines become constrained edges")
        ->type_name("MAP.png|auto")
        ->group(zg);
    app.add_option("--palette", palette, "Palette JSON (default: assets/palettes/default.json)")
        ->type_name("P.json")
        ->group(zg);
    app.add_option("--band", band,
                   "Transition band width in zone-map pixels (default: the palette's bandWidth)")
        ->type_name("W")
        ->group(zg)
        ->check(kNonNegative);
    // --epsilon, or --zone-epsilon as in every other program.
    app.add_option("--epsilon,--zone-epsilon", epsilon,
                   "Borderline simplification (rule 3) in zone-map pixels (default with a "
                   "triangle or point budget alone: from the budget)")
        ->type_name("PX")
        ->group(zg)
        ->check(kNonNegative)
        ->capture_default_str();
    const std::string sg = "Mesh";
    app.add_option("--max-error", o.maxError,
                   "Stop when the largest vertical error is at most E (world height units)")
        ->type_name("E")
        ->group(sg)
        ->check(kNonNegative);
    app.add_option("--max-error-rel", o.maxErrorRel,
                   "Stop when the largest vertical error is at most F x the height range")
        ->type_name("F")
        ->group(sg)
        ->check(CLI::Range(0.0, 1.0));
    app.add_option("--max-triangles", o.maxTriangles,
                   "Stop before exceeding N triangles (0 = no limit)")
        ->type_name("N")
        ->group(sg)
        ->check(kNonNegative);
    app.add_option("--max-points", o.maxPoints, "Stop before exceeding N vertices (0 = no limit)")
        ->type_name("N")
        ->group(sg)
        ->check(kNonNegative);
    app.add_option("--budget-stop", o.budgetStop,
                   "With --max-triangles/--max-points: best-max keeps the mesh of smallest max "
                   "error within the budget; last keeps the last insertion's")
        ->type_name("best-max|last")
        ->group(sg)
        ->check(CLI::IsMember({"best-max", "last"}))
        ->capture_default_str();
    app.add_option("--delaunay", o.delaunay, "plain: Delaunay flips; data: data-dependent flips")
        ->type_name("plain|data")
        ->group(sg)
        ->check(CLI::IsMember({"plain", "data"}))
        ->capture_default_str();
    app.add_option("--uv-period", o.uvPeriod,
                   "OBJ planar UVs: grid samples per texture repeat (with --zones: each tile's "
                   "own period, as the renderer's, unless given)")
        ->type_name("P")
        ->group(sg)
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    // Required, except with --print-config (checked after parsing).
    app.add_option("--out", o.out,
                   "Output mesh: .obj (with .mtl beside it), .ply or .stl (required)")
        ->type_name("MESH")
        ->group(sg);
    app.add_option("--json", o.json, "Write the statistics to this JSON file")
        ->type_name("STATS.json")
        ->group(sg);
    return apps::runMain(
        app, argc, argv,
        [&] {
            // The zone options are the scene's zones: applied over --config (or the
            // defaults) before the scene is checked and --print-config prints it, so a
            // printed config gives the same mesh with --config.
            sceneOptions.apply([&](scene::Scene& scene) {
                scene::ZonesDesc& z = scene.zones;
                if (!zoneMap.empty()) z.map = zoneMap;
                if (!palette.empty()) z.palette = palette;
                if (app.count("--band")) z.band = band;
                if (app.count("--epsilon")) z.epsilon = epsilon;
                if (z.map.empty() &&
                    (app.count("--palette") || app.count("--band") || app.count("--epsilon")))
                    throw Error(
                        "--palette, --band and --epsilon need --zones (or zones.map in --config)");
                if (!std::isfinite(z.epsilon) || z.epsilon < 0.0f)
                    throw Error(
                        msg("--epsilon must be a finite number of pixels >= 0, got ", z.epsilon));
                if (!std::isfinite(z.band))
                    throw Error(msg("--band must be a finite number of pixels, got ", z.band));
            });
            o.uvPeriodGiven = app.count("--uv-period") > 0;
            o.epsilonGiven = app.count("--epsilon") > 0;
            if (o.out.empty() && !sceneOptions.printConfigRequested())
                throw Error("--out is required (a .obj, .ply or .stl file)");
        },
        [&] {
            if (sceneOptions.printConfigRequested()) return 0;
            return run(o);
        });
}
