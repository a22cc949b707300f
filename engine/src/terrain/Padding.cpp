#include <sierra/terrain/Padding.h>

#include <algorithm>
#include <cstdio>
#include <vector>

namespace sierra::terrain {

int paddedSide(int size) {
    SIERRA_CHECK(size >= 1 && size <= 65537, "paddedSide: size ", size,
                 " is outside 1..65537 samples");
    int side = 3;
    while (side < size) side = 2 * side - 1;  // 2^n + 1 -> 2^(n+1) + 1
    return side;
}

std::string paddingWarning(int width, int height) {
    SIERRA_CHECK(width >= 1 && height >= 1, "paddingWarning: empty size ", width, "x", height);
    const int side = paddedSide(std::max(width, height));
    const double real = double(width) * double(height);
    const double padded = double(side) * double(side);
    if (padded <= kPaddingWarnRatio * real) return "";
    char ratio[32];
    std::snprintf(ratio, sizeof ratio, "%.1f", padded / real);
    return msg("a ", width, "x", height, " heightfield is padded to ", side, "x", side, " = ",
               int64_t(side) * side, " samples, ", ratio, "x its ", int64_t(width) * height,
               " real samples (the padding costs memory and refinement time but is not drawn); "
               "crop or tile it closer to a 2^n+1 square to avoid this");
}

Heightfield padToPowerOfTwoPlusOne(const Heightfield& field) {
    SIERRA_CHECK(!field.empty(), "padToPowerOfTwoPlusOne: the heightfield is empty");
    const int width = field.width(), height = field.height();
    const int side = paddedSide(std::max(width, height));
    if (width == side && height == side) return field;

    Heightfield padded(side, side);
    padded.setSpacing(field.spacingX(), field.spacingZ());
    padded.setVerticalScale(field.verticalScale());
    padded.setMetres(field.metres());
    padded.setGeoCentre(field.geoCentre());
    padded.setGeoreference(field.georeference());
    std::vector<uint8_t> mask(size_t(side) * side, 0);
    for (int j = 0; j < side; ++j) {
        const int sj = std::min(j, height - 1);
        for (int i = 0; i < side; ++i) {
            const int si = std::min(i, width - 1);
            padded.at(i, j) = field.at(si, sj);
            if (i < width && j < height) mask[size_t(j) * side + i] = field.valid(i, j) ? 1 : 0;
        }
    }
    padded.setMask(std::move(mask));
    return padded;
}

void fillNoData(Heightfield& field) {
    if (!field.hasMask()) return;
    const int width = field.width(), height = field.height();
    const auto mask = field.mask();
    // filled[k]: the sample has its final height (valid, or filled earlier).
    std::vector<uint8_t> filled(mask.begin(), mask.end());
    std::vector<int64_t> frontier, next;
    auto pushNeighbours = [&](int i, int j, std::vector<int64_t>& into,
                              std::vector<uint8_t>& queued) {
        const int di[4] = {1, -1, 0, 0}, dj[4] = {0, 0, 1, -1};
        for (int n = 0; n < 4; ++n) {
            const int x = i + di[n], z = j + dj[n];
            if (x < 0 || z < 0 || x >= width || z >= height) continue;
            const size_t k = size_t(z) * width + x;
            if (filled[k] || queued[k]) continue;
            queued[k] = 1;
            into.push_back(int64_t(k));
        }
    };
    std::vector<uint8_t> queued(filled.size(), 0);
    for (int j = 0; j < height; ++j)
        for (int i = 0; i < width; ++i)
            if (filled[size_t(j) * width + i]) pushNeighbours(i, j, frontier, queued);
    if (frontier.empty()) {
        // No valid sample (or none missing): nothing to grow from.
        for (size_t k = 0; k < filled.size(); ++k)
            if (!filled[k]) field.samples()[k] = 0.0f;
        return;
    }
    while (!frontier.empty()) {
        // Each ring reads only samples filled in earlier rings, so the result
        // does not depend on the order within a ring.
        std::vector<float> values(frontier.size());
        for (size_t n = 0; n < frontier.size(); ++n) {
            const int i = int(frontier[n] % width), j = int(frontier[n] / width);
            float sum = 0.0f;
            int count = 0;
            if (i > 0 && filled[frontier[n] - 1]) sum += field.at(i - 1, j), ++count;
            if (i + 1 < width && filled[frontier[n] + 1]) sum += field.at(i + 1, j), ++count;
            if (j > 0 && filled[frontier[n] - width]) sum += field.at(i, j - 1), ++count;
            if (j + 1 < height && filled[frontier[n] + width]) sum += field.at(i, j + 1), ++count;
            values[n] = count ? sum / float(count) : 0.0f;
        }
        for (size_t n = 0; n < frontier.size(); ++n) {
            field.samples()[frontier[n]] = values[n];
            filled[frontier[n]] = 1;
        }
        next.clear();
        for (int64_t k : frontier) pushNeighbours(int(k % width), int(k / width), next, queued);
        std::swap(frontier, next);
    }
}

}  // namespace sierra::terrain
