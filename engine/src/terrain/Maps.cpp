#include <sierra/terrain/Maps.h>

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/core/Progress.h>

#include <stb/stb_image_write.h>

// The digits and letters of legends: a small vector font of quads, header-only.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wold-style-cast"
#pragma GCC diagnostic ignored "-Wcast-qual"
#include <stb/stb_easy_font.h>
#pragma GCC diagnostic pop

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace sierra::terrain {
namespace {

void appendBytes(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<uint8_t>*>(context);
    auto* p = static_cast<const uint8_t*>(data);
    out->insert(out->end(), p, p + size);
}

std::string tickLabel(double value, double step) {
    const int decimals = step >= 1.0 ? 0 : int(std::ceil(-std::log10(step) - 1e-9));
    if (std::abs(value) < step * 1e-6) value = 0.0;  // no "-0"
    return fixed(value, decimals);
}

}  // namespace

bool parseMapScheme(const std::string& name, MapScheme* out) {
    MapScheme scheme;
    if (name == "plasma")
        scheme = MapScheme::Plasma;
    else if (name == "atlas")
        scheme = MapScheme::Atlas;
    else if (name == "hypsometric")
        scheme = MapScheme::Hypsometric;
    else
        return false;
    if (out) *out = scheme;
    return true;
}

RgbImage renderMap(const Heightfield& field, const ColourRamp& ramp) {
    SIERRA_CHECK(!field.empty(), "cannot draw a map of an empty heightfield");
    RgbImage image{field.width(), field.height(),
                   std::vector<uint8_t>(size_t(field.sampleCount()) * 3)};
    for (int j = 0; j < field.height(); ++j)
        for (int i = 0; i < field.width(); ++i)
            image.set(i, j,
                      field.valid(i, j) ? ramp.colourAt(field.at(i, j)) : ramp.noDataColour());
    return image;
}

RgbImage colourField(int width, int height, std::span<const float> values, const ColourRamp& ramp) {
    SIERRA_CHECK(width > 0 && height > 0 && values.size() == size_t(width) * size_t(height), "a ",
                 width, "x", height, " map needs ", int64_t(width) * height, " values, got ",
                 values.size());
    RgbImage image{width, height, std::vector<uint8_t>(values.size() * 3)};
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const float v = values[size_t(y) * size_t(width) + size_t(x)];
            image.set(x, y, std::isnan(v) ? ramp.noDataColour() : ramp.colourAt(v));
        }
    return image;
}

float finiteQuantile(std::span<const float> values, double share) {
    SIERRA_CHECK(share >= 0.0 && share <= 1.0, "a quantile needs a share in [0, 1], got ", share);
    std::vector<float> finite;
    finite.reserve(values.size());
    for (float v : values)
        if (std::isfinite(v)) finite.push_back(v);
    if (finite.empty()) return 0.0f;
    auto nth = finite.begin() +
               std::ptrdiff_t(std::min(finite.size() - 1, size_t(double(finite.size()) * share)));
    std::nth_element(finite.begin(), nth, finite.end());
    return *nth;
}

