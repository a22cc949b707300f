#include <sierra/render/TiledTerrain.h>

#include <sierra/core/Error.h>
#include <sierra/core/Log.h>
#include <sierra/core/Timer.h>
#include <sierra/gpu/GlStateScope.h>
#include <sierra/gpu/Program.h>
#include <sierra/sbt/TiledRefiner.h>
#include <sierra/sbt/VertexErrors.h>

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <numeric>

namespace sierra::render {
namespace {

// Tile resolutions the shaders take (tiled_common.glsl's uClass).
constexpr int kMaxClasses = 9;
// Texture units (tiled_common.glsl, tiled_terrain.frag): above the surfaces'
// (GL 4.5 has at least 80 units; the fragment stage samples at most 13 of
// these besides a surface's few, within its 16).
constexpr GLuint kPagesUnit = 16, kClassUnit = 17, kCornersUnit = 26, kReliefUnit = 27;

// The refinement's view of a cache: a tile's usable levels are those read
// and uploaded both.
class GpuResident : public sbt::TiledVertices {
  public:
    GpuResident(const sbt::TileCache& cache, const std::vector<int>& gpuLevels)
        : TiledVertices(cache.desc()), cache_(cache), gpu_(gpuLevels) {}
    int residentLevels(int tx, int ty) const override {
        const int cpu = cache_.residentLevels(tx, ty);
        if (!cache_.file().stored(tx, ty)) return cpu;  // the padding: never refined
        return std::min(cpu, gpu_[size_t(ty) * size_t(tilesPerSide()) + size_t(tx)]);
    }
    const sbt::VertexRecord* tileRecords(int tx, int ty) const override {
        return cache_.tileRecords(tx, ty);
    }
    sbt::VertexRecord corner(uint32_t i, uint32_t j) const override { return cache_.corner(i, j); }

  private:
    const sbt::TileCache& cache_;
    const std::vector<int>& gpu_;
};

// Class c's tiles: an array texture of layers, each an atlas of
// slotsPerRow^2 slots side by side. A slot is the tile's side^2 heights in a
// one-texel gutter repeating its edge: the shaders' bilinear lookups stay
// within a tile's own texels, so neighbouring slots never bleed into each
// other, whatever the rounding of the texture coordinates.
struct GpuClass {
    gpu::Texture texture;
    int side = 0;  // 2^c + 1
    int pitch() const { return side + 2; }
    int slotsPerRow = 1;
    int layers = 0;
    int slots = 0;  // usable: the last layer may have unused slots
    std::vector<int> freeSlots;
    std::vector<int> owner;  // tile per slot, -1 = free
    int perLayer() const { return slotsPerRow * slotsPerRow; }
    // Layer, then texel x and y of the slot's first texel (its gutter's).
    std::array<int, 3> place(int slot) const {
        const int r = slot % perLayer();
        return {slot / perLayer(), r % slotsPerRow * pitch(), r / slotsPerRow * pitch()};
    }
};

// Class `g`'s layout for `wanted` tiles of `bytes` each within `left` bytes:
// as few slots per layer as keep the layers within `maxLayers` and the layer
// within `maxSide` texels.
void layoutClass(GpuClass& g, uint64_t wanted, uint64_t left, uint64_t bytes, int maxLayers,
                 int maxSide) {
    const uint64_t perLayerMin = (wanted + uint64_t(maxLayers) - 1) / uint64_t(maxLayers);
    int n = std::max(1, int(std::ceil(std::sqrt(double(perLayerMin)))));
    while (uint64_t(n) * uint64_t(n) < perLayerMin) ++n;
    n = std::max(1, std::min(n, maxSide / g.pitch()));
    const uint64_t q = uint64_t(n) * uint64_t(n);
    uint64_t layers = std::min<uint64_t>((wanted + q - 1) / q, uint64_t(maxLayers));
    while (layers > 1 && layers * q * bytes > left) --layers;
    g.slotsPerRow = n;
    g.layers = int(layers);
    g.slots = int(std::min<uint64_t>(wanted, layers * q));
}

}  // namespace

struct TiledTerrain::State {
    std::unique_ptr<sbt::TileFile> file;
    std::unique_ptr<sbt::TileCache> cache;
    sbt::TileAddressing address{1};
    std::vector<int> gpuLevels;  // per tile: tile levels uploaded
    std::vector<int> gpuClass, gpuSlot;
    std::vector<int64_t> gpuUsed;  // frame a tile was last drawn from
    std::unique_ptr<GpuResident> resident;
    std::unique_ptr<sbt::TiledRefiner> refiner;
    sbt::TiledMesh mesh;
    std::vector<GpuClass> classes;
    gpu::Texture pages;
    gpu::Texture corners;  // the tile corners' world heights
    std::unique_ptr<TiledRelief> relief;
    std::vector<int32_t> pageData;
    bool pagesDirty = true;
    std::unique_ptr<Surface> surface;
    // The surface's programs, without and with contour edges (built on first use).
    std::array<gpu::Program, 2> programs;
    gpu::Buffer uniforms;
    gpu::VertexArray vao;
    gpu::Buffer vertices, indices;
    std::vector<uint32_t> indexData;
    uint64_t gpuBytes = 0;
    int gpuSlots = 0;  // all classes'
    int64_t frame = 0;
    glm::vec3 lastEye{0.0f};
    bool haveLastEye = false;
    glm::vec2 range{0.0f, 1.0f};
    std::vector<float> grid, slotTexels;  // scratch of an upload

