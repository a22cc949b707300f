// sierra-gen: offline generators of Sierra's data (no GL).
//   sierra-gen zones ...   zone map -> vectorised borderlines (JSON, SVG), optionally the map itself
//   sierra-gen tiles ...   procedural seamless surface tiles (PNG)
//
// Exit status: 0 done, 1 an error (bad file, failed write), 2 a usage error.

#include "Commands.h"

#include <cstdio>
#include <exception>

int main(int argc, char** argv) {
    CLI::App app{"sierra-gen: offline generators for Sierra (zone borderlines, surface tiles)"};
    app.require_subcommand(1);
    sierra::apps::addZonesCommand(app);
    sierra::apps::addTilesCommand(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "sierra-gen: error: %s\nRun with --help for usage.\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "sierra-gen: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
