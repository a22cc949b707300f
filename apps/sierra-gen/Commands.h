#pragma once
// The subcommands of sierra-gen, each registering itself on the app.

#include <CLI/CLI.hpp>

namespace sierra::apps {

// `map`: a 2D map PNG of a heightfield (height colours, hillshade or slope).
void addMapCommand(CLI::App& app);
// `zones`: a zone map (or auto-zoning of a heightfield) to vector borderlines (JSON, SVG).
void addZonesCommand(CLI::App& app);
// `tiles`: the procedural surface tiles as PNGs.
void addTilesCommand(CLI::App& app);

}  // namespace sierra::apps
