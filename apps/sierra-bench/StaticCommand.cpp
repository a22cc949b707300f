// sierra-bench static [terrain options] --max-error E [--repeat K] [--threads T]
//                     [--obj FILE] [--json FILE] [--config FILE.json] [--print-config]
//
// The terrain options are the scene registrar's (sierra/scene/Options.h), as in
// every Sierra app; this command needs no GL and links none.
//
// The fixed-error SBT mesh of one heightfield: the error pass is timed once,
// then refinement + strip extraction K times (median and p95). Prints grid size,
// error pass ms, triangles, distinct vertices, strip indices, indices per
// triangle, extraction ms, million triangles per second (total and per thread)
// and the true maximum vertical distance between the grid and the mesh.
#include "Commands.h"

#include "AppMain.h"

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/core/Parallel.h>
#include <sierra/core/Timer.h>
#include <sierra/sbt/Refiner.h>
#include <sierra/sbt/VertexErrors.h>
#include <sierra/scene/Options.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace sierra::apps {
namespace {

struct StaticOptions {
    scene::Scene scene;  // only its terrain is used
    float maxError = 0.0f;
    int repeat = 20;
    int threads = 0;
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
        std::fprintf(out, "# sierra-bench static: fixed-error SBT mesh, %zu triangles\n",
                     tris.size());
        for (uint32_t v : order) {
            int i = int(v % uint32_t(side)), j = int(v / uint32_t(side));
            std::fprintf(out, "v %.6g %.6g %.6g\n", i * double(field.spacingX()),
                         double(field.worldHeight(i, j)), j * double(field.spacingZ()));
        }
        for (const auto& t : tris)
            std::fprintf(out, "f %u %u %u\n", remap[t[0]], remap[t[1]], remap[t[2]]);
    });
}

void runStatic(const StaticOptions& o) {
    if (!std::isfinite(o.maxError))
        throw Error(msg("static: --max-error must be a finite number (world height units), got ",
                        o.maxError));
    if (o.repeat < 1) throw Error(msg("static: --repeat must be >= 1, got ", o.repeat));
    if (o.threads < 0)
        throw Error(msg("static: --threads must be >= 0 (0 = all cores), got ", o.threads));

    // The same loading, padding and generation as every Sierra app (heights in
    // the file's units by default here, see addStaticCommand).
    std::string source;
    terrain::Heightfield field = scene::loadTerrain(o.scene.terrain, &source);
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
    std::printf("extraction median      %.3f ms (p95 %.3f ms, %d runs)\n", medianMs, p95Ms,
                o.repeat);
    std::printf("throughput             %.1f M triangles/s (%.1f M/s per thread)\n", mtps,
                mtps / threads);
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
            {"extraction_ms",
             {{"median", medianMs}, {"p95", p95Ms}, {"runs", o.repeat}, {"all", times}}},
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
    // The options and the scene registrar live as long as the app: the callback
    // runs inside app.parse().
    struct State {
        StaticOptions options;
        std::unique_ptr<scene::SceneOptions> sceneOptions;
    };
    auto state = std::make_shared<State>();
    StaticOptions& o = state->options;
    // Heights stay in the file's units unless --vertical-scale says otherwise:
    // the error bound is then in the data's own units.
    o.scene.terrain.verticalScale = 1.0f;

    CLI::App* cmd = app.add_subcommand(
        "static", "Fixed-error SBT mesh: size, strip efficiency, extraction speed, true max error");
    state->sceneOptions =
        std::make_unique<scene::SceneOptions>(*cmd, o.scene, scene::kTerrainOptions);
    CLI::Option* maxError = cmd->add_option("--max-error", o.maxError,
                                            "Split while the saturated vertex error exceeds this "
                                            "(world height units; < 0 = full grid); required");
    cmd->add_option("--repeat", o.repeat, "Timed extraction runs")->capture_default_str();
    cmd->add_option("--threads", o.threads, "Threads (0 = all cores)")->capture_default_str();
    cmd->add_option("--obj", o.obj,
                    "Write the mesh as Wavefront OBJ (x = column, y = height, z = row)");
    cmd->add_option("--json", o.json, "Write the figures as JSON");
    cmd->callback([state, maxError] {
        asUsage([&] { state->sceneOptions->apply(); });
        if (state->sceneOptions->printConfigRequested()) return;
        if (maxError->count() == 0)
            throw UsageError("static: --max-error E is required (world height units)");
        runStatic(state->options);
    });
}

}  // namespace sierra::apps
