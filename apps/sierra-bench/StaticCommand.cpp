// sierra-bench static --heightmap FILE | --generate N [--seed S --roughness R]
//                     --max-error E [--repeat K] [--threads T] [--obj FILE] [--json FILE]
//
// The fixed-error SBT mesh of one heightfield: the error pass is timed once,
// then refinement + strip extraction K times (median and p95). Prints grid size,
// error pass ms, triangles, distinct vertices, strip indices, indices per
// triangle, extraction ms, million triangles per second (total and per thread)
// and the true maximum vertical distance between the grid and the mesh.
#include "Commands.h"

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/core/Parallel.h>
#include <sierra/core/Timer.h>
#include <sierra/scene/Terrain.h>
#include <sierra/sbt/Refiner.h>
#include <sierra/sbt/VertexErrors.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace sierra::apps {
namespace {

struct StaticOptions {
    std::string heightmap;
    int generate = 0;
    uint64_t seed = 1;
    float roughness = 1.0f;
    float maxError = 0.0f;
    int repeat = 20;
    int threads = 0;
    int rawWidth = 0;
    int rawHeight = 0;
    float spacing = 0.0f;        // 0 = automatic (1; SRTM 90 or 30 m)
    float verticalScale = 1.0f;  // stored height -> world height
    std::string obj;
    std::string json;
};

// OBJ of the mesh: only the vertices it uses, x = column * spacingX,
// y = world height, z = row * spacingZ (grid units with the default spacing 1);
// one face per triangle, 1-based, winding as decoded. Written to a temporary
// name in the same directory, then renamed.
void writeObj(const std::string& path, const terrain::Heightfield& field,
              const std::vector<std::array<uint32_t, 3>>& tris) {
    const int side = field.width();
    std::vector<uint32_t> remap(size_t(side) * side, 0);
    std::vector<uint32_t> order;
    for (const auto& t : tris)
        for (uint32_t v : t)
            if (!remap[v]) {
                order.push_back(v);
                remap[v] = uint32_t(order.size());
            }
    writeFileAtomic(path, [&](std::FILE* out) {
        std::fprintf(out, "# sierra-bench static: fixed-error SBT mesh, %zu triangles\n", tris.size());
        for (uint32_t v : order) {
            int i = int(v % uint32_t(side)), j = int(v / uint32_t(side));
            std::fprintf(out, "v %.6g %.6g %.6g\n", i * double(field.spacingX()), double(field.worldHeight(i, j)),
                         j * double(field.spacingZ()));
        }
        for (const auto& t : tris) std::fprintf(out, "f %u %u %u\n", remap[t[0]], remap[t[1]], remap[t[2]]);
    });
}

void runStatic(const StaticOptions& o) {
    if (o.heightmap.empty() == (o.generate == 0))
        throw Error("static: give exactly one of --heightmap FILE or --generate N");
    if (!std::isfinite(o.maxError))
        throw Error(msg("static: --max-error must be a finite number (world height units), got ", o.maxError));
    if (o.repeat < 1) throw Error(msg("static: --repeat must be >= 1, got ", o.repeat));
    if (o.threads < 0) throw Error(msg("static: --threads must be >= 0 (0 = all cores), got ", o.threads));

    // The same loading, padding and generation as every Sierra app, but heights
    // stay in the file's units unless --vertical-scale says otherwise: the
    // error bound is then in the data's own units.
    scene::TerrainSource terrainSource{.heightmap = o.heightmap,
                                       .generateSize = o.generate ? o.generate : 1025,
                                       .seed = o.seed,
                                       .roughness = o.roughness,
                                       .rawWidth = o.rawWidth,
                                       .rawHeight = o.rawHeight,
                                       .spacing = o.spacing,
                                       .verticalScale = o.verticalScale};
    std::string source;
    terrain::Heightfield field = scene::loadTerrain(terrainSource, &source);
    const int inputW = field.width(), inputH = field.height();
    const int threads = o.threads > 0 ? o.threads : defaultThreadCount();

    Stopwatch sw;
    sbt::VertexErrors errors = sbt::computeVertexErrors(field, threads);
    const double errorPassMs = sw.ms();

    sbt::Refiner refiner(field, errors, {.threads = threads});
    sbt::StripMesh mesh;
    refiner.refineFixed(o.maxError, mesh);  // warm-up: buffers reach their size
    std::vector<double> times;
    for (int k = 0; k < o.repeat; ++k) {
        sw.restart();
        refiner.refineFixed(o.maxError, mesh);
        times.push_back(sw.ms());
    }
    const double medianMs = median(times), p95Ms = quantile(times, 0.95);
    const auto tris = sbt::decodeStrip(mesh.indices);
    const int64_t vertices = sbt::countDistinctVertices(mesh.indices, field.width());
    const double maxDistance = sbt::maxVerticalDistance(field, tris, threads);
    const double mtps = medianMs > 0 ? double(mesh.triangleCount) / (medianMs * 1e3) : 0.0;

    std::printf("source                 %s\n", source.c_str());
    std::printf("grid                   %dx%d%s\n", field.width(), field.height(),
                (inputW != field.width() || inputH != field.height())
                    ? msg(" (padded from ", inputW, "x", inputH, ")").c_str()
                    : "");
    std::printf("max error              %g\n", double(o.maxError));
    std::printf("threads                %d\n", threads);
    std::printf("error pass             %.3f ms\n", errorPassMs);
    std::printf("triangles              %lld\n", (long long)mesh.triangleCount);
    std::printf("distinct vertices      %lld\n", (long long)vertices);
    std::printf("strip indices          %zu (%d strips)\n", mesh.indices.size(), mesh.stripCount);
    std::printf("indices per triangle   %.4f\n", mesh.indicesPerTriangle());
    std::printf("extraction median      %.3f ms (p95 %.3f ms, %d runs)\n", medianMs, p95Ms, o.repeat);
    std::printf("throughput             %.1f M triangles/s (%.1f M/s per thread)\n", mtps, mtps / threads);
    std::printf("max vertical distance  %g\n", maxDistance);

    if (!o.obj.empty()) writeObj(o.obj, field, tris);
    if (!o.json.empty()) {
        nlohmann::json j = {
            {"source", source},
            {"grid", {{"width", field.width()}, {"height", field.height()}}},
            {"input", {{"width", inputW}, {"height", inputH}}},
            {"max_error", o.maxError},
            {"threads", threads},
            {"error_pass_ms", errorPassMs},
            {"triangles", mesh.triangleCount},
            {"distinct_vertices", vertices},
            {"strip_indices", mesh.indices.size()},
            {"strips", mesh.stripCount},
            {"indices_per_triangle", mesh.indicesPerTriangle()},
            {"extraction_ms", {{"median", medianMs}, {"p95", p95Ms}, {"runs", o.repeat}, {"all", times}}},
            {"mtriangles_per_s", mtps},
            {"mtriangles_per_s_per_thread", mtps / threads},
            {"max_vertical_distance", maxDistance},
        };
        std::string text = j.dump(2) + "\n";
        writeFileAtomic(o.json, text);
    }
}

}  // namespace

