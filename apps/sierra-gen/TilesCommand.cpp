// sierra-gen tiles --out DIR [--size N] [--seed S] [--only NAME...] [--sheet FILE.png]
//
// Writes DIR/<name>.png for every surface tile (grass, sand, rock, snow,
// shallow-water, deep-water, earth): RGBA8, seamless, the height for
// height-based blending in alpha. The same size and seed give the same bytes.
#include "Commands.h"

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/zones/Tiles.h>

#include <cstdio>
#include <filesystem>
#include <memory>

namespace sierra::apps {
namespace {

struct TilesOptions {
    std::string out;
    int size = 256;
    uint64_t seed = 1;
    std::vector<std::string> only;
    std::string sheet;
};

void runTiles(const TilesOptions& o) {
    std::error_code ec;
    std::filesystem::create_directories(o.out, ec);
    if (ec) throw Error(msg("tiles: cannot create ", o.out, ": ", ec.message()));
    const auto& names = o.only.empty() ? zones::tileNames() : o.only;
    std::vector<zones::TileImage> all;
    for (const std::string& name : names) {
        zones::TileImage tile = zones::generateTile(name, o.size, o.seed);
        if (!o.sheet.empty()) all.push_back(tile);
        std::string path = (std::filesystem::path(o.out) / (name + ".png")).string();
        writeFileAtomic(path, zones::encodeTilePng(tile));
        std::printf("%s: %dx%d RGBA (height in alpha)\n", path.c_str(), tile.size, tile.size);
    }
    if (!o.sheet.empty()) {
        writeFileAtomic(o.sheet, zones::encodeTileSheetPng(all));
        std::printf("%s: contact sheet (top: 2x2 repeats, bottom: heights)\n", o.sheet.c_str());
    }
}

}  // namespace

void addTilesCommand(CLI::App& app) {
    auto opts = std::make_shared<TilesOptions>();
    CLI::App* cmd = app.add_subcommand(
        "tiles", "Generate the seamless surface tiles as PNGs (RGB albedo, A height)");
    cmd->add_option("--out", opts->out, "Output folder (created if missing)")->required();
    cmd->add_option("--size", opts->size,
                    "Tile side in texels, a power of two 16..2048 (default 256)")
        ->check(CLI::Range(16, 2048));
    cmd->add_option("--seed", opts->seed, "Seed (default 1)");
    cmd->add_option(
        "--only", opts->only,
        "Only these tiles (names: grass sand rock snow shallow-water deep-water earth)");
    cmd->add_option("--sheet", opts->sheet,
                    "Also write a contact sheet PNG (2x2 repeats over heights)");
    cmd->callback([opts] { runTiles(*opts); });
}

}  // namespace sierra::apps