    int tiles() const { return file->info().tilesPerSide(); }
    const gpu::Program& program(bool contours);
    void upload(int tile, const sbt::PackedTile& data, int& uploaded);
    void uploadArrivals(int& uploaded, int limit);
    void cacheStats(TiledFrameStats& stats) const {
        stats.cache = cache->stats();
        stats.gpuBytes = gpuBytes;
        stats.gpuSlots = gpuSlots;
        stats.gpuTiles =
            int(std::count_if(gpuClass.begin(), gpuClass.end(), [](int c) { return c >= 0; }));
    }
};

std::unique_ptr<TiledTerrain> TiledTerrain::open(const TiledTerrainDesc& desc) {
    auto s = std::make_unique<State>();
    s->file = std::make_unique<sbt::TileFile>(desc.path);
    const sbt::TileFileInfo& info = s->file->info();
    SIERRA_CHECK(info.k <= kMaxClasses - 1, desc.path, ": tiles of 2^", info.k,
                 " cells; the GPU tile cache draws tiles of at most 2^", kMaxClasses - 1,
                 " (rebuild with sierra-tile build --tile-levels ", kMaxClasses - 1, ")");
    const uint64_t cpuBudget = desc.memoryBudget / 4 * 3, gpuBudget = desc.memoryBudget / 4;
    s->cache = std::make_unique<sbt::TileCache>(
        *s->file,
        sbt::TileCacheOptions{.budgetBytes = cpuBudget, .loaderThreads = desc.loaderThreads});
    s->address = sbt::TileAddressing(info.k);
    const int P = info.tilesPerSide(), tiles = P * P;
    s->gpuLevels.assign(size_t(tiles), 0);
    s->gpuClass.assign(size_t(tiles), -1);
    s->gpuSlot.assign(size_t(tiles), -1);
    s->gpuUsed.assign(size_t(tiles), 0);
    s->resident = std::make_unique<GpuResident>(*s->cache, s->gpuLevels);
    s->refiner = std::make_unique<sbt::TiledRefiner>(*s->resident);

    // The GPU budget over the resolutions, coarsest first: each takes a slot
    // for every stored tile or an equal share of what is left for it and the
    // finer ones, so the cheap coarse classes are whole and the finest gets
    // what remains. Beyond the layer limit a layer holds several slots.
    GLint maxLayers = 256, maxSide = 2048;
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSide);
    if (desc.maxLayers > 0) maxLayers = std::min(maxLayers, GLint(desc.maxLayers));
    s->classes.resize(size_t(kMaxClasses));
    uint64_t left = gpuBudget;
    for (int c = 0; c <= info.k; ++c) {
        GpuClass& g = s->classes[size_t(c)];
        g.side = (1 << c) + 1;
        const uint64_t tileBytes = uint64_t(g.pitch()) * uint64_t(g.pitch()) * 4;
        const uint64_t wanted =
            std::min<uint64_t>(left / uint64_t(info.k + 1 - c) / tileBytes, uint64_t(tiles));
        SIERRA_CHECK(wanted >= 1, "a memory budget of ", desc.memoryBudget >> 20,
                     " MiB leaves no GPU slot for tiles of ", g.side, "^2 heights");
        layoutClass(g, wanted, left, tileBytes, maxLayers, maxSide);
        const uint64_t bytes = uint64_t(g.layers) * uint64_t(g.perLayer()) * tileBytes;
        left -= std::min(left, bytes);
        g.texture = gpu::Texture::create({.target = GL_TEXTURE_2D_ARRAY,
                                          .format = GL_R32F,
                                          .width = g.pitch() * g.slotsPerRow,
                                          .height = g.pitch() * g.slotsPerRow,
                                          .layers = g.layers,
                                          .filter = GL_LINEAR});
        g.freeSlots.resize(size_t(g.slots));
        std::iota(g.freeSlots.rbegin(), g.freeSlots.rend(), 0);
        g.owner.assign(size_t(g.slots), -1);
        s->gpuBytes += bytes;
        s->gpuSlots += g.slots;
    }
    for (int c = info.k + 1; c < kMaxClasses; ++c)  // unused units still need a texture
        s->classes[size_t(c)].texture = gpu::Texture::create({.target = GL_TEXTURE_2D_ARRAY,
                                                              .format = GL_R32F,
                                                              .width = 1,
                                                              .height = 1,
                                                              .layers = 1});
    s->pages =
        gpu::Texture::create({.format = GL_RGBA32I, .width = P, .height = P, .filter = GL_NEAREST});
    s->pageData.assign(size_t(tiles) * 4, -1);
    s->vao = gpu::VertexArray::create();
    s->relief = std::make_unique<TiledRelief>(*s->file, desc.reliefMaxSide);

