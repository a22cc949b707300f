#include <sierra/render/ReliefGpu.h>

#include <sierra/analysis/ReliefLines.h>
#include <sierra/core/Error.h>
#include <sierra/gpu/GlStateScope.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace sierra::render {

namespace {

constexpr double kPi = 3.14159265358979323846;
// The shader packs doubled major and minor indices in 16 bits each.
constexpr int kMaxSide = 32767;

// The CPU's checks and lines (analysis/ReliefLines.h), so both sweep the
// same lines and refuse the same options with the same messages.
void validate(int width, int height, const analysis::HorizonOptions& o, const char* caller) {
    analysis::checkHorizonOptions(width, height, o, caller);
}
void validateDirections(const analysis::HorizonOptions& o, const char* caller) {
    analysis::checkHorizonDirections(o, caller);
}
using Lines = analysis::DigitalLines;
Lines makeLines(double degrees, double sx, double sz, int validW, int validH) {
    return analysis::digitalLines(degrees, sx, sz, validW, validH);
}
std::pair<int, int> groupSpan(const Lines& l, int o, int count) {
    return analysis::lineSpan(l, o, count);
}

// horizon.comp's Direction and Group (std430).
struct DirectionGpu {
    float steps[4];
    int32_t lines[4];
    int32_t more[4];
    float limit[4];
};
static_assert(sizeof(DirectionGpu) == 64);
struct GroupGpu {
    int32_t direction, firstLine, lines, majorBegin, majorEnd;
    uint32_t base;
    int32_t unused0, unused1;
};
static_assert(sizeof(GroupGpu) == 32);

// Image units 0 and 1 and storage buffer bindings 0..3 (not part of GlState).
class BindingScope {
  public:
    BindingScope() {
        for (GLuint u = 0; u < 2; ++u) {
            Image& s = images_[u];
            glGetIntegeri_v(GL_IMAGE_BINDING_NAME, u, &s.name);
            glGetIntegeri_v(GL_IMAGE_BINDING_LEVEL, u, &s.level);
            glGetIntegeri_v(GL_IMAGE_BINDING_LAYERED, u, &s.layered);
            glGetIntegeri_v(GL_IMAGE_BINDING_LAYER, u, &s.layer);
            glGetIntegeri_v(GL_IMAGE_BINDING_ACCESS, u, &s.access);
            glGetIntegeri_v(GL_IMAGE_BINDING_FORMAT, u, &s.format);
        }
        for (GLuint b = 0; b < 4; ++b) {
            Storage& s = storage_[b];
            glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, b, &s.name);
            glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, b, &s.start);
            glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, b, &s.size);
        }
        glGetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &generic_);
    }
    ~BindingScope() {
        for (GLuint u = 0; u < 2; ++u) {
            const Image& s = images_[u];
            glBindImageTexture(u, GLuint(s.name), s.level, GLboolean(s.layered), s.layer,
                               GLenum(s.access), GLenum(s.format));
        }
        for (GLuint b = 0; b < 4; ++b) {
            const Storage& s = storage_[b];
            if (s.name && s.size > 0)
                glBindBufferRange(GL_SHADER_STORAGE_BUFFER, b, GLuint(s.name), GLintptr(s.start),
                                  GLsizeiptr(s.size));
            else
                glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, GLuint(s.name));
        }
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, GLuint(generic_));
    }
    BindingScope(const BindingScope&) = delete;
    BindingScope& operator=(const BindingScope&) = delete;

  private:
    struct Image {
        GLint name = 0, level = 0, layered = 0, layer = 0, access = GL_READ_ONLY, format = GL_R32F;
    };
    struct Storage {
        GLint name = 0;
        GLint64 start = 0, size = 0;
    };
    std::array<Image, 2> images_;
    std::array<Storage, 4> storage_;
    GLint generic_ = 0;
};

gpu::Texture floatTexture(int width, int height, int layers) {
    gpu::Texture t = gpu::Texture::create(
        {.target = static_cast<GLenum>(layers > 0 ? GL_TEXTURE_2D_ARRAY : GL_TEXTURE_2D),
         .format = GL_R32F,
         .width = width,
         .height = height,
         .layers = layers,
         .filter = GL_NEAREST});
    const float nan = std::numeric_limits<float>::quiet_NaN();
    glClearTexImage(t.id(), 0, GL_RED, GL_FLOAT, &nan);
    return t;
}

void clearToNaN(const gpu::Texture& t) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    glClearTexImage(t.id(), 0, GL_RED, GL_FLOAT, &nan);
}

