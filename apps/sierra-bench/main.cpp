// sierra-bench: measurements of Sierra's pipeline as programs, not tests.
//   sierra-bench static ...   fixed-error SBT mesh: size, strip efficiency, extraction speed
//   sierra-bench frames ...   frames along a camera path: per-stage times, PSNR against the full grid

#include "Commands.h"

#include <sierra/core/Error.h>

#include <cstdio>

int main(int argc, char** argv) {
    CLI::App app{"sierra-bench: benchmarks of Sierra's SBT extraction and frame pipeline"};
    app.require_subcommand(1);
    sierra::apps::addStaticCommand(app);
    sierra::apps::addFramesCommand(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "sierra-bench: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
