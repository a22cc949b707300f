#include <sierra/render/Scene.h>

#include <sierra/core/Error.h>
#include <sierra/terrain/DiamondSquare.h>
#include <sierra/terrain/HeightfieldIO.h>
#include <sierra/terrain/Padding.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>

namespace sierra::render {

std::pair<int, int> parseFrameSize(const std::string& text, const std::string& option) {
    int w = 0, h = 0;
    char x = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') || w <= 0 ||
        h <= 0 || w > 16384 || h > 16384)
        throw Error(msg(option, " '", text, "': expected WIDTHxHEIGHT, each 1..16384, e.g. 1920x1080"));
    return {w, h};
}

terrain::Heightfield loadTerrain(const TerrainSource& source, std::string* description) {
    terrain::Heightfield field;
    std::string what;
    bool metric = false;
    if (source.heightmap.empty()) {
        field = terrain::generateDiamondSquare(
            {.size = source.generateSize, .seed = source.seed, .roughness = source.roughness});
        what = msg("diamond-square ", source.generateSize, "x", source.generateSize, ", seed ", source.seed,
                   ", roughness ", source.roughness);
    } else {
        field = terrain::loadHeightfield(source.heightmap,
                                         {.rawWidth = source.rawWidth, .rawHeight = source.rawHeight});
        std::string ext = std::filesystem::path(source.heightmap).extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
        // SRTM and GeoTIFF carry metres: their loaders set the ground spacing,
        // and heights need no exaggeration.
        metric = ext == ".hgt" || ext == ".tif" || ext == ".tiff";
        what = msg(source.heightmap, " (", field.width(), "x", field.height(), ")");
    }
    int originalWidth = field.width(), originalHeight = field.height();
    field = terrain::padToPowerOfTwoPlusOne(field);
    if (field.width() != originalWidth || field.height() != originalHeight)
        what += msg(", padded to ", field.width(), "x", field.height());

    if (source.spacing > 0.0f) field.setSpacing(source.spacing, source.spacing);
    float spacing = std::max(field.spacingX(), field.spacingZ());
    float scale = source.verticalScale;
    if (scale <= 0.0f) {
        if (metric) {
            scale = 1.0f;
        } else {
            auto [lo, hi] = field.range();
            float extent = float(std::max(originalWidth, originalHeight) - 1) * spacing;
            scale = hi > lo ? 0.2f * extent / (hi - lo) : 1.0f;
        }
    }
    field.setVerticalScale(scale);
    what += msg(", spacing ", field.spacingX(), "x", field.spacingZ(), ", vertical scale ", scale);
    if (description) *description = what;
    return field;
}

}  // namespace sierra::render
