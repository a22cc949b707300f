#include <sierra/render/DrapeSurface.h>

#include <sierra/render/VectorOverlay.h>

#include "render/TextureFiltering.h"

#include <sierra/core/Error.h>
#include <sierra/core/Parallel.h>

#include <algorithm>
#include <cmath>
#include <optional>

namespace sierra::render {

namespace {

// Layer texel (x, y) of a target `width` x `height` composite: the layer's
// colour and alpha there, bilinear between its texel centres (a layer spans
// the same grid extent at its own resolution).
std::array<float, 4> sampleLayer(const terrain::DrapeImage& image, int x, int y, int width,
                                 int height) {
    const float u = std::clamp((float(x) + 0.5f) * float(image.width) / float(width) - 0.5f, 0.0f,
                               float(image.width - 1));
    const float v = std::clamp((float(y) + 0.5f) * float(image.height) / float(height) - 0.5f, 0.0f,
                               float(image.height - 1));
    const int x0 = int(u), y0 = int(v);
    const int x1 = std::min(x0 + 1, image.width - 1), y1 = std::min(y0 + 1, image.height - 1);
    const float fu = u - float(x0), fv = v - float(y0);
    std::array<float, 4> out{};
    auto at = [&](int px, int py, int c) {
        return float(image.rgba[(size_t(py) * size_t(image.width) + size_t(px)) * 4 + size_t(c)]);
    };
    for (int c = 0; c < 4; ++c)
        out[size_t(c)] =
            ((1.0f - fu) * (1.0f - fv) * at(x0, y0, c) + fu * (1.0f - fv) * at(x1, y0, c) +
             (1.0f - fu) * fv * at(x0, y1, c) + fu * fv * at(x1, y1, c)) /
            255.0f;
    return out;
}

uint8_t unorm(float v) {
    return uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
}

class DrapeSurface final : public Surface {
  public:
    // `multiplier` absent: replace layers only, `added` premultiplied with
    // alpha = 1 - the multiplier (surface_drape.glsl).
    DrapeSurface(std::unique_ptr<Surface> base, gpu::Texture added,
                 std::optional<gpu::Texture> multiplier, std::optional<gpu::Texture> lines = {})
        : base_(std::move(base)),
          added_(std::move(added)),
          multiplier_(std::move(multiplier)),
          lines_(std::move(lines)) {}
    std::string shaderFile() const override { return "surface_drape.glsl"; }
    std::string baseShaderFile() const override { return base_->shaderFile(); }
    std::string defines() const override {
        return base_->defines() + (multiplier_ ? "#define SIERRA_DRAPE_MULTIPLY 1\n" : "") +
               (lines_ ? "#define SIERRA_DRAPE_LINES 1\n" : "");
    }
    bool lit() const override { return base_->lit(); }
    // bind() binds the base's textures and blocks, its zone field among them.
    bool zoneIds() const override { return base_->zoneIds(); }
    void bind() const override {
        base_->bind();
        glBindTextureUnit(9, added_.id());
        if (multiplier_) glBindTextureUnit(8, multiplier_->id());
        if (lines_) glBindTextureUnit(10, lines_->id());
    }