    float lo = INFINITY, hi = -INFINITY;
    const int T = 1 << info.k;
    std::vector<float> corners(size_t(P + 1) * size_t(P + 1));
    for (int cj = 0; cj <= P; ++cj)
        for (int ci = 0; ci <= P; ++ci) {
            const float h =
                s->file->corner(int64_t(ci) * T, int64_t(cj) * T).height * info.verticalScale;
            corners[size_t(cj) * size_t(P + 1) + size_t(ci)] = h;
            if (int64_t(ci) * T > info.width - 1 + T || int64_t(cj) * T > info.height - 1 + T)
                continue;
            lo = std::min(lo, h);
            hi = std::max(hi, h);
        }
    s->corners = gpu::Texture::create(
        {.format = GL_R32F, .width = P + 1, .height = P + 1, .filter = GL_LINEAR});
    s->corners.upload(GL_RED, GL_FLOAT, corners.data());
    s->range = {lo, std::max(hi, lo + 1e-3f)};
    // tiled_common.glsl's Terrain block: uGrid, uSpacingValid, uHeightInfo, uTileInfo.
    const int32_t side = int32_t(info.gridSide());
    const int32_t ints[8] = {side, 0, 0, 0, info.k, P, T, 0};
    const float block[8] = {info.spacingX,
                            info.spacingZ,
                            float(double(info.width - 1) * info.spacingX),
                            float(double(info.height - 1) * info.spacingZ),
                            0.0f,
                            0.0f,
                            s->range.x,
                            s->range.y};
    std::vector<uint8_t> bytes(64);
    std::memcpy(bytes.data(), ints, 16);
    std::memcpy(bytes.data() + 16, block, sizeof(block));
    std::memcpy(bytes.data() + 48, ints + 4, 16);
    s->uniforms = gpu::Buffer::create({.size = bytes.size(), .data = bytes.data()});
    auto terrain = std::unique_ptr<TiledTerrain>(new TiledTerrain(std::move(s)));
    terrain->setSurface(makeRampSurface(terrain->surfaceRamp({.metric = info.metres})));
    const State& st = *terrain->state_;
    log::info("tiled terrain ", desc.path, ": ", info.width, "x", info.height, " samples, ", P,
              "^2 tiles of ", info.tileSide(), "^2; tile caches ", cpuBudget >> 20, " MiB CPU, ",
              st.gpuBytes >> 20, " MiB GPU");
    return terrain;
}

