// sierra-bench facade: the time an embedding program pays for one frame of a
// scene through facade::SceneRenderer, as the Python module renders it: the
// renderer created for the scene on a context kept between calls (terrain
// loaded, padded and uploaded, relief fields and surface built, cameras
// placed), frame k drawn and read back. The Python module's benchmark
// (python/bench_render.py) runs this beside `sierra.Renderer.render` of the
// same scene, so the two medians come from one run.

#include "Commands.h"

#include "AppMain.h"

#include <sierra/core/Files.h>
#include <sierra/core/Timer.h>
#include <sierra/facade/SceneRenderer.h>
#include <sierra/gpu/EglContext.h>
#include <sierra/scene/Options.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace sierra::apps {
namespace {

struct FacadeOptions {
    scene::Scene scene;
    std::unique_ptr<scene::SceneOptions> registrar;
    int repeat = 5;  // timed renders after one untimed warm-up
    int frame = 0;   // the frame of the scene's path each render draws
    std::string json;
};

void runFacade(const FacadeOptions& o) {
    const scene::Scene& s = o.scene;
    auto context = std::make_shared<gpu::EglContext>(
        gpu::EglContext::create({.width = s.output.width, .height = s.output.height}));
    std::vector<double> ms;
    std::string renderer;
    for (int k = 0; k <= o.repeat; ++k) {
        Stopwatch clock;
        facade::SceneRenderer r = facade::SceneRenderer::create(s, context);
        const gpu::Image image = r.frame(o.frame);
        const double t = clock.ms();
        if (k == 0) {
            renderer = r.description();
            continue;  // the warm-up: shader compilation and first-touch costs
        }
        ms.push_back(t);
        std::printf("render %d: %.1f ms (%dx%d)\n", k, t, image.width, image.height);
    }
    const double med = median(ms);
    std::printf("median %.1f ms over %d renders; %s\n", med, o.repeat, renderer.c_str());
    if (!o.json.empty()) {
        const nlohmann::json j = {{"command", "facade"},     {"gl_renderer", context->renderer()},
                                  {"width", s.output.width}, {"height", s.output.height},
                                  {"frame", o.frame},        {"render_ms", ms},
                                  {"median_ms", med}};
        writeFileAtomic(o.json, j.dump(2) + "\n");
    }
}

}  // namespace

void addFacadeCommand(CLI::App& app) {
    auto o = std::make_shared<FacadeOptions>();
    o->scene.output.width = 1920;
    o->scene.output.height = 1080;
    o->scene.output.debug.clear();
    CLI::App* cmd = app.add_subcommand(
        "facade", "Time whole renders of a scene through the SceneRenderer facade (EGL)");
    o->registrar = std::make_unique<scene::SceneOptions>(
        *cmd, o->scene,
        scene::kTerrainOptions | scene::kCameraOptions | scene::kPathOptions |
            scene::kLightingOptions | scene::kLodOptions | scene::kStyleOptions |
            scene::kFrameOptions | scene::kZoneOptions | scene::kZoneShadingOptions);
    cmd->add_option("--repeat", o->repeat, "Timed renders, after one untimed warm-up")
        ->check(CLI::Range(1, 1000));
    cmd->add_option("--frame", o->frame, "The frame of the scene's path each render draws")
        ->check(CLI::NonNegativeNumber);
    cmd->add_option("--json", o->json, "Write the render times as JSON");
    cmd->callback([o] {
        asUsage([&] { o->registrar->apply(); });
        if (o->registrar->printConfigRequested()) return;
        runFacade(*o);
    });
}

}  // namespace sierra::apps
