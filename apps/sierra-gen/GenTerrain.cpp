#include "GenTerrain.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace sierra::apps {

terrain::Heightfield loadRealTerrain(const scene::TerrainSource& source, std::string* description) {
    terrain::Heightfield padded = scene::loadTerrain(source, description);
    if (!padded.hasMask()) return padded;
    int w = 0, h = 0;
    for (int j = 0; j < padded.height(); ++j)
        for (int i = 0; i < padded.width(); ++i)
            if (padded.valid(i, j)) w = std::max(w, i + 1), h = std::max(h, j + 1);
    if (w == 0) return padded;
    terrain::Heightfield field(w, h);
    std::vector<uint8_t> mask(size_t(w) * h);
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            field.at(i, j) = padded.at(i, j);
            mask[size_t(j) * w + i] = padded.valid(i, j) ? 1 : 0;
        }
    field.setMask(std::move(mask));
    field.setSpacing(padded.spacingX(), padded.spacingZ());
    field.setVerticalScale(padded.verticalScale());
    return field;
}

}  // namespace sierra::apps