TiledTerrain::TiledTerrain(std::unique_ptr<State> state) : state_(std::move(state)) {}
TiledTerrain::~TiledTerrain() = default;

const sbt::TileFileInfo& TiledTerrain::info() const {
    return state_->file->info();
}

const sbt::TileFile& TiledTerrain::file() const {
    return *state_->file;
}

SceneBounds TiledTerrain::bounds() const {
    const sbt::TileFileInfo& info = state_->file->info();
    SceneBounds b;
    b.min = {0.0f, state_->range.x, 0.0f};
    b.max = {float(double(info.width - 1) * info.spacingX), state_->range.y,
             float(double(info.height - 1) * info.spacingZ)};
    return b;
}

glm::vec2 TiledTerrain::worldRange() const {
    return state_->range;
}

// Tile `tile`'s first data.levels levels as its resolution class's grid: the
// resident vertices' world heights, an odd last level's missing vertices the
// means of their hypotenuse ends.
void TiledTerrain::State::upload(int tile, const sbt::PackedTile& data, int& uploaded) {
    const sbt::TileFileInfo& info = file->info();
    const int k = info.k, T = 1 << k, P = tiles();
    const int c = std::min(k, (data.levels + 1) / 2);
    GpuClass& g = classes[size_t(c)];
    if (g.freeSlots.empty()) {
        // The class is full: the slot drawn from least recently goes, unless
        // every slot was drawn from this frame (then the tile waits).
        int victim = 0;
        for (int l = 1; l < g.slots; ++l)
            if (gpuUsed[size_t(g.owner[size_t(l)])] < gpuUsed[size_t(g.owner[size_t(victim)])])
                victim = l;
        const int gone = g.owner[size_t(victim)];
        if (gpuUsed[size_t(gone)] >= frame) return;
        gpuClass[size_t(gone)] = gpuSlot[size_t(gone)] = -1;
        gpuLevels[size_t(gone)] = 0;
        std::fill_n(pageData.begin() + ptrdiff_t(gone) * 4, 4, -1);
        g.owner[size_t(victim)] = -1;
        g.freeSlots.push_back(victim);
    }
    if (gpuClass[size_t(tile)] >= 0) {  // its coarser slot goes back
        GpuClass& old = classes[size_t(gpuClass[size_t(tile)])];
        old.freeSlots.push_back(gpuSlot[size_t(tile)]);
        old.owner[size_t(gpuSlot[size_t(tile)])] = -1;
    }
    const int slot = g.freeSlots.back();
    g.freeSlots.pop_back();
    const int side = g.side, step = T >> c, tx = tile % P, ty = tile / P;
    grid.assign(size_t(side) * size_t(side), 0.0f);
    std::vector<uint8_t> have(grid.size(), 0);
    const float vs = info.verticalScale;
    for (int b = 0; b < side; ++b)
        for (int a = 0; a < side; ++a) {
            const int x = a * step, y = b * step;
            float h;
            if ((x == 0 || x == T) && (y == 0 || y == T)) {
                h = file->corner(int64_t(tx) * T + x, int64_t(ty) * T + y).height;
            } else if (address.level(x, y) < data.levels) {
                h = data.records[address.index(x, y)].height;
            } else {
                continue;
            }
            grid[size_t(b) * size_t(side) + size_t(a)] = h * vs;
            have[size_t(b) * size_t(side) + size_t(a)] = 1;
        }
    // No-data samples (a tile read whole keeps its mask): NaN, which the
    // fragment shader drops and the vertex shader draws at the lowest height.
    if (!data.mask.empty())
        for (int b = 0; b < side; ++b)
            for (int a = 0; a < side; ++a)
                if (!data.mask[size_t(b * step) * size_t(T + 1) + size_t(a * step)])
                    grid[size_t(b) * size_t(side) + size_t(a)] = std::nanf("");
    // The missing ones (an odd last level's): the mean of their hypotenuse's ends.
    for (int b = 0; b < side; ++b)
        for (int a = 0; a < side; ++a) {
            const size_t m = size_t(b) * size_t(side) + size_t(a);
            if (have[m]) continue;
            int ai, aj, bi, bj;
            sbt::hypotenuseEndpoints(a, b, c, &ai, &aj, &bi, &bj);
            grid[m] = 0.5f * (grid[size_t(aj) * size_t(side) + size_t(ai)] +
                              grid[size_t(bj) * size_t(side) + size_t(bi)]);
        }
    // The slot: the grid in its gutter, the edge texels repeated.
    const int pitch = g.pitch();
    slotTexels.resize(size_t(pitch) * size_t(pitch));
    for (int b = 0; b < pitch; ++b)
        for (int a = 0; a < pitch; ++a)
            slotTexels[size_t(b) * size_t(pitch) + size_t(a)] =
                grid[size_t(std::clamp(b - 1, 0, side - 1)) * size_t(side) +
                     size_t(std::clamp(a - 1, 0, side - 1))];
    const auto [layer, x0, y0] = g.place(slot);
    glTextureSubImage3D(g.texture.id(), 0, x0, y0, layer, pitch, pitch, 1, GL_RED, GL_FLOAT,
                        slotTexels.data());
    g.owner[size_t(slot)] = tile;
    gpuClass[size_t(tile)] = c;
    gpuSlot[size_t(tile)] = slot;
    gpuLevels[size_t(tile)] = std::min(data.levels, 2 * c);
    gpuUsed[size_t(tile)] = frame;
    const int page[4] = {c, layer, x0 + 1, y0 + 1};
    std::copy_n(page, 4, pageData.begin() + ptrdiff_t(tile) * 4);
    pagesDirty = true;
    ++uploaded;
}

