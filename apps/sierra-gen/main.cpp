// sierra-gen: offline generators of Sierra's data (no GL).
//   sierra-gen map ...     a 2D map PNG: height colours, hillshade or slope, with a colour bar
//   sierra-gen zones ...   zone map -> vectorised borderlines (JSON, SVG), optionally the map
//   itself sierra-gen tiles ...   procedural seamless surface tiles (PNG) sierra-gen curvature ...
//   the 4-direction curvature field (.npy) and its Figure 2 image (PNG)
// One source, two executables: sierra-gen links no GL; built with SIERRA_GEN_GPU
// it is sierra-gen-gpu, which sierra-gen runs for `curvature --device gpu` and for `map` with
// labels or map furniture.

#include "Commands.h"

#include "AppMain.h"

int main(int argc, char** argv) {
    CLI::App app{
        "Offline generators of Sierra's data: 2D maps, zone borderlines, surface tiles (no GL)",
        "sierra-gen"};
    app.require_subcommand(1);
#ifdef SIERRA_GEN_GPU
    // sierra-gen-gpu: the GL half of sierra-gen, run by it for `curvature --device gpu`
    // and for maps with labels or furniture.
    sierra::apps::addMapCommand(app);
    sierra::apps::addCurvatureCommand(app);
#else
    sierra::apps::addMapCommand(app);
    sierra::apps::addZonesCommand(app);
    sierra::apps::addTilesCommand(app);
    sierra::apps::addCurvatureCommand(app);
#endif
    // The subcommands do their work in their callbacks, during parsing.
    return sierra::apps::runMain(app, argc, argv, nullptr, nullptr);
}
