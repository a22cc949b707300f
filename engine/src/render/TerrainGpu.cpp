#include <sierra/render/TerrainGpu.h>

#include "render/SbtBridge.h"
#include <sierra/analysis/Relief.h>
#include <sierra/core/Error.h>
#include <sierra/core/Log.h>
#include <sierra/core/Progress.h>
#include <sierra/core/Timer.h>
#include <sierra/render/FrameUniforms.h>
#include <sierra/terrain/HeightfieldIO.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <optional>

namespace sierra::render {

namespace {

// The framing outline of the real samples [0, last.x] x [0, last.y]: a grid of
// kOutlineBlocks^2 blocks; at each block corner two points, at the lowest and
// the highest world height of the blocks that share the corner. Every real
// sample lies in the hull of its block's corner points, so a camera that
// frames these frames the terrain, yet far tighter than the bounding box.
constexpr int kOutlineBlocks = 16;

std::vector<glm::vec3> outlineOf(const terrain::Heightfield& field, glm::ivec2 last) {
    const int blocks = kOutlineBlocks;
    auto edge = [&](int b, int lastIndex) { return int(int64_t(b) * lastIndex / blocks); };
    std::vector<glm::vec2> range(
        size_t(blocks * blocks),
        glm::vec2(std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest()));
    for (int bj = 0; bj < blocks; ++bj)
        for (int bi = 0; bi < blocks; ++bi) {
            glm::vec2& r = range[size_t(bj * blocks + bi)];
            for (int j = edge(bj, last.y); j <= edge(bj + 1, last.y); ++j)
                for (int i = edge(bi, last.x); i <= edge(bi + 1, last.x); ++i) {
                    float h = field.worldHeight(i, j);
                    r = {std::min(r.x, h), std::max(r.y, h)};
                }
        }
    std::vector<glm::vec3> points;
    points.reserve(size_t((blocks + 1) * (blocks + 1) * 2));
    for (int cj = 0; cj <= blocks; ++cj)
        for (int ci = 0; ci <= blocks; ++ci) {
            glm::vec2 r(std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest());
            for (int bj = std::max(cj - 1, 0); bj <= std::min(cj, blocks - 1); ++bj)
                for (int bi = std::max(ci - 1, 0); bi <= std::min(ci, blocks - 1); ++bi) {
                    glm::vec2 b = range[size_t(bj * blocks + bi)];
                    r = {std::min(r.x, b.x), std::max(r.y, b.y)};
                }
            float x = float(edge(ci, last.x)) * field.spacingX(),
                  z = float(edge(cj, last.y)) * field.spacingZ();
            points.push_back({x, r.x, z});
            points.push_back({x, r.y, z});
        }
    return points;
}

// Field for field the layout of `uniform Terrain` in shaders/terrain_common.glsl.
struct TerrainUniformData {
    glm::ivec4 grid{0};         // x: samples per side
    glm::vec4 spacingValid{0};  // xy: spacing; zw: world x, z of the last real sample
    glm::vec4 heights{
        0};  // x: world sea level; y: 1 with water; z, w: lowest and highest world height
};
static_assert(sizeof(TerrainUniformData) == 48,
              "TerrainUniformData must match std140 `uniform Terrain`");
}  // namespace

// The relief fields kept on the CPU and the texture that holds the last
// frame's. Keys are exact floats: a sun that is the same to the bit is the
// same sun (a sequence with a fixed sun computes it once).
struct ReliefState {
    using SunKey = std::array<float, 4>;  // azimuth, altitude, size, radius
    struct Sun {
        std::vector<float> visibility;
        uint64_t lastUse = 0;
    };
    std::map<float, std::vector<float>> skyLight;  // by radius
    std::map<SunKey, Sun> suns;
    uint64_t uses = 0;
    gpu::Texture texture;                          // RG16F: sun visibility, sky light
    std::optional<std::array<float, 6>> uploaded;  // shadows, sky light, then SunKey
    double ms = 0.0;
};

struct TerrainGpu::State {
    int side = 0;
    glm::vec2 spacing{1.0f};
    float verticalScale = 1.0f;
    float seaLevel = std::numeric_limits<float>::quiet_NaN();
    float worldSeaLevel = std::numeric_limits<float>::quiet_NaN();
    glm::vec2 worldRange{0.0f};
    SceneBounds bounds;
    std::string summary;
    double sbtBuildMs = 0.0;
    bool viewPrepared = false;  // prepareSbtView() has run

