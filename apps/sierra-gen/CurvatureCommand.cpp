// sierra-gen curvature --heightmap FILE [terrain options]
//                      --method two-normal|three-normal|three-vertex|edge-angle [--distance D]
//                      [--normals edge|triangle|quad] [--scale S|auto] [--signed] [--device
//                      cpu|gpu]
//                      --out FILE.npy [--png FILE.png]
//
// The curvature field of the terrain as loaded (padding removed) along the 4
// grid directions of analysis/Curvature.h. --out: float32 .npy of shape (rows,
// cols, 4), row j = z, column i = x, the last axis in the order +x, +z, x+z,
// x-z; values scaled by --scale, no level control, NaN at no-data samples.
// --scale auto: the scale that brings the top 5% of the samples' largest
// magnitudes to 1 (white in the PNG), the field computed again at it.
// --png: the Figure 2 image of the seed document, one pixel per sample: the
// largest of the 4 magnitudes as grey intensity (0 black, 1 and above white);
// no-data samples black. --device gpu computes the same field with the
// compute shader (render/CurvatureGpu.h) in a headless EGL context: sierra-gen
// runs sierra-gen-gpu for it (CurvatureGpu.cpp), so sierra-gen links no GL.
#include "Commands.h"

#include "AppMain.h"

#include <sierra/analysis/Curvature.h>
#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/core/Log.h>
#include <sierra/core/Npy.h>
#include <sierra/core/Parallel.h>
#include <sierra/core/Timer.h>
#include <sierra/scene/Options.h>
#include <sierra/scene/Terrain.h>
#include <sierra/terrain/Maps.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace sierra::apps {
namespace {

struct CurvatureCommandOptions {
    scene::Scene scene;  // only its terrain is used
    std::string method;
    int distance = 1;  // reinforcement distance in grid steps, 1 = none
    std::string normals = "quad";
    std::string scale = "1";  // a number >= 0, or "auto"
    bool signedValues = false;
    std::string device = "cpu";
    std::string out;
    std::string png;
};

// The options as the analysis takes them; throws UsageError naming the option.
analysis::CurvatureOptions curvatureOptions(const CurvatureCommandOptions& o) {
    analysis::CurvatureOptions options;
    asUsage([&] {
        try {
            options.method = analysis::parseCurvatureMethod(o.method);
        } catch (const Error& e) {
            throw Error(msg("curvature: --method: ", e.what()));
        }
        try {
            options.normals = analysis::parseNormalMethod(o.normals);
        } catch (const Error& e) {
            throw Error(msg("curvature: --normals: ", e.what()));
        }
        options.distance = o.distance;
        if (o.scale != "auto")
            options.scale = scene::parseFloat(o.scale, "curvature: --scale", "a number or 'auto'");
        options.signedValues = o.signedValues;
        analysis::validate(options);  // its messages start "curvature: " and name the value
    });
    if (o.device != "cpu" && o.device != "gpu")
        throw UsageError(msg("curvature: --device must be cpu or gpu, got '", o.device, "'"));
    if (lowerExtension(o.out) != ".npy")
        throw UsageError(msg("curvature: --out must name a .npy file, got '", o.out, "'"));
    if (!o.png.empty() && lowerExtension(o.png) != ".png")
        throw UsageError(msg("curvature: --png must name a .png file, got '", o.png, "'"));
    return options;
}

// Figure 2: the largest magnitude per sample as grey intensity, clamped at 1.
std::vector<uint8_t> intensityImage(const analysis::CurvatureField& field) {
    std::vector<uint8_t> grey(size_t(field.width) * size_t(field.height));
    for (int j = 0; j < field.height; ++j)
        for (int i = 0; i < field.width; ++i) {
            const float k = field.maxMagnitude(i, j);  // NaN only at no data: black
            const float v = std::isnan(k) ? 0.0f : std::clamp(k, 0.0f, 1.0f);
            grey[size_t(j) * size_t(field.width) + size_t(i)] = uint8_t(std::lround(v * 255.0f));
        }
    return grey;
}

void runCurvature(const CurvatureCommandOptions& o) {
    const analysis::CurvatureOptions options = curvatureOptions(o);
#ifndef SIERRA_GEN_GPU
    // sierra-gen links no GL: the GPU path is sierra-gen-gpu's, run with these arguments.
    if (o.device == "gpu") execBeside("sierra-gen-gpu");
#endif
    // Every output location is checked before the work, so a bad path fails at once.
    ensureWritableLocation(o.out);
    if (!o.png.empty()) ensureWritableLocation(o.png);

    std::string source;
    const terrain::Heightfield field =
        scene::loadTerrain(o.scene.terrain, &source, scene::Padding::None);
    log::info("terrain: ", source, "; curvature of ", field.width(), "x", field.height(),
              " samples");
    auto compute = [&](const analysis::CurvatureOptions& with) {
        analysis::CurvatureField c;
        if (o.device == "gpu") {
#ifdef SIERRA_GEN_GPU
            c = computeCurvatureOnGpu(field, with);
#endif
        } else {
            Stopwatch clock;
            c = analysis::computeCurvature(field, with);
            log::info("curvature on the cpu: ", clock.ms(), " ms, ", defaultThreadCount(),
                      " threads");
        }
        return c;
    };
    analysis::CurvatureField curvature = compute(options);
    if (o.scale == "auto") {
        std::vector<float> largest = analysis::largestMagnitudes(curvature);
        const float top = analysis::topFivePercent(largest);
        if (top > 0.0f && std::isfinite(top)) {
            analysis::CurvatureOptions scaled = options;
            scaled.scale = analysis::scaleToReach(top, options.scale, 1.0f);
            curvature = compute(scaled);
            // 9 digits: --scale with the number logged gives the same field, bit for bit.
            std::ostringstream text;
            text << std::setprecision(9) << scaled.scale;
            log::info("curvature scale auto: ", text.str(), " (the top 5% of samples at 1)");
        } else {
            log::warn("curvature: --scale auto: the field is 0 (or no data) everywhere; scale 1");
        }
    }

    const int shape[] = {curvature.height, curvature.width, analysis::kDirectionCount};
    writeFileAtomic(o.out, encodeNpyFloat32(shape, curvature.values));
    log::info("wrote ", o.out, " (", curvature.height, "x", curvature.width, "x",
              analysis::kDirectionCount, " float32, ",
              analysis::curvatureMethodName(options.method), ")");
    if (!o.png.empty()) {
        terrain::writeGreyPng(o.png, curvature.width, curvature.height, intensityImage(curvature));
        log::info("wrote ", o.png, " (", curvature.width, "x", curvature.height, ")");
    }
}

}  // namespace