  private:
    std::unique_ptr<Surface> base_;
    gpu::Texture added_;
    std::optional<gpu::Texture> multiplier_;
    std::optional<gpu::Texture> lines_;
};

int mipLevels(int width, int height) {
    return 1 + int(std::floor(std::log2(double(std::max(width, height)))));
}

gpu::Texture drapeTexture(int width, int height) {
    const int limit = maxTextureSide();
    if (width > limit || height > limit)
        throw Error(msg("a drape of ", width, "x", height,
                        " texels is over this driver's texture limit of ", limit));
    return gpu::Texture::create(
        {.format = GL_RGBA8, .width = width, .height = height, .levels = mipLevels(width, height)});
}

void finish(gpu::Texture& texture) {
    texture.generateMipmaps();
    applyMipmapFiltering(texture, mipLevels(texture.width(), texture.height()));
}

gpu::Texture upload(const DrapeMaps& maps, const std::vector<uint8_t>& pixels) {
    gpu::Texture texture = drapeTexture(maps.width, maps.height);
    texture.upload(GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
    finish(texture);
    return texture;
}

bool replaceOnly(std::span<const DrapeLayer> layers) {
    for (const DrapeLayer& layer : layers)
        if (layer.blend != DrapeBlend::Replace) return false;
    return true;
}

}  // namespace

DrapeMaps composeDrapes(std::span<const DrapeLayer> layers) {
    SIERRA_CHECK(!layers.empty(), "composeDrapes needs at least one layer");
    DrapeMaps maps;
    for (const DrapeLayer& layer : layers) {
        SIERRA_CHECK(layer.image && layer.image->width > 0 && layer.image->height > 0 &&
                         layer.image->rgba.size() ==
                             size_t(layer.image->width) * size_t(layer.image->height) * 4,
                     "a drape layer needs an image");
        SIERRA_CHECK(layer.opacity >= 0.0f && layer.opacity <= 1.0f,
                     "a drape's opacity is 0..1, got ", layer.opacity);
        maps.width = std::max(maps.width, layer.image->width);
        maps.height = std::max(maps.height, layer.image->height);
    }
    maps.replaceOnly = replaceOnly(layers);
    const size_t texels = size_t(maps.width) * size_t(maps.height);
    maps.multiplier.assign(texels * 4, 255);
    maps.added.assign(texels * 4, maps.replaceOnly ? 0 : 255);
    parallelFor(0, maps.height, [&](int64_t row) {
        const int y = int(row);
        for (int x = 0; x < maps.width; ++x) {
            // c -> c * m + a, composed layer after layer.
            float m[3] = {1.0f, 1.0f, 1.0f}, a[3] = {0.0f, 0.0f, 0.0f};
            for (const DrapeLayer& layer : layers) {
                const auto s = sampleLayer(*layer.image, x, y, maps.width, maps.height);
                const float alpha = s[3] * layer.opacity;
                for (int c = 0; c < 3; ++c) {
                    // Replace: c (1 - alpha) + alpha L. Multiply: c (1 - alpha + alpha L).
                    const float lm = layer.blend == DrapeBlend::Replace
                                         ? 1.0f - alpha
                                         : 1.0f - alpha + alpha * s[size_t(c)];
                    const float la =
                        layer.blend == DrapeBlend::Replace ? alpha * s[size_t(c)] : 0.0f;
                    m[c] *= lm;
                    a[c] = a[c] * lm + la;
                }
            }
            const size_t k = (size_t(y) * size_t(maps.width) + size_t(x)) * 4;
            for (int c = 0; c < 3; ++c) {
                maps.multiplier[k + size_t(c)] = unorm(m[c]);
                maps.added[k + size_t(c)] = unorm(a[c]);
            }
            // Replace layers alone leave a grey multiplier: its complement is alpha.
            if (maps.replaceOnly) maps.added[k + 3] = unorm(1.0f - m[0]);
        }
    });
    return maps;
}

int maxTextureSide() {
    GLint side = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &side);
    return int(side);
}

// The far lines' texture, each level uploaded as rasterised; none without lines.
std::optional<gpu::Texture> lineTextureOf(const LinePyramid* lines) {
    if (!lines) return std::nullopt;
    const int levels = int(lines->levels.size());
    SIERRA_CHECK(
        levels >= 1 && lines->width <= maxTextureSide() && lines->height <= maxTextureSide(),
        "the vector lines' texture of ", lines->width, "x", lines->height,
        " texels does not fit this driver");
    gpu::Texture texture = gpu::Texture::create(
        {.format = GL_RGBA8, .width = lines->width, .height = lines->height, .levels = levels});
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    for (int l = 0; l < levels; ++l)
        glTextureSubImage2D(texture.id(), l, 0, 0, lines->levelWidth(l), lines->levelHeight(l),
                            GL_RGBA, GL_UNSIGNED_BYTE, lines->levels[size_t(l)].data());
    applyMipmapFiltering(texture, levels);
    return texture;
}

std::unique_ptr<Surface> makeDrapeSurface(std::unique_ptr<Surface> base,
                                          std::span<const DrapeLayer> layers,
                                          const LinePyramid* lines) {
    SIERRA_CHECK(base != nullptr, "a drape needs a surface beneath it");
    SIERRA_CHECK(!layers.empty() || lines, "a drape needs a layer or lines");
    std::optional<gpu::Texture> lineTexture = lineTextureOf(lines);
    if (layers.empty()) {
        // Lines alone: a transparent texel stands for the drapes.
        gpu::Texture none = gpu::Texture::create({.format = GL_RGBA8});
        const uint8_t clear[4] = {0, 0, 0, 0};
        none.upload(GL_RGBA, GL_UNSIGNED_BYTE, clear);
        return std::make_unique<DrapeSurface>(std::move(base), std::move(none), std::nullopt,
                                              std::move(lineTexture));
    }
    DrapeMaps maps = composeDrapes(layers);
    gpu::Texture added = upload(maps, maps.added);
    std::optional<gpu::Texture> multiplier;
    if (!maps.replaceOnly) multiplier = upload(maps, maps.multiplier);
    return std::make_unique<DrapeSurface>(std::move(base), std::move(added), std::move(multiplier),
                                          std::move(lineTexture));
}

std::unique_ptr<Surface> makeStreamedDrapeSurface(std::unique_ptr<Surface> base,
                                                  const std::string& path,
                                                  const terrain::DrapeOptions& options,
                                                  float opacity, terrain::DrapeImage* header,
                                                  const LinePyramid* lines) {
    SIERRA_CHECK(base != nullptr, "a drape needs a surface beneath it");
    SIERRA_CHECK(opacity >= 0.0f && opacity <= 1.0f, "a drape's opacity is 0..1, got ", opacity);
    std::optional<gpu::Texture> texture;
    std::vector<uint8_t> premultiplied;
    terrain::DrapeOptions limited = options;
    limited.maxTexels = std::min(options.maxTexels, maxTextureSide());
    // Strips of about 16 MiB: each premultiplied and uploaded as it comes.
    const auto info = terrain::readDrapeStrips(
        path, limited, size_t(16) << 20,
        [&](const terrain::DrapeImage& size) { texture = drapeTexture(size.width, size.height); },
        [&](const terrain::DrapeStrip& s) {
            premultiplied.assign(s.rgba, s.rgba + size_t(s.width) * size_t(s.rows) * 4);
            for (size_t k = 0; k < premultiplied.size(); k += 4) {
                const float a = float(premultiplied[k + 3]) / 255.0f * opacity;
                for (int c = 0; c < 3; ++c)
                    premultiplied[k + size_t(c)] =
                        unorm(float(premultiplied[k + size_t(c)]) / 255.0f * a);
                premultiplied[k + 3] = unorm(a);
            }
            glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
            glTextureSubImage2D(texture->id(), 0, 0, s.row, s.width, s.rows, GL_RGBA,
                                GL_UNSIGNED_BYTE, premultiplied.data());
        });
    finish(*texture);
    if (header) *header = info;
    return std::make_unique<DrapeSurface>(std::move(base), std::move(*texture), std::nullopt,
                                          lineTextureOf(lines));
}

}  // namespace sierra::render