RgbImage shadedRelief(const Heightfield& field, const ColourRamp& tints,
                      std::span<const float> hillshade, std::span<const float> skyView,
                      const ReliefDesc& desc) {
    SIERRA_CHECK(!field.empty(), "cannot draw a relief of an empty heightfield");
    const size_t n = size_t(field.sampleCount());
    SIERRA_CHECK(hillshade.size() == n && skyView.size() == n, "shaded relief: ", n,
                 " samples need as many hillshade and sky-view values, got ", hillshade.size(),
                 " and ", skyView.size());
    SIERRA_CHECK(desc.flatShade > 0.0f && desc.shadeWeight >= 0.0f && desc.shadeWeight <= 1.0f &&
                     desc.skyWeight >= 0.0f && desc.skyWeight <= 1.0f && desc.skyFloor >= 0.0f &&
                     desc.skyFloor < 1.0f,
                 "shaded relief: flatShade > 0, weights in 0..1 and skyFloor in 0..1, got ",
                 desc.flatShade, ", ", desc.shadeWeight, ", ", desc.skyWeight, ", ", desc.skyFloor);
    RgbImage image{field.width(), field.height(), std::vector<uint8_t>(n * 3)};
    for (int j = 0; j < field.height(); ++j)
        for (int i = 0; i < field.width(); ++i) {
            const size_t k = size_t(j) * size_t(field.width()) + size_t(i);
            if (!field.valid(i, j)) {
                image.set(i, j, tints.noDataColour());
                continue;
            }
            const Rgb tint = tints.colourAt(field.at(i, j));
            // Light relative to flat ground: 1 on the flat, above on the lit side.
            const float shade = std::isnan(hillshade[k]) ? desc.flatShade : hillshade[k];
            const float light = 1.0f + desc.shadeWeight * (shade / desc.flatShade - 1.0f);
            const float sky =
                std::isnan(skyView[k])
                    ? 1.0f
                    : std::clamp((skyView[k] - desc.skyFloor) / (1.0f - desc.skyFloor), 0.0f, 1.0f);
            const float open = 1.0f - desc.skyWeight * (1.0f - sky);
            // Shadows lean blue-grey and lit slopes warm, as in hand-drawn relief.
            const float dark = std::max(0.0f, 1.0f - light);
            const float lit = std::max(0.0f, light - 1.0f);
            const float mix[3] = {1.0f - 0.35f * dark + 0.08f * lit,
                                  1.0f - 0.18f * dark + 0.03f * lit,
                                  1.0f + 0.12f * dark - 0.12f * lit};
            const float base[3] = {float(tint.r), float(tint.g), float(tint.b)};
            uint8_t out[3];
            for (int c = 0; c < 3; ++c)
                out[c] =
                    uint8_t(std::lround(std::clamp(base[c] * light * open * mix[c], 0.0f, 255.0f)));
            image.set(i, j, {out[0], out[1], out[2]});
        }
    return image;
}

int drawText(RgbImage& image, int x, int y, const std::string& text, Rgb colour, int scale) {
    // A glyph is up to ~12 quads of 4 vertices of 16 bytes: 1 KiB per
    // character is ample (the font silently drops quads that do not fit).
    std::vector<char> vertices(text.size() * 1024 + 1024);
    std::string copy = text;
    const int quads = stb_easy_font_print(0.0f, 0.0f, copy.data(), nullptr, vertices.data(),
                                          int(vertices.size()));
    struct Vertex {
        float x, y, z;
        unsigned char rgba[4];
    };
    const auto* v = reinterpret_cast<const Vertex*>(vertices.data());
    for (int q = 0; q < quads; ++q) {
        float x0 = v[4 * q].x, y0 = v[4 * q].y, x1 = x0, y1 = y0;
        for (int k = 1; k < 4; ++k) {
            x0 = std::min(x0, v[4 * q + k].x), x1 = std::max(x1, v[4 * q + k].x);
            y0 = std::min(y0, v[4 * q + k].y), y1 = std::max(y1, v[4 * q + k].y);
        }
        for (int py = y + int(y0) * scale; py < y + int(y1) * scale; ++py)
            for (int px = x + int(x0) * scale; px < x + int(x1) * scale; ++px)
                if (px >= 0 && py >= 0 && px < image.width && py < image.height)
                    image.set(px, py, colour);
    }
    return stb_easy_font_width(copy.data()) * scale;
}