void TiledTerrain::State::uploadArrivals(int& uploaded, int limit) {
    const int P = tiles();
    // Nearest first would need the distances; the refinement's order is
    // good enough: tiles it reached, deepest want first.
    std::vector<std::pair<int, int>> todo;  // (-levels, tile)
    for (int t = 0; t < P * P; ++t) {
        const int cpu = cache->residentLevels(t % P, t / P);
        if (!file->stored(t % P, t / P) || cpu <= gpuLevels[size_t(t)]) continue;
        todo.push_back({-cpu, t});
    }
    std::sort(todo.begin(), todo.end());
    for (const auto& [negLevels, t] : todo) {
        if (uploaded >= limit) break;
        (void)negLevels;
        if (const sbt::PackedTile* data = cache->packed(t % P, t / P)) upload(t, *data, uploaded);
    }
}

TiledFrameStats TiledTerrain::prepare(const Camera& camera, int width, int height,
                                      const TiledFrameOptions& options) {
    State& s = *state_;
    TiledFrameStats stats;
    ++s.frame;
    Stopwatch upload;
    s.cache->beginFrame();
    int uploaded = 0;
    s.uploadArrivals(uploaded, std::max(options.uploadsPerFrame, 1));
    stats.uploadMs = upload.ms();
    stats.uploadedTiles = uploaded;
    const TiledReliefRequest relief{.shadows = options.shadows,
                                    .skyLight = options.skyLight,
                                    .sunDirection = options.sunDirection,
                                    .sunSize = options.sunSize,
                                    .radius = options.horizonRadius};
    stats.reliefMs = s.relief->prepare(relief);

    const float aspect = float(width) / float(height);
    sbt::ViewParams view;
    view.eye = {camera.position.x, camera.position.y, camera.position.z};
    view.lambda = camera.lambda(height);
    view.tau = options.tau;
    view.cull = options.cull;
    const auto planes = camera.frustumPlanes(aspect);
    for (size_t p = 0; p < 6; ++p)
        view.planes[p] = {planes[p].x, planes[p].y, planes[p].z, planes[p].w};
    Stopwatch refine;
    s.refiner->refineView(view, s.mesh);
    stats.refineMs = refine.ms();
    stats.triangles = s.mesh.triangleCount;
    stats.coarseTiles = s.mesh.coarseTiles;
    const std::vector<uint8_t>& reached = s.refiner->reachedLevels();
    for (size_t t = 0; t < reached.size(); ++t)
        if (reached[t] > 0) s.gpuUsed[t] = s.frame;
    // Prefetch along the motion since the last frame.
    glm::vec3 ahead = camera.position;
    if (s.haveLastEye && options.frameSeconds > 0.0f)
        ahead += (camera.position - s.lastEye) * (options.prefetchSeconds / options.frameSeconds);
    s.lastEye = camera.position;
    s.haveLastEye = true;
    s.cache->wantForView(*s.refiner, view.eye, {ahead.x, ahead.y, ahead.z});
    s.cacheStats(stats);
    return stats;
}