std::vector<float> readTexture(const gpu::Texture& t, size_t floats) {
    if (!t) return {};
    std::vector<float> out(floats);
    gpu::GlStateScope scope;
    GLint packBuffer = 0;  // not part of GlState
    glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &packBuffer);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(t.id(), 0, GL_RED, GL_FLOAT, GLsizei(floats * sizeof(float)), out.data());
    glBindBuffer(GL_PIXEL_PACK_BUFFER, GLuint(packBuffer));
    return out;
}

void validateSun(const analysis::SunDisc& sun) {
    analysis::checkSunDisc(sun);
}

}  // namespace

ReliefGpu ReliefGpu::create(const terrain::Heightfield& field) {
    ReliefGpu r;
    r.upload(field);
    return r;
}

void ReliefGpu::upload(const terrain::Heightfield& field) {
    SIERRA_CHECK(!field.empty(), "GPU relief: the heightfield is empty");
    GLint maxSide = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSide);
    const int limit = std::min(int(maxSide), kMaxSide);
    SIERRA_CHECK(field.width() <= limit && field.height() <= limit, "GPU relief: a ", field.width(),
                 "x", field.height(), " grid has a side beyond ", limit,
                 " samples (the driver's textures or the shader's 16-bit indices)");
    if (field.width() != width_ || field.height() != height_) {
        horizons_ = {};
        sun_ = {};
        skyView_ = {};
        skyLight_ = {};
        heights_ = {};
        directions_ = 0;
    }
    width_ = field.width();
    height_ = field.height();
    spacingX_ = field.spacingX();
    spacingZ_ = field.spacingZ();
    scale_ = field.verticalScale();
    masked_ = field.hasMask();
    gpu::GlStateScope scope;
    GLint unpackBuffer = 0;  // not part of GlState
    glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &unpackBuffer);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    if (!heights_)
        heights_ = gpu::Texture::create(
            {.format = GL_R32F, .width = width_, .height = height_, .filter = GL_NEAREST});
    heights_.upload(GL_RED, GL_FLOAT, field.samples().data());
    const uint8_t one = 1;
    const int maskW = masked_ ? width_ : 1, maskH = masked_ ? height_ : 1;
    if (!mask_ || mask_.width() != maskW || mask_.height() != maskH)
        mask_ = gpu::Texture::create(
            {.format = GL_R8UI, .width = maskW, .height = maskH, .filter = GL_NEAREST});
    mask_.upload(GL_RED_INTEGER, GL_UNSIGNED_BYTE, masked_ ? field.mask().data() : &one);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, GLuint(unpackBuffer));
}

