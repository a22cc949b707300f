// sierra-tin: a triangulated irregular network of a heightfield by greedy
// insertion, written as OBJ (+MTL), PLY or STL. No GL.

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/core/Timer.h>
#include <sierra/terrain/DiamondSquare.h>
#include <sierra/terrain/HeightfieldIO.h>
#include <sierra/tin/Export.h>
#include <sierra/tin/Tin.h>

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cctype>
#include <cstdio>
#include <nlohmann/json.hpp>

using namespace sierra;

namespace {

struct Options {
    std::string heightmap;
    int generate = 0;
    uint64_t seed = 1;
    double maxError = 0.0;
    double maxErrorRel = 0.0;
    int64_t maxTriangles = 0;
    int64_t maxPoints = 0;
    std::string delaunay = "plain";
    double uvPeriod = 64.0;
    std::string out;
    std::string json;
};

int run(const Options& o) {
    // Reject an unknown mesh format before the work, not after it.
    std::string ext = o.out.size() >= 4 ? o.out.substr(o.out.size() - 4) : "";
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (ext != ".obj" && ext != ".ply" && ext != ".stl")
        throw Error(msg(o.out, ": unknown mesh format (use .obj, .ply or .stl)"));
    Stopwatch clock, total;
    nlohmann::json report;
    terrain::Heightfield field;
    if (!o.heightmap.empty()) {
        field = terrain::loadHeightfield(o.heightmap);
        report["input"] = o.heightmap;
    } else {
        field = terrain::generateDiamondSquare({.size = o.generate, .seed = o.seed});
        report["input"] = msg("diamond-square ", o.generate, " seed ", o.seed);
    }
    const double loadMs = clock.ms();

    tin::TinDesc desc{.maxError = o.maxError,
                      .maxErrorRel = o.maxErrorRel,
                      .maxTriangles = o.maxTriangles,
                      .maxPoints = o.maxPoints,
                      .triangulation = o.delaunay == "data" ? tin::Triangulation::DataDependent
                                                            : tin::Triangulation::Delaunay};
    if (o.maxError == 0.0 && o.maxErrorRel == 0.0 && o.maxTriangles == 0 && o.maxPoints == 0)
        desc.maxErrorRel = 0.001;
    // A progress line rewritten in place on a terminal, plain lines (fewer) when redirected.
    const bool terminal = ::isatty(fileno(stderr));
    desc.progressEvery = terminal ? 20000 : 200000;
    desc.progress = [&](const tin::TinProgress& p) {
        std::fprintf(stderr,
                     "%ssierra-tin: %lld points, %lld triangles, error %.6g (target %.6g)%s",
                     terminal ? "\r" : "", (long long)p.points, (long long)p.triangles,
                     p.worstError, p.targetError, terminal ? "   " : "\n");
    };
    tin::TinResult result = tin::buildTin(field, {}, desc);
    if (terminal) std::fprintf(stderr, "\n");

    clock.restart();
    const tin::ErrorStats error = tin::measureError(result.mesh, field);
    const double measureMs = clock.ms();
    clock.restart();
    tin::writeMesh(o.out, result.mesh, {.uvPeriod = o.uvPeriod});
    const double writeMs = clock.ms();

    const auto& s = result.stats;
    const double pointsPerSecond =
        s.insertMs > 0 ? double(s.inserted) / (s.insertMs / 1000.0) : 0.0;
    std::printf("grid %d x %d, %s triangulation\n", field.width(), field.height(),
                o.delaunay == "data" ? "data-dependent" : "Delaunay");
    std::printf("triangles %zu, vertices %zu (%lld inserted, %.0f points/s), stopped by %s\n",
                result.mesh.triangles.size(), result.mesh.vertices.size(), (long long)s.inserted,
                pointsPerSecond, tin::toString(s.stop));
    std::printf("vertical error: max %.6g, rms %.6g (target %.6g) over %lld samples\n",
                error.maxError, error.rmsError, s.targetError, (long long)error.samples);
    std::printf(
        "time ms: load %.1f, setup %.1f, insert %.1f, zones %.1f, measure %.1f, write %.1f, total "
        "%.1f\n",
        loadMs, s.setupMs, s.insertMs, s.zonesMs, measureMs, writeMs, total.ms());
    std::printf("wrote %s\n", o.out.c_str());

    if (!o.json.empty()) {
        report["grid"] = {field.width(), field.height()};
        report["triangulation"] = o.delaunay;
        report["triangles"] = result.mesh.triangles.size();
        report["vertices"] = result.mesh.vertices.size();
        report["inserted"] = s.inserted;
        report["flips"] = s.flips;
        report["edge_splits"] = s.edgeSplits;
        report["snap_splits"] = s.snapSplits;
        report["stop"] = tin::toString(s.stop);
        report["target_error"] = s.targetError;
        report["max_error"] = error.maxError;
        report["rms_error"] = error.rmsError;
        report["samples"] = error.samples;
        report["points_per_second"] = pointsPerSecond;
        report["time_ms"] = {{"load", loadMs},     {"setup", s.setupMs},   {"insert", s.insertMs},
                             {"zones", s.zonesMs}, {"measure", measureMs}, {"write", writeMs},
                             {"total", total.ms()}};
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
        "With no stop option: --max-error-rel 0.001."};
    app.option_defaults()->always_capture_default();
    auto* heightmap = app.add_option(
        "--heightmap", o.heightmap,
        "Heightmap to load: .png (8/16-bit), .pgm, .r16/.r32, .hgt, .npy (any width x height)");
    auto* generate = app.add_option("--generate", o.generate,
                                    "Generate a diamond-square terrain of N = 2^n+1 samples")
                         ->excludes(heightmap);
    heightmap->excludes(generate);
    app.add_option("--seed", o.seed, "Seed of the generated terrain");
    app.add_option("--max-error", o.maxError,
                   "Stop when the largest vertical error is at most E (world height units)")
        ->check(CLI::NonNegativeNumber);
    app.add_option("--max-error-rel", o.maxErrorRel,
                   "Stop when the largest vertical error is at most F x the height range")
        ->check(CLI::Range(0.0, 1.0));
    app.add_option("--max-triangles", o.maxTriangles,
                   "Stop before exceeding N triangles (0 = no limit)")
        ->check(CLI::NonNegativeNumber);
    app.add_option("--max-points", o.maxPoints, "Stop before exceeding N vertices (0 = no limit)")
        ->check(CLI::NonNegativeNumber);
    app.add_option("--delaunay", o.delaunay, "plain: Delaunay flips; data: data-dependent flips")
        ->check(CLI::IsMember({"plain", "data"}));
    app.add_option("--uv-period", o.uvPeriod, "OBJ planar UVs: grid samples per texture repeat")
        ->check(CLI::PositiveNumber);
    app.add_option("--out", o.out, "Output mesh: .obj (with .mtl beside it), .ply or .stl")
        ->required();
    app.add_option("--json", o.json, "Write the statistics to this JSON file");
    try {
        app.parse(argc, argv);
        if (o.heightmap.empty() && o.generate == 0)
            throw CLI::ValidationError("give --heightmap FILE or --generate N");
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "sierra-tin: usage: %s (see --help)\n", e.what());
        return 2;
    }
    try {
        return run(o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "sierra-tin: error: %s\n", e.what());
        return 1;
    }
}
