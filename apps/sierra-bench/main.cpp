// sierra-bench: measurements of Sierra's pipeline as programs, not tests.
//   sierra-bench static ...   fixed-error SBT mesh: size, strip efficiency, extraction speed
//   sierra-bench tiled ...    a fly-through of a tiled terrain: refinement and streaming
//   sierra-bench frames ...   frames along a camera path: per-stage times, PSNR against the full
//   grid
//   sierra-bench facade ...   whole renders of a scene through the SceneRenderer facade
//
// One source, two executables: `sierra-bench` itself links no GL (static needs
// none), and hands `frames` and `facade` to `sierra-bench-frames` beside it, which links the
// renderer. Built with SIERRA_BENCH_FRAMES it is that second program.

#include "Commands.h"

#include "AppMain.h"

#include <cstdio>
#include <string_view>

int main(int argc, char** argv) {
    CLI::App app{"Benchmarks of Sierra's SBT extraction and frame pipeline", "sierra-bench"};
    app.require_subcommand(1);
#ifdef SIERRA_BENCH_FRAMES
    sierra::apps::addFramesCommand(app);
    sierra::apps::addFacadeCommand(app);
#else
    if (argc > 1 &&
        (std::string_view(argv[1]) == "frames" || std::string_view(argv[1]) == "facade")) {
        try {
            sierra::apps::execBeside("sierra-bench-frames", argc, argv);
        } catch (const sierra::Error& e) {
            std::fprintf(stderr, "sierra-bench: error: %s: %s\n", argv[1], e.what());
            return sierra::apps::kExitRuntime;
        }
    }
    sierra::apps::addStaticCommand(app);
    sierra::apps::addTiledCommand(app);
    // Listed for --help; its options are the frames program's own.
    app.add_subcommand("frames",
                       "Time view-dependent frames along a camera path (EGL; `frames --help`)")
        ->allow_extras();
    app.add_subcommand("facade",
                       "Time whole renders of a scene through the SceneRenderer facade (EGL; "
                       "`facade --help`)")
        ->allow_extras();
#endif
    // The subcommands do their work in their callbacks, during parsing.
    return sierra::apps::runMain(app, argc, argv, nullptr, nullptr);
}