TiledFrameStats TiledTerrain::draw(const Camera& camera, int width, int height,
                                   const TiledFrameOptions& options) {
    TiledFrameStats stats = prepare(camera, width, height, options);
    State& s = *state_;
    const float aspect = float(width) / float(height);

    // The mesh: (i, j) pairs and their indices with restarts.
    Stopwatch meshUpload;
    const std::vector<uint64_t>& strip = s.mesh.strip;
    s.indexData.resize(strip.size());
    for (size_t v = 0; v < strip.size(); ++v)
        s.indexData[v] = strip[v] == sbt::kTiledRestart ? 0xFFFFFFFFu : uint32_t(v);
    if (s.pagesDirty) {
        glTextureSubImage2D(s.pages.id(), 0, 0, 0, s.tiles(), s.tiles(), GL_RGBA_INTEGER, GL_INT,
                            s.pageData.data());
        s.pagesDirty = false;
    }
    if (!strip.empty()) {
        s.vertices = gpu::Buffer::create({.size = strip.size() * 8, .data = strip.data()});
        s.indices =
            gpu::Buffer::create({.size = s.indexData.size() * 4, .data = s.indexData.data()});
    }
    stats.uploadMs += meshUpload.ms();

    if (!strip.empty()) {
        gpu::GlStateScope scope;
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDisable(GL_CULL_FACE);
        glEnable(GL_PRIMITIVE_RESTART_FIXED_INDEX);
        const bool contours = options.contourWidth > 0.0f;
        const gpu::Program& program = s.program(contours);
        glUseProgram(program.id());
        if (contours) {
            glUniform1f(program.uniform("uContourWidth"), options.contourWidth);
            glUniform4fv(program.uniform("uContourColour"), 1,
                         glm::value_ptr(options.contourColour));
        }
        const glm::mat4 vp = camera.viewProjection(aspect);
        glUniformMatrix4fv(program.uniform("uViewProj"), 1, GL_FALSE, glm::value_ptr(vp));
        glUniform3fv(program.uniform("uEye"), 1, glm::value_ptr(camera.position));
        // A sun whose whole disc is below the horizon lights nothing directly.
        glm::vec3 sun = glm::normalize(options.sunDirection);
        if (std::asin(std::clamp(sun.y, -1.0f, 1.0f)) <= -0.5f * glm::radians(options.sunSize))
            sun = glm::vec3(0.0f);
        glUniform3fv(program.uniform("uSun"), 1, glm::value_ptr(sun));
        glUniform3fv(program.uniform("uSky"), 1, glm::value_ptr(options.sky));
        const SceneBounds b = bounds();
        // Automatic haze: a third of the light gone at the terrain's centre.
        const float fog = options.fogDensity >= 0.0f
                              ? options.fogDensity
                              : 0.4f / std::max(glm::distance(camera.position, b.centre()), 1.0f);
        glUniform1f(program.uniform("uFog"), fog);
        glUniform1f(program.uniform("uAmbient"), options.ambient);
        glUniform4fv(program.uniform("uReliefUv"), 1, glm::value_ptr(s.relief->worldToUv()));
        s.surface->bind();
        s.relief->bind(kReliefUnit, kReliefUnit + 1);
        glBindBufferBase(GL_UNIFORM_BUFFER, 1, s.uniforms.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, s.vertices.id());
        glBindTextureUnit(kPagesUnit, s.pages.id());
        glBindTextureUnit(kCornersUnit, s.corners.id());
        for (int c = 0; c < kMaxClasses; ++c)
            glBindTextureUnit(kClassUnit + GLuint(c), s.classes[size_t(c)].texture.id());
        glBindVertexArray(s.vao.id());
        glVertexArrayElementBuffer(s.vao.id(), s.indices.id());
        glDrawElements(GL_TRIANGLE_STRIP, GLsizei(s.indexData.size()), GL_UNSIGNED_INT, nullptr);
        glBindVertexArray(0);
        glDisable(GL_PRIMITIVE_RESTART_FIXED_INDEX);
    }
    s.cacheStats(stats);
    return stats;
}

