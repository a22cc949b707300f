// sierra-tile: tiled SBT files (.sierra) for terrain larger than memory. No GL.
//
//   sierra-tile build INPUT... --out T.sierra [--tile-levels K] [--heights int16|float]
//                     [--vertical-scale S] [--raw-size WxH] [--threads N] [--json REPORT]
//   sierra-tile info T.sierra [--json REPORT]
//
// build streams through INPUT (a .r16, .r32 or .npy file, memory-mapped; or
// anything GDAL reads, several files mosaicked into one grid) in bounded
// memory, a band of tiles at a time, on every core, with a progress line;
// the output appears complete or not at all. info prints a file's header.

#include "AppMain.h"

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/core/Timer.h>
#include <sierra/sbt/TileFile.h>
#include <sierra/terrain/GridReader.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <nlohmann/json.hpp>

using namespace sierra;

namespace {

nlohmann::json infoJson(const sbt::TileFileInfo& info) {
    nlohmann::json j;
    j["width"] = info.width;
    j["height"] = info.height;
    j["grid_side"] = info.gridSide();
    j["n"] = info.n;
    j["tile_levels"] = info.k;
    j["tiles_per_side"] = info.tilesPerSide();
    j["heights"] = info.heights == sbt::TileHeights::Int16 ? "int16" : "float";
    j["height_scale"] = info.heightScale;
    j["height_offset"] = info.heightOffset;
    j["spacing"] = {info.spacingX, info.spacingZ};
    j["vertical_scale"] = info.verticalScale;
    j["metres"] = info.metres;
    j["no_data"] = info.hasNoData;
    if (info.geoCentre) j["geo_centre"] = {info.geoCentre->latitude, info.geoCentre->longitude};
    if (info.georeference) j["geo_transform"] = info.georeference->geoTransform;
    return j;
}

void printInfo(const sbt::TileFileInfo& info, uint64_t bytes) {
    std::printf("%lld x %lld samples in a %lld^2 grid (n = %d), %d^2 tiles of %d^2 samples\n",
                (long long)info.width, (long long)info.height, (long long)info.gridSide(), info.n,
                info.tilesPerSide(), info.tileSide());
    std::printf("heights %s", info.heights == sbt::TileHeights::Int16 ? "int16" : "float32");
    if (info.heights == sbt::TileHeights::Int16)
        std::printf(" (stored = %.9g + %.9g q)", info.heightOffset, info.heightScale);
    std::printf(", spacing %g x %g%s, vertical scale %g%s\n", info.spacingX, info.spacingZ,
                info.metres ? " m" : "", info.verticalScale,
                info.hasNoData ? ", no-data masked" : "");
    std::printf("%llu bytes, %.2f bytes a sample\n", (unsigned long long)bytes,
                double(bytes) / (double(info.width) * double(info.height)));
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"sierra-tile: tiled SBT files (.sierra) for terrain larger than memory"};
    app.require_subcommand(1);

    std::vector<std::string> inputs;
    std::string out, json, heights = "int16", rawSize;
    sbt::TileBuildOptions build;
    CLI::App* b = app.add_subcommand(
        "build", "Build a tile file from a heightmap (or several GDAL tiles, mosaicked)");
    b->add_option("inputs", inputs,
                  "Heightmap: .r16/.r32/.npy (memory-mapped) or anything GDAL reads (GeoTIFF, "
                  "COG, VRT, .hgt); several GDAL files are mosaicked")
        ->type_name("INPUT...")
        ->required();
    b->add_option("--out", out, "The tile file to write")->type_name("T.sierra")->required();
    b->add_option("--tile-levels", build.k,
                  "Tiles of 2^K cells ((2^K+1)^2 samples; at most the grid's n). Default: the "
                  "K of 4..8 that makes the smallest file (8 for large grids)")
        ->type_name("K")
        ->check(CLI::Range(1, 16));
    b->add_option(
         "--heights", heights,
         "int16: quantised over the input's range (integer inputs exactly); float: as read")
        ->type_name("int16|float")
        ->check(CLI::IsMember({"int16", "float"}))
        ->capture_default_str();
    b->add_option("--vertical-scale", build.verticalScale, "World height = stored height x S")
        ->type_name("S")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    b->add_option("--raw-size", rawSize,
                  "Samples of a .r16/.r32 file (default: a square from its size)")
        ->type_name("WxH");
    b->add_option("--threads", build.threads, "Worker threads (0 = every core)")
        ->type_name("N")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
    b->add_option("--json", json, "Write what was built to this JSON file")->type_name("REPORT");

    std::string file;
    CLI::App* info = app.add_subcommand("info", "Print a tile file's header");
    info->add_option("file", file, "The tile file")->type_name("T.sierra")->required();
    info->add_option("--json", json, "Write the header to this JSON file")->type_name("REPORT");

    terrain::GridReaderOptions readerOptions;
    return apps::runMain(
        app, argc, argv,
        [&] {
            build.heights =
                heights == "float" ? sbt::TileHeights::Float32 : sbt::TileHeights::Int16;
            if (!rawSize.empty()) {
                long long w = 0, h = 0;
                char x = 0, extra = 0;
                if (std::sscanf(rawSize.c_str(), "%lld%c%lld%c", &w, &x, &h, &extra) != 3 ||
                    (x != 'x' && x != 'X') || w < 2 || h < 2)
                    throw Error(msg("--raw-size must be WxH with W, H >= 2, got '", rawSize, "'"));
                readerOptions.rawWidth = w;
                readerOptions.rawHeight = h;
            }
        },
        [&] {
            if (*b) {
                ensureWritableLocation(out);
                if (!json.empty()) ensureWritableLocation(json);
                const auto reader = terrain::openGridReader(inputs, readerOptions);
                const auto& in = reader->info();
                std::fprintf(
                    stderr, "sierra-tile: %lld x %lld samples from %s%s\n", (long long)in.width,
                    (long long)in.height, inputs[0].c_str(),
                    inputs.size() > 1 ? msg(" and ", inputs.size() - 1, " more").c_str() : "");
                build.progress = true;
                Stopwatch timer;
                const sbt::TileBuildReport r = sbt::buildTileFile(*reader, out, build);
                const double seconds = timer.ms() / 1000.0;
                printInfo(r.info, r.fileBytes);
                std::printf("built %s in %.1f s (%lld tiles stored)\n", out.c_str(), seconds,
                            (long long)r.storedTiles);
                if (!json.empty()) {
                    nlohmann::json j = infoJson(r.info);
                    j["file_bytes"] = r.fileBytes;
                    j["bytes_per_sample"] = r.bytesPerSample;
                    j["stored_tiles"] = r.storedTiles;
                    j["seconds"] = seconds;
                    writeFileAtomic(json, j.dump(2) + "\n");
                }
                return 0;
            }
            const sbt::TileFile t(file);
            printInfo(t.info(), t.fileBytes());
            if (!json.empty()) {
                nlohmann::json j = infoJson(t.info());
                j["file_bytes"] = t.fileBytes();
                writeFileAtomic(json, j.dump(2) + "\n");
            }
            return 0;
        });
}
