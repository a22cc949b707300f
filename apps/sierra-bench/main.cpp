// sierra-bench: measurements of Sierra's pipeline as programs, not tests.
//   sierra-bench static ...   fixed-error SBT mesh: size, strip efficiency, extraction speed
//   sierra-bench frames ...   frames along a camera path: per-stage times, PSNR against the full grid
//
// One source, two executables: `sierra-bench` itself links no GL (static needs
// none), and hands `frames` to `sierra-bench-frames` beside it, which links the
// renderer. Built with SIERRA_BENCH_FRAMES it is that second program.

#include "Commands.h"

#include "AppMain.h"

#ifndef SIERRA_BENCH_FRAMES
#include <sierra/core/Error.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>
#endif

namespace {

#ifndef SIERRA_BENCH_FRAMES
constexpr const char* kFramesProgram = "sierra-bench-frames";

// Replaces this process with the GL program beside it, passing the arguments
// on unchanged; returns only when that program cannot be started.
int execFrames(int argc, char** argv) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    const fs::path program = (ec ? fs::path(argv[0]).parent_path() : self.parent_path()) / kFramesProgram;
    std::vector<char*> args(argv, argv + argc);
    args.push_back(nullptr);
    ::execv(program.c_str(), args.data());
    const int code = errno;
    std::fprintf(stderr, "sierra-bench: error: frames runs %s, which cannot be started (%s)\n",
                 program.c_str(), std::strerror(code));
    return sierra::apps::kExitRuntime;
}
#endif

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Benchmarks of Sierra's SBT extraction and frame pipeline", "sierra-bench"};
    app.require_subcommand(1);
#ifdef SIERRA_BENCH_FRAMES
    sierra::apps::addFramesCommand(app);
#else
    if (argc > 1 && std::string(argv[1]) == "frames") return execFrames(argc, argv);
    sierra::apps::addStaticCommand(app);
    // Listed for --help; its options are the frames program's own.
    app.add_subcommand("frames", "Time view-dependent frames along a camera path (EGL; `frames --help`)")
        ->allow_extras();
#endif
    // The subcommands do their work in their callbacks, during parsing.
    return sierra::apps::runMain(app, argc, argv, nullptr, nullptr);
}
