// sierra-gen: terrain products as files, without GL.
//   sierra-gen map ...   a 2D map PNG: height colours, hillshade or slope, with a colour bar

#include "Commands.h"

#include "AppMain.h"

int main(int argc, char** argv) {
    CLI::App app{"Terrain products of Sierra as files (no GL)", "sierra-gen"};
    app.require_subcommand(1);
    sierra::apps::addMapCommand(app);
    // The subcommands do their work in their callbacks, during parsing.
    return sierra::apps::runMain(app, argc, argv, nullptr, nullptr);
}
