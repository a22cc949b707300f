#include <sierra/render/TerrainRenderer.h>

#include <sierra/core/Error.h>
#include <sierra/core/Timer.h>
#include <sierra/render/passes/DebugColourPass.h>
#include <sierra/render/passes/PointsPass.h>
#include <sierra/render/passes/TerrainPass.h>
#include <sierra/render/passes/WireframePass.h>

#include <algorithm>
#include <cmath>

namespace sierra::render {

struct TerrainRenderer::State {
    TerrainGpu terrain;
    SbtStream stream;
    FrameUniforms uniforms;
    std::unique_ptr<TerrainPass> shaded;           // replaced by setSurface()
    std::unique_ptr<TerrainPass> ramp;             // TerrainDesc's ramp once setSurface() ran
    std::unique_ptr<WireframePass> wireframe;      // built on first use
    std::unique_ptr<PointsPass> points;            // built on first use
    std::unique_ptr<DebugColourPass> debugColour;  // built on first use
    std::vector<std::unique_ptr<Pass>> extra;
    std::unique_ptr<DepthPass> depth;       // built on first use, per frame size
    std::unique_ptr<LabelPass> labels;      // built on first use, per frame size and surface
    const Surface* labelSurface = nullptr;  // the zone surface `labels` was built for
    gpu::Query timer;
    bool timerPending = false;
};

TerrainRenderer TerrainRenderer::create(const TerrainDesc& desc) {
    TerrainGpu terrain = TerrainGpu::create(
        {.field = desc.field, .seaLevel = desc.seaLevel, .threads = desc.threads});
    auto shaded = TerrainPass::create(makeRampSurface(terrain, {.metric = desc.metric,
                                                                .treeLine = desc.treeLine,
                                                                .snowLine = desc.snowLine,
                                                                .cpt = desc.cpt}));
    auto state = std::unique_ptr<State>(new State{
        .terrain = std::move(terrain),
        .stream = SbtStream::create(),
        .uniforms = FrameUniforms::create(),
        .shaded = std::move(shaded),
    });
    state->timer = gpu::Query::create(GL_TIME_ELAPSED);
    return TerrainRenderer(std::move(state));
}

TerrainRenderer::TerrainRenderer(std::unique_ptr<State> state) : state_(std::move(state)) {}
TerrainRenderer::TerrainRenderer(TerrainRenderer&&) noexcept = default;
TerrainRenderer& TerrainRenderer::operator=(TerrainRenderer&&) noexcept = default;
TerrainRenderer::~TerrainRenderer() = default;

glm::vec4 TerrainRenderer::clearColour(const Lighting& lighting) {
    return {lighting.sky, lighting.transparent ? 0.0f : 1.0f};
}

FrameUniformData TerrainRenderer::frameUniforms(const Camera& camera, int width, int height,
                                                const DrawOptions& options) const {
    const Lighting& light = options.lighting;
    SIERRA_CHECK(std::isfinite(light.ambient) && light.ambient >= 0.0f && light.ambient <= 1.0f,
                 "ambient light must be in [0, 1], got ", light.ambient);
    float aspect = float(width) / float(height);
    LodView lod = camera.lodView(height);
    // Automatic haze over the terrain's bounding sphere as the eye sees it;
    // an orthographic view has no meaningful eye distance (its eye is put
    // anywhere behind the terrain), so maps get none unless asked for.
    FogRange fog{.density = std::max(light.fogDensity, 0.0f)};
    if (light.fogDensity < 0.0f && camera.projection != Projection::Orthographic) {
        const SceneBounds bounds = state_->terrain.bounds();
        fog = automaticFog(glm::distance(camera.position, bounds.centre()),
                           0.5f * glm::length(bounds.size()));
    }
    // A sun whose whole disc is below the horizon lights nothing directly.
    glm::vec3 sun = glm::normalize(light.sunDirection);
    if (std::asin(std::clamp(sun.y, -1.0f, 1.0f)) <= -0.5f * glm::radians(light.sunSize))
        sun = glm::vec3(0.0f);
    FrameUniformData u;
    u.viewProj = camera.viewProjection(aspect);
    u.eye = {camera.position, 1.0f};
    u.lodEye = {lod.eye,
                options.lod == Lod::Sbt && options.geomorph ? lod.lambda / options.tau : 0.0f};
    u.sun = {sun, light.ambient};
    u.sky = clearColour(light);
    u.frameSize = {float(width), float(height), lod.lambda, options.tau};
    u.fog = {fog.density, camera.projection == Projection::Orthographic ? 1.0f : 0.0f, fog.start,
             0.0f};
    u.viewDir = {camera.forward(), 0.0f};
    return u;
}

namespace {
ReliefRequest reliefRequest(const Lighting& light) {
    const glm::vec3 d = glm::normalize(light.sunDirection);
    float azimuth = glm::degrees(std::atan2(d.x, -d.z));
    if (azimuth < 0.0f) azimuth += 360.0f;
    return {.shadows = light.shadows,
            .skyLight = light.skyLight,
            .sunAzimuth = azimuth,
            .sunAltitude = glm::degrees(std::asin(std::clamp(d.y, -1.0f, 1.0f))),
            .sunSize = light.sunSize,
            .radius = light.horizonRadius};
}

LodSettings lodSettings(const DrawOptions& options) {
    return {.lod = options.lod,
            .tau = options.tau,
            .cull = options.cull,
            .geomorph = options.geomorph,
            .threads = options.threads};
}
}  // namespace

DrawStats TerrainRenderer::draw(const Camera& camera, int width, int height,
                                const DrawOptions& options) {
    State& s = *state_;
    SIERRA_CHECK(width > 0 && height > 0, "frame size must be positive, got ", width, "x", height);
    DrawStats stats;
    MeshDraw mesh = s.stream.prepare(s.terrain, camera, width, height, lodSettings(options), stats);
    // The relief fields of this frame's sun (computed once per terrain and
    // sun, outside the submit time; TerrainGpu::reliefMs has their cost).
    TerrainPass& shadedPass = options.plainSurface && s.ramp ? *s.ramp : *s.shaded;
    const bool relief = options.polygons && options.colourBy == 0 && shadedPass.lit() &&
                        s.terrain.prepareRelief(reliefRequest(options.lighting));
    Stopwatch submit;
    FrameUniformData uniforms = frameUniforms(camera, width, height, options);
    GLint previousBlock = 0;
    glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, kFrameUniformBinding, &previousBlock);
    s.uniforms.update(uniforms);
    FrameContext frame{s.terrain, mesh, uniforms, camera, width, height};
    glBeginQuery(GL_TIME_ELAPSED, s.timer.id());
    if (options.polygons && options.colourBy != 0) {
        if (!s.debugColour) s.debugColour = DebugColourPass::create();
        s.debugColour->setMode(options.colourBy == 2 ? ColourBy::Error : ColourBy::Level);
        s.debugColour->draw(frame);
    } else if (options.polygons) {
        TerrainShading shading;
        shading.relief = relief;
        for (size_t k = 0; k < s.extra.size(); ++k)
            if (k >= 64 || (options.addedPasses >> k & 1u) != 0) s.extra[k]->shadeTerrain(shading);
        shadedPass.setShading(shading);
        shadedPass.draw(frame);
    }
    if (options.points) {
        if (!s.points) s.points = PointsPass::create();
        s.points->draw(frame);
    }
    if (options.wireframe) {
        if (!s.wireframe) s.wireframe = WireframePass::create();
        s.wireframe->draw(frame);
    }
    for (size_t k = 0; k < s.extra.size(); ++k)
        if (k >= 64 || (options.addedPasses >> k & 1u) != 0) s.extra[k]->draw(frame);
    glEndQuery(GL_TIME_ELAPSED);
    glBindBufferBase(GL_UNIFORM_BUFFER, kFrameUniformBinding, GLuint(previousBlock));
    s.timerPending = true;
    s.stream.finishFrame();
    stats.submitMs = submit.ms();
    return stats;
}

