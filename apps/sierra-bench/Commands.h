#pragma once
// The subcommands of sierra-bench, each registering itself on the app.

#include <CLI/CLI.hpp>

namespace sierra::apps {

// `static`: the fixed-error SBT mesh of a heightfield (no GL).
void addStaticCommand(CLI::App& app);
// `tiled`: a fly-through of a tiled terrain file: refinement and streaming (no GL).
void addTiledCommand(CLI::App& app);
// `frames`: view-dependent frames along a camera path, timed per stage.
void addFramesCommand(CLI::App& app);
// `facade`: whole renders of a scene through facade::SceneRenderer, timed.
void addFacadeCommand(CLI::App& app);

}  // namespace sierra::apps