void TiledTerrain::waitForTiles() {
    state_->cache->waitIdle();
}

const TiledRelief& TiledTerrain::relief() const {
    return *state_->relief;
}

const gpu::Program& TiledTerrain::State::program(bool contours) {
    gpu::Program& program = programs[contours ? 1 : 0];
    if (program.id() != 0) return program;
    // IncludeAlias holds views: the names stay in these locals while it builds.
    const std::string file = surface->shaderFile(), base = surface->baseShaderFile();
    const gpu::IncludeAlias aliases[] = {{"surface.glsl", file}, {"surface_base.glsl", base}};
    const std::string defines = surface->defines() +
                                (surface->lit() ? "" : "#define SIERRA_UNLIT 1\n") +
                                (contours ? "#define SIERRA_CONTOURS 1\n" : "");
    program = gpu::Program::create(
        {.vertex = "tiled_terrain.vert",
         .fragment = "tiled_terrain.frag",
         .defines = defines,
         .aliases = std::span<const gpu::IncludeAlias>(aliases, base.empty() ? 1 : 2)});
    return program;
}

void TiledTerrain::setSurface(std::unique_ptr<Surface> surface) {
    SIERRA_CHECK(surface != nullptr, "the tiled terrain needs a surface");
    State& s = *state_;
    std::unique_ptr<Surface> previous = std::move(s.surface);
    std::array<gpu::Program, 2> programs = std::move(s.programs);
    s.surface = std::move(surface);
    s.programs = {};
    try {
        s.program(false);  // a surface that does not compile is refused now
    } catch (...) {
        s.surface = std::move(previous);
        s.programs = std::move(programs);
        throw;
    }
}

terrain::ColourRamp TiledTerrain::surfaceRamp(const RampSurfaceDesc& desc) const {
    return render::surfaceRamp(state_->range / state_->file->info().verticalScale, std::nullopt,
                               desc);
}

}  // namespace sierra::render
