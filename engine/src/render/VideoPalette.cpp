#include "render/VideoPalette.h"

#include <sierra/core/Error.h>

#include <algorithm>
#include <array>

namespace sierra::render::detail {
namespace {

constexpr int kBins = 32 * 32 * 32;  // 5 bits per channel

int binOf(int r, int g, int b) {
    return ((r >> 3) << 10) | ((g >> 3) << 5) | (b >> 3);
}

int channel(int bin, int c) {  // 0..31 for channel c (0 = r) of a bin
    return (bin >> (10 - 5 * c)) & 31;
}

// A box of the colour cube: the occupied bins it holds, [begin, end) of `bins`.
struct Box {
    size_t begin = 0, end = 0;
    uint64_t pixels = 0;
    int axis = 0;    // the channel of greatest extent
    int extent = 0;  // that extent, 0..31
};

void measure(Box& box, const std::vector<int>& bins) {
    int lo[3] = {31, 31, 31}, hi[3] = {0, 0, 0};
    for (size_t k = box.begin; k < box.end; ++k)
        for (int c = 0; c < 3; ++c) {
            lo[c] = std::min(lo[c], channel(bins[k], c));
            hi[c] = std::max(hi[c], channel(bins[k], c));
        }
    box.axis = 0;
    for (int c = 1; c < 3; ++c)
        if (hi[c] - lo[c] > hi[box.axis] - lo[box.axis]) box.axis = c;
    box.extent = hi[box.axis] - lo[box.axis];
}

// 8x8 Bayer matrix, thresholds 0..63.
constexpr std::array<uint8_t, 64> kBayer = {
    0,  32, 8,  40, 2,  34, 10, 42, 48, 16, 56, 24, 50, 18, 58, 26, 12, 44, 4,  36, 14, 46,
    6,  38, 60, 28, 52, 20, 62, 30, 54, 22, 3,  35, 11, 43, 1,  33, 9,  41, 51, 19, 59, 27,
    49, 17, 57, 25, 15, 47, 7,  39, 13, 45, 5,  37, 63, 31, 55, 23, 61, 29, 53, 21};

}  // namespace

GifPalette::GifPalette(const uint8_t* rgba, int width, int height, int colours)
    : argb_(256, 0xFF000000u), lut_(kBins, 0) {
    SIERRA_CHECK(colours >= 2 && colours <= 256, "GIF palette size ", colours, " is not 2..256");
    std::vector<uint64_t> count(kBins, 0);
    for (size_t p = 0, n = size_t(width) * size_t(height); p < n; ++p)
        ++count[size_t(binOf(rgba[p * 4], rgba[p * 4 + 1], rgba[p * 4 + 2]))];
    std::vector<int> bins;
    for (int b = 0; b < kBins; ++b)
        if (count[size_t(b)] > 0) bins.push_back(b);
    // Median cut: split the box that holds the most pixels (and can still be
    // split) along its longest axis, at the pixel median, until there are
    // `colours` boxes.
    std::vector<Box> boxes{{.begin = 0, .end = bins.size(), .pixels = uint64_t(width) * height}};
    measure(boxes[0], bins);
    while (int(boxes.size()) < colours) {
        Box* widest = nullptr;
        for (Box& b : boxes)
            if (b.extent > 0 && (!widest || b.pixels > widest->pixels)) widest = &b;
        if (!widest) break;
        Box box = *widest;
        const int axis = box.axis;
        std::sort(bins.begin() + long(box.begin), bins.begin() + long(box.end),
                  [&](int a, int b) { return channel(a, axis) < channel(b, axis); });
        uint64_t half = 0;
        size_t cut = box.begin;
        while (cut + 1 < box.end && half + count[size_t(bins[cut])] <= box.pixels / 2)
            half += count[size_t(bins[cut++])];
        if (cut == box.begin) half += count[size_t(bins[cut++])];
        Box low{.begin = box.begin, .end = cut, .pixels = half};
        Box high{.begin = cut, .end = box.end, .pixels = box.pixels - half};
        measure(low, bins);
        measure(high, bins);
        *widest = low;
        boxes.push_back(high);
    }
    // Each entry: the pixel-weighted mean of its box, at the bins' centres.
    for (const Box& box : boxes) {
        double sum[3] = {0, 0, 0};
        uint64_t pixels = 0;
        for (size_t k = box.begin; k < box.end; ++k) {
            const uint64_t n = count[size_t(bins[k])];
            for (int c = 0; c < 3; ++c) sum[c] += double(n) * (channel(bins[k], c) * 8 + 4);
            pixels += n;
        }
        uint32_t rgb[3] = {0, 0, 0};
        for (int c = 0; c < 3; ++c)
            rgb[c] = pixels ? uint32_t(std::clamp(sum[c] / double(pixels) + 0.5, 0.0, 255.0)) : 0;
        argb_[size_t(size_)] = 0xFF000000u | (rgb[0] << 16) | (rgb[1] << 8) | rgb[2];
        ++size_;
    }
    if (size_ == 0) size_ = 1;  // an empty frame: one black entry
    // Every bin's nearest entry, also for colours the first frame lacks.
    for (int b = 0; b < kBins; ++b) {
        const int r = channel(b, 0) * 8 + 4, g = channel(b, 1) * 8 + 4, bl = channel(b, 2) * 8 + 4;
        int best = 0, bestDistance = 1 << 30;
        for (int k = 0; k < size_; ++k) {
            const int dr = r - int((argb_[size_t(k)] >> 16) & 255);
            const int dg = g - int((argb_[size_t(k)] >> 8) & 255);
            const int db = bl - int(argb_[size_t(k)] & 255);
            const int d = 2 * dr * dr + 4 * dg * dg + db * db;  // green counts most to the eye
            if (d < bestDistance) bestDistance = d, best = k;
        }
        lut_[size_t(b)] = uint8_t(best);
    }
}

void GifPalette::map(const uint8_t* rgba, int width, int height, uint8_t* out, int stride) const {
    for (int y = 0; y < height; ++y) {
        const uint8_t* row = rgba + size_t(y) * size_t(width) * 4;
        uint8_t* dst = out + size_t(y) * size_t(stride);
        for (int x = 0; x < width; ++x) {
            // Dither of -8..+7.75 levels: a palette step of a smooth sky spreads
            // into a fine pattern rather than a band.
            const int d = int(kBayer[size_t((y & 7) * 8 + (x & 7))]) / 4 - 8;
            auto c = [&](int k) { return std::clamp(int(row[x * 4 + k]) + d, 0, 255); };
            dst[x] = lut_[size_t(binOf(c(0), c(1), c(2)))];
        }
    }
}

}  // namespace sierra::render::detail