void addCurvatureCommand(CLI::App& app) {
    // The options and the scene registrar live as long as the app: the callback
    // runs inside app.parse().
    struct State {
        CurvatureCommandOptions options;
        std::unique_ptr<scene::SceneOptions> sceneOptions;
    };
    auto state = std::make_shared<State>();
    CurvatureCommandOptions& o = state->options;
    CLI::App* cmd = app.add_subcommand("curvature",
                                       "Curvature along the 4 grid directions as .npy (rows, cols, "
                                       "4), and its Figure 2 intensity PNG");
    state->sceneOptions =
        std::make_unique<scene::SceneOptions>(*cmd, o.scene, scene::kTerrainOptions);
    cmd->add_option("--method", o.method,
                    "two-normal, three-normal, three-vertex or edge-angle; required")
        ->required();
    cmd->add_option("--distance", o.distance,
                    "Reinforcement distance in grid steps (1 = none; not with two-normal)")
        ->capture_default_str();
    cmd->add_option("--normals", o.normals,
                    "Vertex normals of the normal methods: edge, triangle or quad")
        ->capture_default_str();
    cmd->add_option("--scale", o.scale,
                    "Factor on every value (>= 0), or 'auto': the top 5% of the samples at 1")
        ->capture_default_str();
    cmd->add_flag("--signed", o.signedValues, "Keep the sign of y'' (negative = convex, a ridge)");
    cmd->add_option("--device", o.device,
                    "cpu (the multithreaded reference) or gpu (the compute shader)")
        ->capture_default_str();
    cmd->add_option("--out", o.out, "Output .npy, float32 (rows, cols, 4); required")->required();
    cmd->add_option("--png", o.png,
                    "Also write the Figure 2 image: the largest value per sample as intensity");
    cmd->callback([state] {
        asUsage([&] { state->sceneOptions->apply(); });
        if (state->sceneOptions->printConfigRequested()) return;
        runCurvature(state->options);
    });
}

}  // namespace sierra::apps
