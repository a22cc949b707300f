#pragma once
// The subcommands of sierra-gen, each registering itself on the app.

#include <CLI/CLI.hpp>

namespace sierra::apps {

// `map`: a 2D map PNG of a heightfield (height colours, hillshade or slope).
void addMapCommand(CLI::App& app);

}  // namespace sierra::apps
