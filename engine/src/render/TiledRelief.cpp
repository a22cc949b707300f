#include <sierra/render/TiledRelief.h>

#include <sierra/core/Error.h>
#include <sierra/core/Log.h>
#include <sierra/core/Progress.h>
#include <sierra/core/Timer.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace sierra::render {
namespace {

// ReliefGpu's own limit on a side (its shader packs doubled indices in 16 bits).
constexpr int kReliefMaxSide = 32767;

gpu::Texture fieldTexture(int width, int height) {
    return gpu::Texture::create(
        {.format = GL_R16F, .width = width, .height = height, .filter = GL_LINEAR});
}

// A relief field into `texture`; no-data samples (NaN) are not occluded and
// see the whole sky, as the in-memory renderer draws them.
void uploadField(gpu::Texture& texture, std::vector<float> field) {
    for (float& v : field)
        if (!std::isfinite(v)) v = 1.0f;
    GLint alignment = 4;
    glGetIntegerv(GL_UNPACK_ALIGNMENT, &alignment);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    texture.upload(GL_RED, GL_FLOAT, field.data());
    glPixelStorei(GL_UNPACK_ALIGNMENT, alignment);
}

std::vector<float> readField(const gpu::Texture& texture, int width, int height) {
    std::vector<float> out(size_t(width) * size_t(height));
    if (!texture || texture.width() != width) return {};
    GLint alignment = 4;
    glGetIntegerv(GL_PACK_ALIGNMENT, &alignment);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(texture.id(), 0, GL_RED, GL_FLOAT, GLsizei(out.size() * sizeof(float)),
                      out.data());
    glPixelStorei(GL_PACK_ALIGNMENT, alignment);
    return out;
}

std::string radiusText(float radius) {
    return radius > 0.0f ? msg(radius, " world units") : std::string("the whole terrain");
}

}  // namespace

TiledRelief::TiledRelief(const sbt::TileFile& file, int maxSide) : file_(&file), maxSide_(maxSide) {
    const float one = 1.0f;
    one_ = fieldTexture(1, 1);
    one_.upload(GL_RED, GL_FLOAT, &one);
}
TiledRelief::TiledRelief(TiledRelief&&) noexcept = default;
TiledRelief& TiledRelief::operator=(TiledRelief&&) noexcept = default;
TiledRelief::~TiledRelief() = default;

void TiledRelief::readOverviewOnce() {
    if (gpu_) return;
    GLint maxTexture = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
    const int side = std::min({maxSide_, int(maxTexture), kReliefMaxSide});
    Stopwatch sw;
    const terrain::Heightfield overview = sbt::readOverview(*file_, side, 0, &stride_);
    width_ = overview.width();
    height_ = overview.height();
    spacing_ = {overview.spacingX(), overview.spacingZ()};
    gpu_ = ReliefGpu::create(overview);
    log::info("tiled terrain: shadows and sky light on an overview of ", width_, "x", height_,
              " samples (stride ", stride_, ": ", spacing_.x, " x ", spacing_.y,
              " world units apart), read in ", fixed(sw.ms(), 1), " ms");
}

double TiledRelief::prepare(const TiledReliefRequest& request) {
    if (!request.any()) return 0.0;
    const glm::vec3 d = glm::normalize(request.sunDirection);
    float azimuth = glm::degrees(std::atan2(d.x, -d.z));
    if (azimuth < 0.0f) azimuth += 360.0f;
    const float altitude = glm::degrees(std::asin(std::clamp(d.y, -1.0f, 1.0f)));
    const std::vector<float> sunKey{azimuth, altitude, request.sunSize, request.radius};
    const bool needSun = request.shadows && sunKey_ != sunKey;
    const bool needSky = request.skyLight && skyRadius_ != request.radius;
    if (!needSun && !needSky) return 0.0;
    Stopwatch total;
    readOverviewOnce();
    const analysis::HorizonOptions options{.radius = request.radius};
    const analysis::SunDisc sun{
        .azimuth = azimuth, .altitude = altitude, .diameter = request.sunSize};
    const bool sunUp = altitude + 0.5f * request.sunSize > 0.0f;
    bool sunDone = false;
    if (needSky) {
        // The horizons of every azimuth (4 bytes a sample each) live only as
        // long as this; the sun's azimuth joins their sweep when asked for too.
        Stopwatch sw;
        ReliefGpu sky = std::move(*gpu_);
        const bool withSun = needSun && sunUp;
        if (withSun)
            sky.computeHorizonsAndSun(options, sun);
        else
            sky.computeHorizons(options);
        sky.computeSky();
        if (!sky_) sky_ = fieldTexture(width_, height_);
        uploadField(sky_, sky.readSkyLight());
        if (withSun) {
            if (!sun_) sun_ = fieldTexture(width_, height_);
            uploadField(sun_, sky.readSunVisibility());
            sunDone = true;
        }
        // The horizons go with `sky`; a later sun reads the overview again.
        gpu_.reset();
        skyRadius_ = request.radius;
        log::info("tiled terrain: sky light", withSun ? " and shadows" : "", " of ", width_, "x",
                  height_, " samples (", options.directions, " azimuths, horizon radius ",
                  radiusText(request.radius), ") in ", fixed(sw.ms(), 1), " ms");
    }
    if (needSun && !sunDone) {
        Stopwatch sw;
        if (!sun_) sun_ = fieldTexture(width_, height_);
        if (!sunUp) {
            uploadField(sun_, std::vector<float>(size_t(width_) * size_t(height_), 0.0f));
        } else {
            readOverviewOnce();
            gpu_->computeSunVisibility(sun, options);
            uploadField(sun_, gpu_->readSunVisibility());
        }
        log::info("tiled terrain: shadows of the sun at azimuth ", azimuth, ", altitude ", altitude,
                  " (", request.sunSize, " degrees wide) in ", fixed(sw.ms(), 1), " ms");
    }
    if (needSun) sunKey_ = sunKey;
    return total.ms();
}

void TiledRelief::bind(unsigned sunUnit, unsigned skyUnit) const {
    glBindTextureUnit(sunUnit, sunKey_ && sun_ ? sun_.id() : one_.id());
    glBindTextureUnit(skyUnit, skyRadius_ && sky_ ? sky_.id() : one_.id());
}

glm::vec4 TiledRelief::worldToUv() const {
    if (width_ == 0) return {0.0f, 0.0f, 0.5f, 0.5f};
    const glm::vec2 size{float(width_), float(height_)};
    return {1.0f / (spacing_.x * size.x), 1.0f / (spacing_.y * size.y), 0.5f / size.x,
            0.5f / size.y};
}

std::vector<float> TiledRelief::readSunVisibility() const {
    return sunKey_ ? readField(sun_, width_, height_) : std::vector<float>{};
}
std::vector<float> TiledRelief::readSkyLight() const {
    return skyRadius_ ? readField(sky_, width_, height_) : std::vector<float>{};
}

}  // namespace sierra::render