void ReliefGpu::sweep(const std::vector<double>& azimuths, const analysis::HorizonOptions& o,
                      const analysis::SunDisc* sun) {
    std::vector<double> all = azimuths;
    if (sun) all.push_back(double(sun->azimuth));
    const int validW = o.validWidth > 0 ? o.validWidth : width_;
    const int validH = o.validHeight > 0 ? o.validHeight : height_;
    std::vector<DirectionGpu> directions;
    std::vector<int32_t> offsets;
    std::vector<GroupGpu> groups;
    std::vector<size_t> entries;  // scratch entries per group
    for (size_t d = 0; d < all.size(); ++d) {
        const Lines l = makeLines(all[d], spacingX_, spacingZ_, validW, validH);
        // A radius at least the region's extent along the azimuth changes nothing.
        const double extent = std::fabs(double(validW) * spacingX_ * l.ux) +
                              std::fabs(double(validH) * spacingZ_ * l.uz);
        const bool limited = o.radius > 0.0f && double(o.radius) < extent;
        // t = i (sx ux) + j (sz uz), w = i (-sx uz) + j (sz ux)
        const double tI = spacingX_ * l.ux, tJ = spacingZ_ * l.uz;
        const double wI = -spacingX_ * l.uz, wJ = spacingZ_ * l.ux;
        DirectionGpu g{};
        g.steps[0] = float(l.iMajor ? tI : tJ);
        g.steps[1] = float(l.iMajor ? tJ : tI);
        g.steps[2] = float(l.iMajor ? wI : wJ);
        g.steps[3] = float(l.iMajor ? wJ : wI);
        g.lines[0] = l.iMajor ? 1 : 0;
        g.lines[1] = l.look;
        g.lines[2] = l.diagonal ? 1 : 0;
        g.lines[3] = l.majorCount;
        g.more[0] = l.minorCount;
        g.more[1] = int32_t(offsets.size());
        g.more[2] = d < azimuths.size() ? int32_t(d) : -1;  // -1: the sun
        g.more[3] = l.slope > 0.0 ? 1 : 0;
        g.limit[0] = limited ? o.radius : 0.0f;
        directions.push_back(g);
        offsets.insert(offsets.end(), l.r.begin(), l.r.end());
        for (int o0 = l.lineBegin; o0 < l.lineEnd; o0 += kGroup) {
            const int count = std::min(kGroup, l.lineEnd - o0);
            const auto [begin, end] = groupSpan(l, o0, count);
            if (begin >= end) continue;
            groups.push_back({.direction = int32_t(d),
                              .firstLine = o0,
                              .lines = count,
                              .majorBegin = begin,
                              .majorEnd = end});
            entries.push_back(size_t(end - begin) * (l.diagonal ? 2 : 1) * (limited ? 3 : 1) *
                              size_t(kGroup));
        }
    }
    // Dispatches of consecutive groups whose scratch fits the budget.
    GLint64 maxBlock = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBlock);
    GLint maxGroups = 0;
    glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 0, &maxGroups);
    const size_t budget =
        std::min<size_t>({kScratchBytes, size_t(maxBlock), size_t(1) << 34}) / sizeof(uint32_t[2]);
    std::vector<std::pair<size_t, size_t>> batches;  // groups [first, last)
    size_t largest = 0;
    for (size_t k = 0; k < groups.size();) {
        size_t used = 0, first = k;
        for (; k < groups.size() && k - first < size_t(maxGroups) && used + entries[k] <= budget;
             ++k) {
            groups[k].base = uint32_t(used);
            used += entries[k];
        }
        SIERRA_CHECK(k > first, "GPU relief: a ", width_, "x", height_,
                     " grid's lines need more scratch than a storage buffer holds (",
                     entries[first] * 8, " bytes for ", kGroup, " lines)");
        largest = std::max(largest, used);
        batches.emplace_back(first, k);
    }
    if (groups.empty()) return;
    if (!scratch_ || scratch_.size() < largest * 8)
        scratch_ = gpu::Buffer::create({.size = largest * 8});
    gpu::Buffer directionBuffer = gpu::Buffer::create(
        {.size = directions.size() * sizeof(DirectionGpu), .data = directions.data()});
    gpu::Buffer offsetBuffer =
        gpu::Buffer::create({.size = offsets.size() * sizeof(int32_t), .data = offsets.data()});
    gpu::Buffer groupBuffer =
        gpu::Buffer::create({.size = groups.size() * sizeof(GroupGpu), .data = groups.data()});

    if (!horizonProgram_) horizonProgram_ = gpu::Program::create({.compute = "horizon.comp"});
    const gpu::Program& program = horizonProgram_;
    gpu::GlStateScope scope;
    BindingScope bindings;
    glUseProgram(program.id());
    glUniform1f(program.uniform("uScale"), scale_);
    glUniform1i(program.uniform("uHasMask"), masked_ ? 1 : 0);
    if (sun) {
        const float rho = float(double(sun->diameter) * kPi / 360.0);  // the disc's radius, rad
        const float alt = float(double(sun->altitude) * kPi / 180.0);
        glUniform2f(program.uniform("uSun"), alt, rho);
        glUniform1i(program.uniform("uNight"), sun->altitude < -0.5f * sun->diameter ? 1 : 0);
    }
    // An image unit without a texture ignores stores (only the sun, or no
    // sun, in this dispatch).
    glBindImageTexture(0, azimuths.empty() ? 0 : horizons_.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY,
                       GL_R32F);
    glBindImageTexture(1, sun ? sun_.id() : 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    glBindTextureUnit(0, heights_.id());
    glBindTextureUnit(1, mask_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, directionBuffer.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, groupBuffer.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, offsetBuffer.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, scratch_.id());
    for (const auto& [first, last] : batches) {
        glUniform1ui(program.uniform("uFirstGroup"), GLuint(first));
        glDispatchCompute(GLuint(last - first), 1, 1);
        // The next dispatch reuses the scratch.
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    // The results are read by texel fetches, texture reads and anything else
    // a caller may do next.
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
}

void ReliefGpu::computeHorizons(const analysis::HorizonOptions& options) {
    computeHorizons(options, nullptr);
}

void ReliefGpu::computeHorizonsAndSun(const analysis::HorizonOptions& options,
                                      const analysis::SunDisc& sun) {
    computeHorizons(options, &sun);
}

void ReliefGpu::computeSunVisibility(const analysis::SunDisc& sun,
                                     const analysis::HorizonOptions& options) {
    validate(width_, height_, options, "sunVisibility");
    validateSun(sun);
    prepareSun();
    sweep({}, options, &sun);
}

void ReliefGpu::computeHorizons(const analysis::HorizonOptions& options,
                                const analysis::SunDisc* sun) {
    validate(width_, height_, options, "computeHorizons");
    validateDirections(options, "computeHorizons");
    if (sun) validateSun(*sun);
    if (!horizons_ || directions_ != options.directions)
        horizons_ = floatTexture(width_, height_, options.directions);
    else
        clearToNaN(horizons_);
    if (sun) prepareSun();
    directions_ = options.directions;
    firstAzimuth_ = options.firstAzimuth;
    // The azimuths as analysis::Horizons::azimuthDegrees rounds them (float).
    const analysis::Horizons layout{.directions = directions_, .firstAzimuth = firstAzimuth_};
    std::vector<double> azimuths(static_cast<size_t>(directions_));
    for (int d = 0; d < directions_; ++d) azimuths[size_t(d)] = double(layout.azimuthDegrees(d));
    sweep(azimuths, options, sun);
}

void ReliefGpu::prepareSun() {
    if (!sun_)
        sun_ = floatTexture(width_, height_, 0);
    else
        clearToNaN(sun_);
}

void ReliefGpu::computeSky() {
    SIERRA_CHECK(horizons_, "GPU relief: the sky needs horizons (computeHorizons) first");
    if (!skyView_) {
        skyView_ = floatTexture(width_, height_, 0);
        skyLight_ = floatTexture(width_, height_, 0);
    }
    if (!skyProgram_) skyProgram_ = gpu::Program::create({.compute = "relief_sky.comp"});
    std::vector<float> azimuths(size_t(directions_) * 2);
    const analysis::Horizons layout{.directions = directions_, .firstAzimuth = firstAzimuth_};
    for (int d = 0; d < directions_; ++d) {
        const double a = double(layout.azimuthDegrees(d)) * kPi / 180.0;
        azimuths[size_t(d) * 2] = float(std::sin(a));
        azimuths[size_t(d) * 2 + 1] = float(-std::cos(a));
    }
    gpu::Buffer azimuthBuffer =
        gpu::Buffer::create({.size = azimuths.size() * sizeof(float), .data = azimuths.data()});
    gpu::GlStateScope scope;
    BindingScope bindings;
    glUseProgram(skyProgram_.id());
    glUniform1f(skyProgram_.uniform("uScale"), scale_);
    glUniform1i(skyProgram_.uniform("uHasMask"), masked_ ? 1 : 0);
    glUniform2f(skyProgram_.uniform("uSpacing"), spacingX_, spacingZ_);
    glUniform1i(skyProgram_.uniform("uDirections"), directions_);
    glBindTextureUnit(0, horizons_.id());
    glBindTextureUnit(1, heights_.id());
    glBindTextureUnit(2, mask_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, azimuthBuffer.id());
    glBindImageTexture(0, skyView_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    glBindImageTexture(1, skyLight_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    glDispatchCompute(GLuint((width_ + 7) / 8), GLuint((height_ + 7) / 8), 1);
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
}

analysis::Horizons ReliefGpu::readHorizons() const {
    analysis::Horizons out;
    if (!horizons_) return out;
    out.width = width_;
    out.height = height_;
    out.directions = directions_;
    out.firstAzimuth = firstAzimuth_;
    out.angle = readTexture(horizons_, size_t(width_) * size_t(height_) * size_t(directions_));
    return out;
}

std::vector<float> ReliefGpu::readSunVisibility() const {
    return readTexture(sun_, size_t(width_) * size_t(height_));
}
std::vector<float> ReliefGpu::readSkyViewFactor() const {
    return readTexture(skyView_, size_t(width_) * size_t(height_));
}
std::vector<float> ReliefGpu::readSkyLight() const {
    return readTexture(skyLight_, size_t(width_) * size_t(height_));
}

analysis::Horizons computeHorizonsGpu(const terrain::Heightfield& field,
                                      const analysis::HorizonOptions& options) {
    validate(field.width(), field.height(), options, "computeHorizons");
    validateDirections(options, "computeHorizons");
    ReliefGpu r = ReliefGpu::create(field);
    r.computeHorizons(options);
    return r.readHorizons();
}

std::vector<float> sunVisibilityGpu(const terrain::Heightfield& field, const analysis::SunDisc& sun,
                                    const analysis::HorizonOptions& options) {
    validate(field.width(), field.height(), options, "sunVisibility");
    ReliefGpu r = ReliefGpu::create(field);
    r.computeSunVisibility(sun, options);
    return r.readSunVisibility();
}

std::vector<float> skyViewFactorGpu(const terrain::Heightfield& field,
                                    const analysis::HorizonOptions& options) {
    validate(field.width(), field.height(), options, "skyViewFactor");
    validateDirections(options, "skyViewFactor");
    ReliefGpu r = ReliefGpu::create(field);
    r.computeHorizons(options);
    r.computeSky();
    return r.readSkyViewFactor();
}

std::vector<float> skyLightGpu(const terrain::Heightfield& field,
                               const analysis::HorizonOptions& options) {
    validate(field.width(), field.height(), options, "skyLight");
    validateDirections(options, "skyLight");
    ReliefGpu r = ReliefGpu::create(field);
    r.computeHorizons(options);
    r.computeSky();
    return r.readSkyLight();
}

}  // namespace sierra::render
