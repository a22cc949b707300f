#include <sierra/render/TerrainRenderer.h>

#include <sierra/core/Error.h>
#include <sierra/core/Log.h>
#include <sierra/core/Timer.h>
#include "render/SbtBridge.h"
#include <sierra/terrain/ColourRamp.h>

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace sierra::render {

Lod parseLod(const std::string& name) {
    if (name == "sbt") return Lod::Sbt;
    if (name == "full") return Lod::Full;
    throw Error(msg("unknown level of detail '", name, "': use sbt or full"));
}

const char* lodName(Lod lod) { return lod == Lod::Sbt ? "sbt" : "full"; }

namespace {
constexpr int kRampEntries = 1024;
constexpr float kAmbient = 0.32f;
const glm::vec3 kSky{0.62f, 0.74f, 0.86f};
const glm::vec3 kSunDirection = glm::normalize(glm::vec3(-0.45f, 0.75f, 0.35f));

// The height below which 30% of the valid samples lie: a coast with some sea
// on any terrain, whatever its units.
float automaticSeaLevel(const terrain::Heightfield& field) {
    std::vector<float> heights;
    heights.reserve(size_t(field.sampleCount()));
    for (int j = 0; j < field.height(); ++j)
        for (int i = 0; i < field.width(); ++i)
            if (field.valid(i, j)) heights.push_back(field.at(i, j));
    if (heights.empty()) return 0.0f;
    auto nth = heights.begin() + std::ptrdiff_t(heights.size() * 3 / 10);
    std::nth_element(heights.begin(), nth, heights.end());
    return *nth;
}

struct TerrainUniforms {
    GLint side, spacing, viewProj, eye, lambdaOverTau;
    GLint rampRange, seaLevel, sunDir, skyColour, fogDensity, ambient;
    GLint validMax;
    GLint colour;  // wire only
    void locate(const gpu::Program& p) {
        side = p.uniform("uSide");
        spacing = p.uniform("uSpacing");
        viewProj = p.uniform("uViewProj");
        eye = p.uniform("uEye");
        lambdaOverTau = p.uniform("uLambdaOverTau");
        rampRange = p.uniform("uRampRange");
        seaLevel = p.uniform("uSeaLevel");
        sunDir = p.uniform("uSunDir");
        skyColour = p.uniform("uSkyColour");
        fogDensity = p.uniform("uFogDensity");
        ambient = p.uniform("uAmbient");
        validMax = p.uniform("uValidMax");
        colour = p.uniform("uColour");
    }
};
}  // namespace

struct TerrainRenderer::State {
    const terrain::Heightfield* field = nullptr;
    int side = 0;
    float seaLevel = 0.0f;       // stored units
    float worldSeaLevel = 0.0f;  // world units
    glm::vec2 worldRange{0.0f};
    glm::vec2 validMax{0.0f};  // world x, z of the last real (unpadded) sample
    SceneBounds bounds;
    std::string summary;
    double errorPassMs = 0.0;
    int threads = 0;

    std::unique_ptr<SbtBridge> sbt;
    terrain::Heightfield surface;  // field with water flattened to sea level
    gpu::Texture data;     // RGBA32F: surface height, morph base, error, radius
    gpu::Texture heights;  // R32F: true world heights
    gpu::Texture ramp;
    gpu::Program shade, wire;
    TerrainUniforms shadeU{}, wireU{};
    gpu::VertexArray vao;
    gpu::StreamRing ring;
    gpu::Buffer fullIndices;
    uint64_t fullIndexCount = 0;
    gpu::Query timer;
    bool timerPending = false;
    std::vector<uint32_t> strip;  // reused every frame

    void buildFullGrid() {
        Stopwatch sw;
        std::vector<uint32_t> triangles = sbt->fullGridTriangles();
        fullIndexCount = triangles.size();
        fullIndices = gpu::Buffer::create({.size = triangles.size() * sizeof(uint32_t), .data = triangles.data()});
        log::debug("full grid: ", fullIndexCount / 3, " triangles built in ", sw.ms(), " ms");
    }

    void setCommon(const gpu::Program& program, const TerrainUniforms& u, const Camera& camera, float aspect) {
        glUseProgram(program.id());
        glUniform1i(u.side, side);
        glUniform2f(u.spacing, field->spacingX(), field->spacingZ());
        glUniformMatrix4fv(u.viewProj, 1, GL_FALSE, glm::value_ptr(camera.viewProjection(aspect)));
        glUniform3fv(u.eye, 1, glm::value_ptr(camera.position));
        glUniform1f(u.seaLevel, worldSeaLevel);
        glUniform2fv(u.validMax, 1, glm::value_ptr(validMax));
    }
};

TerrainRenderer TerrainRenderer::create(const TerrainDesc& desc) {
    SIERRA_CHECK(desc.field && !desc.field->empty(), "TerrainRenderer needs a heightfield");
    const terrain::Heightfield& field = *desc.field;
    int side = field.width();
    SIERRA_CHECK(field.width() == field.height() && side >= 3 && ((side - 1) & (side - 2)) == 0,
                 "the terrain renderer needs a (2^n+1)^2 grid, got ", field.width(), "x",
                 field.height(), " (pad it with padToPowerOfTwoPlusOne)");
    GLint maxTexture = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
    SIERRA_CHECK(side <= maxTexture, "a ", side, "x", side, " grid needs ", side,
                 "-texel textures; this GL (", reinterpret_cast<const char*>(glGetString(GL_RENDERER)),
                 ") allows at most ", maxTexture, " per side");
    auto state = std::make_unique<State>();
    state->field = &state->surface;
    state->side = side;
    state->threads = desc.threads;

    auto [lo, hi] = field.range();
    if (hi <= lo) hi = lo + 1.0f;
    state->seaLevel = std::isnan(desc.seaLevel) ? automaticSeaLevel(field) : desc.seaLevel;
    SIERRA_CHECK(std::isfinite(state->seaLevel), "sea level must be finite");
    float vs = field.verticalScale();
    state->worldSeaLevel = state->seaLevel * vs;
    state->worldRange = {lo * vs, hi * vs};
    state->bounds.min = {0.0f, lo * vs, 0.0f};
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
    state->validMax = {float(lastReal.x) * field.spacingX(), float(lastReal.y) * field.spacingZ()};
    state->bounds.max = {state->validMax.x, hi * vs, state->validMax.y};
    state->summary = msg(side, "x", side, " samples, spacing ", field.spacingX(), "x", field.spacingZ(),
                         ", heights ", lo * vs, "..", hi * vs, " (world units), sea level ",
                         state->worldSeaLevel);

    // The drawn surface: water is flat at sea level. The SBT is built on it, so
    // its errors and culling spheres describe exactly what is drawn.
    state->surface = field;
    for (float& h : state->surface.samples()) h = std::max(h, state->seaLevel);

    Stopwatch sw;
    state->sbt = std::make_unique<SbtBridge>(state->surface, desc.threads);
    state->errorPassMs = sw.ms();

    // Terrain data: the drawn surface and its SBT data for the vertex stage
    // (RGBA32F), the true heights for colour and light (R32F, filtered).
    {
        std::vector<float> texels(size_t(side) * side * 4);
        std::span<const float> h = state->surface.samples();
        std::span<const float> base = state->sbt->morphBase();
        std::span<const float> err = state->sbt->errors();
        std::span<const float> rad = state->sbt->radii();
        for (size_t k = 0, n = size_t(side) * side; k < n; ++k) {
            texels[k * 4 + 0] = h[k] * vs;
            texels[k * 4 + 1] = base[k];
            texels[k * 4 + 2] = err[k];
            texels[k * 4 + 3] = rad[k];
        }
        state->data = gpu::Texture::create({.format = GL_RGBA32F, .width = side, .height = side,
                                            .filter = GL_NEAREST});
        state->data.upload(GL_RGBA, GL_FLOAT, texels.data());
        state->sbt->releaseMorphBase();
        std::vector<float> heights(field.samples().begin(), field.samples().end());
        for (float& v : heights) v *= vs;
        state->heights = gpu::Texture::create({.format = GL_R32F, .width = side, .height = side});
        state->heights.upload(GL_RED, GL_FLOAT, heights.data());
    }
    {
        terrain::ColourRamp ramp({.scheme = terrain::RampScheme::Hypsometric,
                                  .minHeight = state->worldRange.x,
                                  .maxHeight = state->worldRange.y,
                                  .seaLevel = state->worldSeaLevel});
        std::vector<uint8_t> table = ramp.table(kRampEntries);
        state->ramp = gpu::Texture::create({.target = GL_TEXTURE_1D, .format = GL_RGBA8, .width = kRampEntries});
        state->ramp.upload(GL_RGBA, GL_UNSIGNED_BYTE, table.data());
    }
    state->shade = gpu::Program::create({.vertex = "terrain.vert", .fragment = "terrain.frag"});
    state->wire = gpu::Program::create({.vertex = "terrain.vert", .fragment = "wire.frag"});
    state->shadeU.locate(state->shade);
    state->wireU.locate(state->wire);
    state->vao = gpu::VertexArray::create();
    state->ring = gpu::StreamRing::create();
    state->timer = gpu::Query::create(GL_TIME_ELAPSED);
    return TerrainRenderer(std::move(state));
}

TerrainRenderer::TerrainRenderer(std::unique_ptr<State> state) : state_(std::move(state)) {}
TerrainRenderer::TerrainRenderer(TerrainRenderer&&) noexcept = default;
TerrainRenderer& TerrainRenderer::operator=(TerrainRenderer&&) noexcept = default;
TerrainRenderer::~TerrainRenderer() = default;

DrawStats TerrainRenderer::draw(const Camera& camera, int width, int height, const DrawOptions& options) {
    State& s = *state_;
    SIERRA_CHECK(options.tau > 0.0f && std::isfinite(options.tau), "tau must be a positive number of pixels, got ",
                 options.tau);
    DrawStats stats;
    float aspect = float(width) / float(height);
    float lambda = camera.lambda(height);

    // Geometry for this frame.
    GLenum mode = GL_TRIANGLES;
    size_t byteOffset = 0;
    GLuint elementBuffer = 0;
    if (options.lod == Lod::Sbt) {
        Stopwatch sw;
        SbtView view;
        view.eye = camera.position;
        view.lambda = lambda;
        view.tau = options.tau;
        view.cull = options.cull;
        view.planes = camera.frustumPlanes(aspect);
        stats.triangles = s.sbt->refineView(view, s.strip, options.threads ? options.threads : s.threads);
        stats.refineMs = sw.ms();
        sw.restart();
        size_t bytes = s.strip.size() * sizeof(uint32_t);
        std::span<std::byte> region = s.ring.beginFrame(std::max<size_t>(bytes, 4));
        std::memcpy(region.data(), s.strip.data(), bytes);
        stats.uploadMs = sw.ms();
        stats.indices = s.strip.size();
        stats.bytesUploaded = bytes;
        mode = GL_TRIANGLE_STRIP;
        byteOffset = s.ring.offset();
        elementBuffer = s.ring.buffer();
    } else {
        if (!s.fullIndices) s.buildFullGrid();
        stats.indices = s.fullIndexCount;
        stats.triangles = s.fullIndexCount / 3;
        elementBuffer = s.fullIndices.id();
    }

    Stopwatch submit;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glEnable(GL_PRIMITIVE_RESTART_FIXED_INDEX);  // 0xFFFFFFFF joins strips
    glBindVertexArray(s.vao.id());
    glVertexArrayElementBuffer(s.vao.id(), elementBuffer);
    glBindTextureUnit(0, s.data.id());
    glBindTextureUnit(1, s.ramp.id());
    glBindTextureUnit(2, s.heights.id());

    float extent = std::max(s.bounds.size().x, s.bounds.size().z);
    float fog = options.fogDensity >= 0.0f ? options.fogDensity : 0.35f / extent;
    float lambdaOverTau = options.lod == Lod::Sbt && options.geomorph ? lambda / options.tau : 0.0f;

    glBeginQuery(GL_TIME_ELAPSED, s.timer.id());
    s.setCommon(s.shade, s.shadeU, camera, aspect);
    glUniform1f(s.shadeU.lambdaOverTau, lambdaOverTau);
    glUniform2f(s.shadeU.rampRange, s.worldRange.x, s.worldRange.y);
    glUniform3fv(s.shadeU.sunDir, 1, glm::value_ptr(kSunDirection));
    glUniform3fv(s.shadeU.skyColour, 1, glm::value_ptr(kSky));
    glUniform1f(s.shadeU.fogDensity, fog);
    glUniform1f(s.shadeU.ambient, kAmbient);
    if (options.wireframe) {
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(1.0f, 1.0f);
    }
    GL_CHECK(glDrawElements(mode, GLsizei(stats.indices), GL_UNSIGNED_INT,
                            reinterpret_cast<const void*>(byteOffset)));
    if (options.wireframe) {
        glDisable(GL_POLYGON_OFFSET_FILL);
        s.setCommon(s.wire, s.wireU, camera, aspect);
        glUniform1f(s.wireU.lambdaOverTau, lambdaOverTau);
        glUniform4f(s.wireU.colour, 0.08f, 0.08f, 0.1f, 1.0f);
        glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
        glDepthFunc(GL_LEQUAL);
        GL_CHECK(glDrawElements(mode, GLsizei(stats.indices), GL_UNSIGNED_INT,
                                reinterpret_cast<const void*>(byteOffset)));
        glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
        glDepthFunc(GL_LESS);
    }
    glEndQuery(GL_TIME_ELAPSED);
    s.timerPending = true;
    if (options.lod == Lod::Sbt) s.ring.finishFrame();

    glBindVertexArray(0);
    glUseProgram(0);
    glDisable(GL_PRIMITIVE_RESTART_FIXED_INDEX);
    glDisable(GL_DEPTH_TEST);
    stats.submitMs = submit.ms();
    return stats;
}

void TerrainRenderer::collectGpuTime(DrawStats& stats) {
    if (!state_->timerPending) return;
    GLuint64 ns = 0;
    glGetQueryObjectui64v(state_->timer.id(), GL_QUERY_RESULT, &ns);
    state_->timerPending = false;
    stats.drawMs = double(ns) * 1e-6;
}

SceneBounds TerrainRenderer::bounds() const { return state_->bounds; }
glm::vec3 TerrainRenderer::skyColour() const { return kSky; }
float TerrainRenderer::seaLevel() const { return state_->seaLevel; }
int TerrainRenderer::side() const { return state_->side; }
double TerrainRenderer::errorPassMs() const { return state_->errorPassMs; }
const std::string& TerrainRenderer::summary() const { return state_->summary; }

}  // namespace sierra::render