    terrain::Heightfield surface;  // the drawn surface: water flattened to sea level
    std::unique_ptr<SbtBridge> sbt;
    gpu::Texture data;     // RGBA32F: surface height, morph base, error, radius
    gpu::Texture heights;  // R32F: true world heights
    gpu::Buffer uniforms;
    gpu::Buffer fullIndices;
    uint64_t fullIndexCount = 0;
    gpu::Buffer meshIndices;
    uint64_t meshIndexCount = 0;
    glm::ivec2 realSamples{0};  // columns and rows of real data (the rest is padding)
    int threads = 0;
    ReliefState relief;
};

int TerrainGpu::maxGridSide() {
    GLint maxTexture = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
    int side = 3;
    while (side <= terrain::kDefaultMaxPaddedSide && 2 * side - 1 <= maxTexture)
        side = 2 * side - 1;
    return std::min(side, terrain::kDefaultMaxPaddedSide);
}

TerrainGpu TerrainGpu::create(const TerrainGpuDesc& desc) {
    SIERRA_CHECK(desc.field && !desc.field->empty(), "a terrain needs a heightfield");
    const terrain::Heightfield& field = *desc.field;
    int side = field.width();
    SIERRA_CHECK(field.width() == field.height() && side >= 3 && ((side - 1) & (side - 2)) == 0,
                 "the terrain renderer needs a (2^n+1)^2 grid, got ", field.width(), "x",
                 field.height(), " (pad it with padToPowerOfTwoPlusOne)");
    GLint maxTexture = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
    SIERRA_CHECK(side <= maxTexture, "a ", side, "x", side, " grid needs ", side,
                 "-texel textures; this GL (",
                 reinterpret_cast<const char*>(glGetString(GL_RENDERER)), ") allows at most ",
                 maxTexture, " per side");
    auto s = std::make_unique<State>();
    s->side = side;
    s->spacing = {field.spacingX(), field.spacingZ()};
    s->verticalScale = field.verticalScale();

    auto [lo, hi] = field.range();
    if (hi <= lo) hi = lo + 1.0f;
    float vs = field.verticalScale();
    bool water = !std::isnan(desc.seaLevel);
    SIERRA_CHECK(!water || std::isfinite(desc.seaLevel), "sea level must be finite, got ",
                 desc.seaLevel);
    s->seaLevel = desc.seaLevel;
    s->worldSeaLevel = water ? desc.seaLevel * vs : desc.seaLevel;
    s->worldRange = {lo * vs, hi * vs};
    // Padding (edge clamped to (2^n+1)^2) lies beyond the last real row and
    // column: it is refined like the rest but not shown, and the camera frames
    // only the real samples.
    glm::ivec2 lastReal{side - 1, side - 1};
    if (field.hasMask()) {
        lastReal = {0, 0};
        for (int j = 0; j < side; ++j)
            for (int i = 0; i < side; ++i)
                if (field.valid(i, j)) lastReal = glm::max(lastReal, glm::ivec2(i, j));
    }
    glm::vec2 validMax{float(lastReal.x) * field.spacingX(), float(lastReal.y) * field.spacingZ()};
    s->realSamples = lastReal + 1;
    s->threads = desc.threads;
    s->bounds.min = {0.0f, lo * vs, 0.0f};
    s->bounds.max = {validMax.x, hi * vs, validMax.y};
    s->summary = msg(side, "x", side, " samples, spacing ", field.spacingX(), "x", field.spacingZ(),
                     ", heights ", lo * vs, "..", hi * vs, " (world units), ",
                     water ? msg("sea level ", s->worldSeaLevel) : std::string("no water"));

    // The drawn surface: water is flat at sea level. The SBT is built on it, so
    // its errors and culling spheres describe exactly what is drawn.
    s->surface = field;
    if (water)
        for (float& h : s->surface.samples()) h = std::max(h, desc.seaLevel);
    s->bounds.outline = outlineOf(s->surface, lastReal);

    Stopwatch sw;
    s->sbt = std::make_unique<SbtBridge>(s->surface, desc.threads);
    s->sbtBuildMs = sw.ms();

    {
        std::vector<float> texels(size_t(side) * side * 4);
        std::span<const float> h = s->surface.samples();
        std::span<const float> base = s->sbt->morphBase();
        std::span<const float> err = s->sbt->errors();
        std::span<const float> rad = s->sbt->radii();
        for (size_t k = 0, n = size_t(side) * side; k < n; ++k) {
            texels[k * 4 + 0] = h[k] * vs;
            texels[k * 4 + 1] = base[k];
            texels[k * 4 + 2] = err[k];
            texels[k * 4 + 3] = rad[k];
        }
        s->data = gpu::Texture::create(
            {.format = GL_RGBA32F, .width = side, .height = side, .filter = GL_NEAREST});
        s->data.upload(GL_RGBA, GL_FLOAT, texels.data());
        s->sbt->releaseMorphBase();
        std::vector<float> heights(field.samples().begin(), field.samples().end());
        for (float& v : heights) v *= vs;
        s->heights = gpu::Texture::create({.format = GL_R32F, .width = side, .height = side});
        s->heights.upload(GL_RED, GL_FLOAT, heights.data());
    }
    TerrainUniformData u;
    u.grid = {side, 0, 0, 0};
    u.spacingValid = {field.spacingX(), field.spacingZ(), validMax.x, validMax.y};
    u.heights = {water ? s->worldSeaLevel : 0.0f, water ? 1.0f : 0.0f, s->worldRange.x,
                 s->worldRange.y};
    s->uniforms = gpu::Buffer::create({.size = sizeof(u), .data = &u});
    return TerrainGpu(std::move(s));
}

TerrainGpu::TerrainGpu(std::unique_ptr<State> state) : state_(std::move(state)) {}
TerrainGpu::TerrainGpu(TerrainGpu&&) noexcept = default;
TerrainGpu& TerrainGpu::operator=(TerrainGpu&&) noexcept = default;
TerrainGpu::~TerrainGpu() = default;

void TerrainGpu::bind() const {
    glBindTextureUnit(0, state_->data.id());
    glBindTextureUnit(2, state_->heights.id());
    glBindBufferBase(GL_UNIFORM_BUFFER, kTerrainUniformBinding, state_->uniforms.id());
}

bool TerrainGpu::prepareRelief(const ReliefRequest& request) {
    if (!request.any()) return false;
    State& s = *state_;
    ReliefState& r = s.relief;
    const ReliefState::SunKey sunKey{request.sunAzimuth, request.sunAltitude, request.sunSize,
                                     request.radius};
    const std::array<float, 6> key{request.shadows ? 1.0f : 0.0f,
                                   request.skyLight ? 1.0f : 0.0f,
                                   sunKey[0],
                                   sunKey[1],
                                   sunKey[2],
                                   sunKey[3]};
    if (r.uploaded && (*r.uploaded)[0] == key[0] && (*r.uploaded)[1] == key[1] &&
        (!request.shadows || std::equal(key.begin() + 2, key.end(), r.uploaded->begin() + 2)) &&
        (!request.skyLight || (*r.uploaded)[5] == key[5]))
        return true;
    const analysis::HorizonOptions options{.radius = request.radius,
                                           .validWidth = s.realSamples.x,
                                           .validHeight = s.realSamples.y,
                                           .threads = s.threads};
    const std::vector<float>* sky = nullptr;
    if (request.skyLight) {
        auto it = r.skyLight.find(request.radius);
        if (it == r.skyLight.end()) {
            Stopwatch sw;
            // One azimuth's angles at a time: no 4-bytes-per-sample-per-azimuth field.
            std::vector<float> light = analysis::skyLight(s.surface, options);
            const double ms = sw.ms();
            r.ms += ms;
            log::info("relief: sky light of ", s.realSamples.x, "x", s.realSamples.y, " samples (",
                      options.directions, " azimuths, horizon radius ",
                      request.radius > 0.0f ? msg(request.radius) : std::string("the whole grid"),
                      ") computed in ", fixed(ms, 1), " ms");
            it = r.skyLight.emplace(request.radius, std::move(light)).first;
        }
        sky = &it->second;
    }
    const std::vector<float>* sun = nullptr;
    if (request.shadows) {
        auto it = r.suns.find(sunKey);
        if (it == r.suns.end()) {
            if (r.suns.size() >= size_t(kReliefSunsKept)) {
                auto oldest = r.suns.begin();
                for (auto k = r.suns.begin(); k != r.suns.end(); ++k)
                    if (k->second.lastUse < oldest->second.lastUse) oldest = k;
                r.suns.erase(oldest);
            }
            ReliefState::Sun entry;
            if (request.sunAltitude + 0.5f * request.sunSize <= 0.0f) {
                entry.visibility.assign(s.surface.samples().size(), 0.0f);  // below the horizon
            } else {
                Stopwatch sw;
                entry.visibility = analysis::sunVisibility(s.surface,
                                                           {.azimuth = request.sunAzimuth,
                                                            .altitude = request.sunAltitude,
                                                            .diameter = request.sunSize},
                                                           options);
                const double ms = sw.ms();
                r.ms += ms;
                log::info("relief: shadows of the sun at azimuth ", request.sunAzimuth,
                          ", altitude ", request.sunAltitude, " (", request.sunSize,
                          " degrees wide) computed in ", fixed(ms, 1), " ms");
            }
            it = r.suns.emplace(sunKey, std::move(entry)).first;
        }
        it->second.lastUse = ++r.uses;
        sun = &it->second.visibility;
    }
    // No-data samples (NaN) are not occluded and see the whole sky.
    const size_t n = s.surface.samples().size();
    std::vector<float> texels(2 * n, 1.0f);
    for (size_t k = 0; k < n; ++k) {
        if (sun && std::isfinite((*sun)[k])) texels[2 * k] = (*sun)[k];
        if (sky && std::isfinite((*sky)[k])) texels[2 * k + 1] = (*sky)[k];
    }
    if (!r.texture)
        r.texture = gpu::Texture::create({.format = GL_RG16F, .width = s.side, .height = s.side});
    r.texture.upload(GL_RG, GL_FLOAT, texels.data());
    r.uploaded = key;
    return true;
}

void TerrainGpu::bindRelief() const {
    glBindTextureUnit(kReliefTextureUnit, state_->relief.texture.id());
}

double TerrainGpu::reliefMs() const {
    return state_->relief.ms;
}

SbtBridge& TerrainGpu::sbt() {
    return *state_->sbt;
}

const gpu::Buffer& TerrainGpu::fullGridIndices() {
    State& s = *state_;
    if (!s.fullIndices) {
        Stopwatch sw;
        std::vector<uint32_t> triangles = s.sbt->fullGridTriangles();
        s.fullIndexCount = triangles.size();
        s.fullIndices = gpu::Buffer::create(
            {.size = triangles.size() * sizeof(uint32_t), .data = triangles.data()});
        log::debug("full grid: ", s.fullIndexCount / 3, " triangles built in ", sw.ms(), " ms");
    }
    return s.fullIndices;
}

uint64_t TerrainGpu::fullGridIndexCount() const {
    return state_->fullIndexCount;
}

void TerrainGpu::setMesh(const std::vector<uint32_t>& triangles) {
    State& s = *state_;
    SIERRA_CHECK(!triangles.empty() && triangles.size() % 3 == 0,
                 "a terrain mesh needs whole triangles, got ", triangles.size(), " indices");
    const uint64_t samples = uint64_t(s.side) * uint64_t(s.side);
    for (uint32_t index : triangles)
        SIERRA_CHECK(index < samples, "a terrain mesh index ", index, " is outside the ", s.side,
                     "^2 grid");
    s.meshIndices = gpu::Buffer::create(
        {.size = triangles.size() * sizeof(uint32_t), .data = triangles.data()});
    s.meshIndexCount = triangles.size();
}

const gpu::Buffer& TerrainGpu::meshIndices() const {
    return state_->meshIndices;
}
uint64_t TerrainGpu::meshIndexCount() const {
    return state_->meshIndexCount;
}
SceneBounds TerrainGpu::bounds() const {
    return state_->bounds;
}
glm::vec2 TerrainGpu::worldRange() const {
    return state_->worldRange;
}
bool TerrainGpu::hasWater() const {
    return !std::isnan(state_->seaLevel);
}
float TerrainGpu::seaLevel() const {
    return state_->seaLevel;
}
float TerrainGpu::worldSeaLevel() const {
    return state_->worldSeaLevel;
}
const terrain::Heightfield& TerrainGpu::surface() const {
    return state_->surface;
}
int TerrainGpu::side() const {
    return state_->side;
}
glm::vec2 TerrainGpu::spacing() const {
    return state_->spacing;
}
float TerrainGpu::verticalScale() const {
    return state_->verticalScale;
}
void TerrainGpu::prepareSbtView(const SbtView& view) {
    if (state_->viewPrepared) return;
    Stopwatch sw;
    state_->sbt->prepareView(view);
    state_->sbtBuildMs += sw.ms();
    state_->viewPrepared = true;
}
size_t TerrainGpu::refinerKeyBytes() const {
    return state_->sbt->keyBytes();
}
double TerrainGpu::sbtBuildMs() const {
    return state_->sbtBuildMs;
}
const std::string& TerrainGpu::summary() const {
    return state_->summary;
}

}  // namespace sierra::render