std::vector<LegendTick> addColourBar(RgbImage& image, const ColourRamp& ramp, float unitScale,
                                     const std::string& units, int* barXOut) {
    SIERRA_CHECK(image.width > 0 && image.height > 0, "cannot add a colour bar to an empty image");
    SIERRA_CHECK(std::isfinite(unitScale) && unitScale > 0.0f,
                 "legend unit scale must be > 0, got ", unitScale);
    const int h = image.height;
    const int scale = std::max(1, h / 200);  // font pixels: ~7 per line at scale 1
    const double lo = ramp.desc().minHeight, hi = ramp.desc().maxHeight;
    const double loU = lo * unitScale, hiU = hi * unitScale;

    // "Nice" step: 1, 2 or 5 times a power of ten, about 5 ticks over the range.
    const double raw = (hiU - loU) / 5.0;
    const double p10 = std::pow(10.0, std::floor(std::log10(raw)));
    const double m = raw / p10;
    const double step = (m < 1.5 ? 1.0 : m < 3.5 ? 2.0 : m < 7.5 ? 5.0 : 10.0) * p10;
    std::vector<LegendTick> ticks;
    for (double v = std::ceil(loU / step - 1e-9) * step; v <= hiU + step * 1e-9; v += step) {
        const int row = int(std::lround((hiU - v) / (hiU - loU) * (h - 1)));
        ticks.push_back({v, std::clamp(row, 0, h - 1), tickLabel(v, step)});
    }
    if (!units.empty() && !ticks.empty()) ticks.back().label += " " + units;

    const int gap = std::max(2, image.width / 50);
    const int bar = std::max(8, image.width / 16);
    const int tick =
        3 * scale;  // drawn from inside the bar out, then a gap: not read as a minus sign
    int labelWidth = 0;
    for (auto& t : ticks) {
        std::string s = t.label;
        labelWidth = std::max(labelWidth, stb_easy_font_width(s.data()) * scale);
    }
    const int barX = image.width + gap;
    // The font's width leaves out the last glyph's right edge: a margin of 6.
    const int width = barX + bar + tick + 3 * scale + labelWidth + 6 * scale;
    RgbImage out{width, h, std::vector<uint8_t>(size_t(width) * h * 3, 255)};
    for (int y = 0; y < h; ++y) {
        std::copy_n(image.rgb.data() + size_t(y) * image.width * 3, size_t(image.width) * 3,
                    out.rgb.data() + size_t(y) * width * 3);
        const double t = h > 1 ? double(y) / double(h - 1) : 0.0;
        const Rgb c = ramp.colourAt(float(hi - (hi - lo) * t));  // top row = maxHeight
        for (int x = barX; x < barX + bar; ++x) out.set(x, y, c);
    }
    constexpr Rgb kInk{0, 0, 0};
    const int textHeight = 7 * scale;
    for (const auto& t : ticks) {
        for (int x = barX + bar - bar / 3; x < barX + bar + tick; ++x)
            for (int y = t.row; y < std::min(h, t.row + std::max(1, scale / 2)); ++y)
                out.set(x, y, kInk);
        const int ty = std::clamp(t.row - textHeight / 2, 0, std::max(0, h - textHeight));
        drawText(out, barX + bar + tick + 3 * scale, ty, t.label, kInk, scale);
    }
    image = std::move(out);
    if (barXOut) *barXOut = barX;
    return ticks;
}

void writeRgbPng(const std::string& path, const RgbImage& image) {
    SIERRA_CHECK(image.width > 0 && image.height > 0, "cannot write ", path,
                 ": the image is empty");
    std::vector<uint8_t> png;
    if (!stbi_write_png_to_func(appendBytes, &png, image.width, image.height, 3, image.rgb.data(),
                                image.width * 3))
        throw Error(msg("cannot write ", path, ": PNG encoding failed for a ", image.width, "x",
                        image.height, " image"));
    writeFileAtomic(path, png);
}

void writeGreyPng(const std::string& path, int width, int height, std::span<const uint8_t> grey) {
    SIERRA_CHECK(width > 0 && height > 0 && grey.size() == size_t(width) * size_t(height),
                 "cannot write ", path, ": a ", width, "x", height, " grey image needs ",
                 int64_t(width) * height, " bytes, got ", grey.size());
    std::vector<uint8_t> png;
    if (!stbi_write_png_to_func(appendBytes, &png, width, height, 1, grey.data(), width))
        throw Error(msg("cannot write ", path, ": PNG encoding failed for a ", width, "x", height,
                        " image"));
    writeFileAtomic(path, png);
}

}  // namespace sierra::terrain
