#pragma once
// Subcommands of sierra-bench. Each adds itself to the app; its callback
// throws sierra::Error on bad input (main prints it and exits non-zero).

#include <CLI/CLI.hpp>

namespace sierra::apps {

// sierra-bench static: the fixed-error SBT mesh of one heightfield (see StaticCommand.cpp).
void addStaticCommand(CLI::App& app);

// sierra-bench frames: per-frame, per-stage timings along a camera path.
void addFramesCommand(CLI::App& app);

}  // namespace sierra::apps
