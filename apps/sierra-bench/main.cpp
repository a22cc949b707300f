// sierra-bench: measurements of Sierra's pipeline as programs, not tests.
//   sierra-bench static ...   fixed-error SBT mesh: size, strip efficiency, extraction speed
//   sierra-bench frames ...   frames along a camera path: per-stage times, PSNR against the full grid

#include "Commands.h"

#include "AppMain.h"

#include <cstdio>

int main(int argc, char** argv) {
    CLI::App app{"Benchmarks of Sierra's SBT extraction and frame pipeline", "sierra-bench"};
    app.require_subcommand(1);
    sierra::apps::addStaticCommand(app);
    sierra::apps::addFramesCommand(app);
    // The subcommands do their work in their callbacks, during parsing.
    return sierra::apps::runMain(app, argc, argv, nullptr, nullptr);
}