void addStaticCommand(CLI::App& app) {
    auto opts = std::make_shared<StaticOptions>();
    CLI::App* cmd = app.add_subcommand(
        "static", "Fixed-error SBT mesh: size, strip efficiency, extraction speed, true max error");
    auto* hm = cmd->add_option("--heightmap", opts->heightmap,
                               "Heightfield file (.png .pgm .r16 .r32 .hgt .npy); padded to (2^n+1)^2 if needed");
    auto* gen = cmd->add_option("--generate", opts->generate, "Diamond-square fractal of N x N samples (N = 2^n + 1)");
    hm->excludes(gen);
    cmd->add_option("--seed", opts->seed, "Seed of --generate (default 1)");
    cmd->add_option("--roughness", opts->roughness, "Roughness of --generate (default 1)");
    cmd->add_option("--max-error", opts->maxError,
                    "Split while the saturated vertex error exceeds this (world height units; < 0 = full grid)")
        ->required();
    cmd->add_option("--raw-width", opts->rawWidth, "Width of a .r16/.r32 heightmap");
    cmd->add_option("--raw-height", opts->rawHeight, "Height of a .r16/.r32 heightmap");
    cmd->add_option("--spacing", opts->spacing, "World units between samples (0 = automatic: 1, SRTM 90/30 m)");
    cmd->add_option("--vertical-scale", opts->verticalScale,
                    "Stored height to world height (default 1: errors in the data's units; 0 = automatic)");
    cmd->add_option("--repeat", opts->repeat, "Timed extraction runs (default 20)");
    cmd->add_option("--threads", opts->threads, "Threads (default 0 = all cores)");
    cmd->add_option("--obj", opts->obj, "Write the mesh as Wavefront OBJ (x = column, y = height, z = row)");
    cmd->add_option("--json", opts->json, "Write the figures as JSON");
    cmd->callback([opts] { runStatic(*opts); });
}

}  // namespace sierra::apps