void TerrainRenderer::drawAlone(Pass& pass, const Camera& camera, int width, int height,
                                const DrawOptions& options) {
    State& s = *state_;
    MeshStats stats;
    MeshDraw mesh = s.stream.prepare(s.terrain, camera, width, height, lodSettings(options), stats);
    FrameUniformData uniforms = frameUniforms(camera, width, height, options);
    GLint previousBlock = 0;
    glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, kFrameUniformBinding, &previousBlock);
    s.uniforms.update(uniforms);
    pass.draw({s.terrain, mesh, uniforms, camera, width, height});
    glBindBufferBase(GL_UNIFORM_BUFFER, kFrameUniformBinding, GLuint(previousBlock));
    s.stream.finishFrame();
}

DepthImage TerrainRenderer::renderDepth(const Camera& camera, int width, int height,
                                        const DrawOptions& options) {
    State& s = *state_;
    if (!s.depth || s.depth->width() != width || s.depth->height() != height)
        s.depth = DepthPass::create(width, height);
    drawAlone(*s.depth, camera, width, height, options);
    return s.depth->read();
}

LabelImage TerrainRenderer::renderLabels(const Camera& camera, int width, int height,
                                         const DrawOptions& options,
                                         const glm::mat3& normalRotation) {
    State& s = *state_;
    const Surface* zones = hasZoneIds() ? &s.shaded->surface() : nullptr;
    if (!s.labels || s.labels->width() != width || s.labels->height() != height ||
        s.labelSurface != zones) {
        s.labels = LabelPass::create(width, height, zones);
        s.labelSurface = zones;
    }
    s.labels->setNormalRotation(normalRotation);
    drawAlone(*s.labels, camera, width, height, options);
    return s.labels->read();
}

bool TerrainRenderer::hasZoneIds() const {
    return state_->shaded->surface().zoneIds();
}

void TerrainRenderer::collectGpuTime(DrawStats& stats) {
    if (!state_->timerPending) return;
    GLuint64 ns = 0;
    glGetQueryObjectui64v(state_->timer.id(), GL_QUERY_RESULT, &ns);
    state_->timerPending = false;
    stats.drawMs = double(ns) * 1e-6;
}

void TerrainRenderer::setSurface(std::unique_ptr<Surface> surface) {
    if (!state_->ramp) state_->ramp = std::move(state_->shaded);
    state_->shaded = TerrainPass::create(std::move(surface));
    // The label pass binds the surface it was built for.
    state_->labels.reset();
    state_->labelSurface = nullptr;
}

void TerrainRenderer::addPass(std::unique_ptr<Pass> pass) {
    SIERRA_CHECK(pass != nullptr, "addPass needs a pass");
    state_->extra.push_back(std::move(pass));
}

std::vector<std::string> TerrainRenderer::addedPassNames() const {
    std::vector<std::string> names;
    for (const auto& pass : state_->extra) names.emplace_back(pass->name());
    return names;
}

TerrainGpu& TerrainRenderer::terrain() {
    return state_->terrain;
}
SceneBounds TerrainRenderer::bounds() const {
    return state_->terrain.bounds();
}
float TerrainRenderer::seaLevel() const {
    return state_->terrain.seaLevel();
}
int TerrainRenderer::side() const {
    return state_->terrain.side();
}
double TerrainRenderer::sbtBuildMs() const {
    return state_->terrain.sbtBuildMs();
}
const std::string& TerrainRenderer::summary() const {
    return state_->terrain.summary();
}

}  // namespace sierra::render
