#include <sierra/render/CurvatureGpu.h>

#include <sierra/core/Error.h>
#include <sierra/gpu/GlStateScope.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace sierra::render {

namespace {

std::string define(const char* name, int value) {
    return std::string("#define ") + name + " " + std::to_string(value) + "\n";
}

// A buffer texture over all of `buffer` (texelFetch by linear index in the shaders).
gpu::Texture bufferTexture(const gpu::Buffer& buffer, GLenum format) {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_BUFFER, 1, &id);
    glTextureBuffer(id, format, buffer.id());
    return gpu::Texture(id, gpu::kAdopt);
}

// An RGBA32F 2D array texture of `layers` layers, and unless `framebuffer`
// is null a framebuffer with layer k as colour attachment k, all drawn.
void layeredTarget(int width, int height, int layers, gpu::Texture& texture,
                   gpu::Framebuffer* framebuffer) {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &id);
    glTextureStorage3D(id, 1, GL_RGBA32F, width, height, layers);
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    texture = gpu::Texture(id, gpu::kAdopt);
    if (!framebuffer) return;
    *framebuffer = gpu::Framebuffer::create();
    std::vector<GLenum> buffers;
    for (int k = 0; k < layers; ++k) {
        glNamedFramebufferTextureLayer(framebuffer->id(), GLenum(GL_COLOR_ATTACHMENT0 + k), id, 0,
                                       k);
        buffers.push_back(GLenum(GL_COLOR_ATTACHMENT0 + k));
    }
    glNamedFramebufferDrawBuffers(framebuffer->id(), layers, buffers.data());
    framebuffer->checkComplete("GPU curvature");
}

// Stencil function and write mask of both faces.
struct StencilState {
    GLint values[2][4] = {};  // front, back: function, reference, value mask, write mask

    static StencilState capture() {
        static constexpr GLenum kNames[2][4] = {
            {GL_STENCIL_FUNC, GL_STENCIL_REF, GL_STENCIL_VALUE_MASK, GL_STENCIL_WRITEMASK},
            {GL_STENCIL_BACK_FUNC, GL_STENCIL_BACK_REF, GL_STENCIL_BACK_VALUE_MASK,
             GL_STENCIL_BACK_WRITEMASK}};
        StencilState s;
        for (int f = 0; f < 2; ++f)
            for (int k = 0; k < 4; ++k) glGetIntegerv(kNames[f][k], &s.values[f][k]);
        return s;
    }
    void restore() const {
        for (int f = 0; f < 2; ++f) {
            const GLenum face = f == 0 ? GL_FRONT : GL_BACK;
            const GLint* v = values[f];
            glStencilFuncSeparate(face, GLenum(v[0]), v[1], GLuint(v[2]));
            glStencilMaskSeparate(face, GLuint(v[3]));
        }
    }
};

}  // namespace

CurvatureGpu::Path CurvatureGpu::defaultPath() {
    const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const std::string name = renderer ? renderer : "";
    const bool software =
        name.find("llvmpipe") != std::string::npos || name.find("softpipe") != std::string::npos;
    return software ? Path::Fragment : Path::Compute;
}

CurvatureGpu CurvatureGpu::create(const terrain::Heightfield& field, std::optional<Path> path) {
    SIERRA_CHECK(!field.empty(), "GPU curvature: the heightfield is empty");
    CurvatureGpu c;
    c.path_ = path.value_or(defaultPath());
    if (c.path_ == Path::Fragment) {
        GLint drawBuffers = 0;
        glGetIntegerv(GL_MAX_DRAW_BUFFERS, &drawBuffers);
        SIERRA_CHECK(drawBuffers >= kRun, "GPU curvature: the driver draws to ", drawBuffers,
                     " colour attachments at once, ", kRun, " needed");
    }
    c.width_ = field.width();
    c.height_ = field.height();
    c.spacingX_ = field.spacingX();
    c.spacingZ_ = field.spacingZ();
    // A row and a float of padding before each row, and the whole last run
    // and a float after it: every run's window (samples -1 ... kRun of rows
    // -1 ... +1) lies inside the buffer and starts a texel.
    c.pitch_ = (c.runs() * kRun + 2 + 3) / 4 * 4;
    const size_t floats = size_t(c.pitch_) * size_t(c.height_ + 2);
    GLint maxSide = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSide);
    SIERRA_CHECK(c.height_ <= maxSide, "GPU curvature: a ", c.width_, "x", c.height_,
                 " grid has more rows than the driver's textures (", maxSide, ")");
    GLint maxTexels = 0;
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
    SIERRA_CHECK(floats <= size_t(maxTexels), "GPU curvature: a ", c.width_, "x", c.height_,
                 " grid has more samples than the driver's buffer textures hold (", maxTexels, ")");

    std::vector<float> heights(floats, 0.0f);
    const float scale = field.verticalScale();
    const bool masked = field.hasMask();
    auto mask = field.mask();
    auto raw = field.samples();
    for (int j = 0; j < c.height_; ++j) {
        for (int i = 0; i < c.width_; ++i) {
            const size_t k = size_t(j) * size_t(c.width_) + size_t(i);
            const float y = masked && !mask[k] ? NAN : raw[k] * scale;
            c.noData_ = c.noData_ || std::isnan(y);
            heights[size_t(j + 1) * size_t(c.pitch_) + size_t(i) + 1] = y;
        }
    }
    c.heights_ =
        gpu::Buffer::create({.size = heights.size() * sizeof(float), .data = heights.data()});
    c.heightsTexture_ = bufferTexture(c.heights_, GL_R32F);
    c.heights4Texture_ = bufferTexture(c.heights_, GL_RGBA32F);
    const bool fragment = c.path_ == Path::Fragment;
    layeredTarget(c.runs(), c.height_, kRun, c.fieldTexture_,
                  fragment ? &c.fieldFramebuffer_ : nullptr);
    layeredTarget(c.runs(), c.height_, kRun / 2, c.gradientTexture_,
                  fragment ? &c.gradientFramebuffer_ : nullptr);
    if (fragment && c.noData_) {
        const std::vector<uint8_t> clearance = runClearance(heights, c.width_, c.height_, c.pitch_);
        c.clearance_ = gpu::Texture::create({.format = GL_STENCIL_INDEX8,
                                             .width = c.runs(),
                                             .height = c.height_,
                                             .filter = GL_NEAREST});
        c.clearance_.upload(GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, clearance.data());
        for (gpu::Framebuffer* f : {&c.fieldFramebuffer_, &c.gradientFramebuffer_}) {
            glNamedFramebufferTexture(f->id(), GL_STENCIL_ATTACHMENT, c.clearance_.id(), 0);
            f->checkComplete("GPU curvature");
        }
    }
    c.vertexArray_ = gpu::VertexArray::create();
    return c;
}

std::vector<uint8_t> CurvatureGpu::runClearance(const std::vector<float>& heights, int width,
                                                int height, int pitch) {
    constexpr int kFar = kMaxRunDistance + 1;
    const int runs = (width + kRun - 1) / kRun;
    // Per row: each run's horizontal distance to the row's nearest no-data
    // sample (0 with one inside the run, kNoDataRun when all are), at most kFar.
    std::vector<uint8_t> across(size_t(runs) * size_t(height));
    std::vector<int> before(size_t(width) + 1), after(size_t(width) + 1), count(size_t(width) + 1);
    for (int j = 0; j < height; ++j) {
        const float* row = &heights[size_t(j + 1) * size_t(pitch) + 1];
        // before[i]: the last no-data sample < i (or -kFar - 1); after[i]:
        // the first >= i; count[i]: the no-data samples < i.
        before[0] = -kFar - 1;
        for (int i = 0; i < width; ++i) {
            const bool none = std::isnan(row[i]);
            before[size_t(i) + 1] = none ? i : before[size_t(i)];
            count[size_t(i) + 1] = count[size_t(i)] + (none ? 1 : 0);
        }
        after[size_t(width)] = width + kFar + kRun;
        for (int i = width - 1; i >= 0; --i)
            after[size_t(i)] = std::isnan(row[i]) ? i : after[size_t(i) + 1];
        for (int c = 0; c < runs; ++c) {
            const int lo = c * kRun, hi = std::min(width, lo + kRun);  // the run's samples
            const int inside = count[size_t(hi)] - count[size_t(lo)];
            int d = 0;
            if (inside == 0)
                d = std::min({kFar, lo - before[size_t(lo)], after[size_t(hi)] - (lo + kRun - 1)});
            else if (inside == hi - lo)
                d = kNoDataRun;
            across[size_t(j) * size_t(runs) + size_t(c)] = uint8_t(d);
        }
    }
    // Rows within kFar: the window of reach R around (c, j) is clear iff
    // every row j' within R has across > R, i.e. max(across, |j' - j|) > R.
    std::vector<uint8_t> out(across.size());
    for (int j = 0; j < height; ++j)
        for (int c = 0; c < runs; ++c) {
            const size_t k = size_t(j) * size_t(runs) + size_t(c);
            int v = across[k];
            if (v != kNoDataRun) {
                v = kFar;
                for (int y = std::max(0, j - kFar); y <= std::min(height - 1, j + kFar); ++y) {
                    const int a = across[size_t(y) * size_t(runs) + size_t(c)];
                    v = std::min(v, std::max(a == kNoDataRun ? 0 : a, std::abs(y - j)));
                }
            }
            out[k] = uint8_t(v);
        }
    return out;
}

void CurvatureGpu::draw(const Pass& pass, int layers, bool gradient) {
    auto drawIn = [&](gpu::Program& p, int x, int y, int w, int h) {
        if (w <= 0 || h <= 0) return;
        glUseProgram(p.id());
        setGridUniforms(p);
        glScissor(x, y, w, h);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    };
    const int cols = runs();
    if (!pass.runs) {
        drawIn(*pass.general, 0, 0, cols, height_);
        return;
    }
    // Rows R ... height - 1 - R in runs (their first and last R samples
    // wrong), the first and last R rows per sample, then the first and the
    // last R samples of the other rows alone, every other output masked.
    // (compute() checks that both sides have at least 2R + 1 samples.)
    const int r = pass.reach;
    if (clearance_) {
        // With no data: the runs where the window is clear of it (the
        // stencil in R + 1 ... kNoDataRun - 1), NaN where the run has no
        // data at all (kNoDataRun), the general program elsewhere (0 ... R).
        static_assert(kNoDataRun == 0x80 && kMaxRunDistance < 0x7f);
        glEnable(GL_STENCIL_TEST);
        glStencilFunc(GL_LESS, r, 0x7f);  // R < stencil, kNoDataRun read as 0
        drawIn(*pass.runs, 0, r, cols, height_ - 2 * r);
        glStencilFunc(GL_GEQUAL, r, 0xff);
        drawIn(*pass.general, 0, r, cols, height_ - 2 * r);
        glStencilFunc(GL_EQUAL, kNoDataRun, 0xff);
        drawIn(*pass.noData, 0, r, cols, height_ - 2 * r);
        glDisable(GL_STENCIL_TEST);
    } else {
        drawIn(*pass.runs, 0, r, cols, height_ - 2 * r);
    }
    drawIn(*pass.general, 0, 0, cols, r);
    drawIn(*pass.general, 0, height_ - r, cols, r);
    for (int e = 0; e < 2 * r; ++e) {
        const int x = e < r ? e : width_ - 2 * r + e;
        const int k = x % kRun;
        for (int b = 0; b < layers; ++b)
            glColorMaski(GLuint(b), GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        if (gradient) {
            const GLboolean even = k % 2 == 0 ? GL_TRUE : GL_FALSE, odd = even ? GL_FALSE : GL_TRUE;
            glColorMaski(GLuint(k / 2), even, even, odd, odd);
        } else {
            glColorMaski(GLuint(k), GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        }
        glUseProgram(pass.oneSample->id());
        glUniform1i(pass.oneSample->uniform("uSample"), k);
        drawIn(*pass.oneSample, x / kRun, r, 1, height_ - 2 * r);
    }
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

std::string CurvatureGpu::gradientDefines(analysis::NormalMethod normals) const {
    return define("CURVATURE_PITCH", pitch_) + define("CURVATURE_RUNS_PER_ROW", runs()) +
           define("CURVATURE_NORMALS", int(normals)) + "#define CURVATURE_GRADIENT 1\n";
}

std::string CurvatureGpu::fieldDefines(const analysis::CurvatureOptions& o) const {
    return define("CURVATURE_PITCH", pitch_) + define("CURVATURE_RUNS_PER_ROW", runs()) +
           define("CURVATURE_METHOD", int(o.method)) +
           (o.levels.enabled ? "#define CURVATURE_LEVELS 1\n" : "");
}

void CurvatureGpu::setGridUniforms(const gpu::Program& p) const {
    glUniform2i(p.uniform("uSize"), width_, height_);
    glUniform2f(p.uniform("uSpacing"), spacingX_, spacingZ_);
}

void CurvatureGpu::setFieldUniforms(const gpu::Program& p, const analysis::CurvatureOptions& o) {
    glUseProgram(p.id());
    glUniform1i(p.uniform("uDistance"), o.distance);
    glUniform1f(p.uniform("uScale"), o.scale);
    glUniform4f(p.uniform("uLevels"), o.levels.enabled ? 1.0f : 0.0f, o.levels.black,
                o.levels.white, o.levels.gamma);
    glUniform1i(p.uniform("uSigned"), o.signedValues ? 1 : 0);
    glUniform1i(p.uniform("uSecond"),
                o.output == analysis::CurvatureOutput::SecondDerivative ? 1 : 0);
}

void CurvatureGpu::ensureGradientCopy() {
    if (gradientCopy_) return;
    const size_t texels = size_t(runs()) * size_t(height_) * (kRun / 2);
    gradientCopy_ = gpu::Buffer::create({.size = texels * 4 * sizeof(float)});
    gradientCopyTexture_ = bufferTexture(gradientCopy_, GL_RGBA32F);
}

void CurvatureGpu::dispatch(const analysis::CurvatureOptions& o, bool normalBased, bool gradients) {
    auto build = [](gpu::Program& p, const std::string& defines) -> gpu::Program& {
        if (!p) p = gpu::Program::create({.compute = "curvature.comp", .defines = defines});
        return p;
    };
    // Image units 0 and 1 as they were (not part of GlState).
    struct ImageBinding {
        GLint name = 0, level = 0, layered = 0, layer = 0, access = GL_READ_ONLY,
              format = GL_RGBA32F;
    } saved[2];
    for (GLuint u = 0; u < 2; ++u) {
        glGetIntegeri_v(GL_IMAGE_BINDING_NAME, u, &saved[u].name);
        glGetIntegeri_v(GL_IMAGE_BINDING_LEVEL, u, &saved[u].level);
        glGetIntegeri_v(GL_IMAGE_BINDING_LAYERED, u, &saved[u].layered);
        glGetIntegeri_v(GL_IMAGE_BINDING_LAYER, u, &saved[u].layer);
        glGetIntegeri_v(GL_IMAGE_BINDING_ACCESS, u, &saved[u].access);
        glGetIntegeri_v(GL_IMAGE_BINDING_FORMAT, u, &saved[u].format);
    }
    auto groups = [](int n) { return GLuint((n + 7) / 8); };
    if (gradients) {
        gpu::Program& p =
            build(gradientComputePrograms_[size_t(o.normals)], gradientDefines(o.normals));
        glUseProgram(p.id());
        setGridUniforms(p);
        glUniform1i(p.uniform("uGradientCopy"), normalBased ? 1 : 0);
        glBindImageTexture(0, gradientTexture_.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        if (normalBased)
            glBindImageTexture(1, gradientCopyTexture_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY,
                               GL_RGBA32F);
        glDispatchCompute(groups(runs() * kRun / 2), groups(height_), 1);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }
    gpu::Program& p =
        build(fieldComputePrograms_[size_t(o.method)][o.levels.enabled ? 1 : 0], fieldDefines(o));
    setFieldUniforms(p, o);
    setGridUniforms(p);
    glBindTextureUnit(1, gradientCopyTexture_.id());
    glBindImageTexture(0, fieldTexture_.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glDispatchCompute(groups(runs() * kRun), groups(height_), 1);
    // The field is read by texel fetches (the overlays), texture reads
    // (read()) and anything else a caller may do next.
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
    for (GLuint u = 0; u < 2; ++u)
        glBindImageTexture(u, GLuint(saved[u].name), saved[u].level, GLboolean(saved[u].layered),
                           saved[u].layer, GLenum(saved[u].access), GLenum(saved[u].format));
}

void CurvatureGpu::compute(const analysis::CurvatureOptions& o, bool tangentPlanes) {
    analysis::validate(o);
    const int minSide = std::max(3, 2 * o.distance + 1);
    SIERRA_CHECK(width_ >= minSide && height_ >= minSide, "curvature: a ", width_, "x", height_,
                 " grid is too small for reinforcement distance ", o.distance,
                 " (each side needs at least ", minSide, " samples)");
    const bool normalBased = o.method == analysis::CurvatureMethod::TwoNormal ||
                             o.method == analysis::CurvatureMethod::ThreeNormal;
    if (path_ == Path::Compute) {
        if (normalBased) ensureGradientCopy();
        gpu::GlStateScope scope;
        glBindTextureUnit(2, heightsTexture_.id());
        glBindTextureUnit(3, heights4Texture_.id());
        dispatch(o, normalBased, normalBased || tangentPlanes);
        return;
    }
    // Runs over the interior where the formulas need no border rule and no
    // no-data checks: always for the gradients, for the field up to
    // kMaxRunDistance.
    const bool fieldRuns = o.distance <= kMaxRunDistance;
    const std::string method = fieldDefines(o), normals = gradientDefines(o.normals);
    auto build = [](gpu::Program& p, const std::string& defines) -> gpu::Program& {
        if (!p)
            p = gpu::Program::create(
                {.vertex = "solid.vert", .fragment = "curvature.frag", .defines = defines});
        return p;
    };
    const std::string runsDefine = "#define CURVATURE_RUNS 1\n";
    const std::string oneSampleDefine = "#define CURVATURE_ONE_SAMPLE 1\n";
    const std::string noDataDefine = "#define CURVATURE_NO_DATA 1\n";
    gpu::GlStateScope scope;
    GLint scissor[4] = {};  // not part of GlState
    glGetIntegerv(GL_SCISSOR_BOX, scissor);
    for (GLenum cap : {GL_DEPTH_TEST, GL_BLEND, GL_CULL_FACE, GL_STENCIL_TEST}) glDisable(cap);
    glEnable(GL_SCISSOR_TEST);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    // The stencil state draw() sets with clearance_ (not part of GlState),
    // read with a framebuffer that has a stencil bound (the reference reads
    // back clamped to the bound stencil's range); tests only, no writes.
    StencilState stencil;
    if (clearance_) {
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fieldFramebuffer_.id());
        stencil = StencilState::capture();
        glStencilMask(0);
    }
    glViewport(0, 0, runs(), height_);
    glBindVertexArray(vertexArray_.id());
    glBindTextureUnit(2, heightsTexture_.id());
    glBindTextureUnit(3, heights4Texture_.id());
    if (normalBased || tangentPlanes) {
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, gradientFramebuffer_.id());
        const size_t n = size_t(o.normals);
        Pass pass{.general = &build(gradientPrograms_[n], normals),
                  .runs = &build(gradientRunPrograms_[n], normals + runsDefine),
                  .oneSample = &build(gradientSamplePrograms_[n], normals + oneSampleDefine)};
        if (clearance_) pass.noData = &build(gradientNoDataProgram_, normals + noDataDefine);
        draw(pass, kRun / 2, true);
        if (normalBased) {
            // A copy the field pass reads as a buffer texture (see curvature.frag), made on first
            // use.
            ensureGradientCopy();
            GLint packBuffer = 0;  // not part of GlState
            glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &packBuffer);
            glBindBuffer(GL_PIXEL_PACK_BUFFER, gradientCopy_.id());
            glPixelStorei(GL_PACK_ALIGNMENT, 4);
            glGetTextureImage(gradientTexture_.id(), 0, GL_RGBA, GL_FLOAT,
                              GLsizei(gradientCopy_.size()), nullptr);
            glBindBuffer(GL_PIXEL_PACK_BUFFER, GLuint(packBuffer));
            glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
        }
    }
    const size_t m = size_t(o.method), l = o.levels.enabled ? 1 : 0;
    Pass pass{.general = &build(fieldPrograms_[m][l], method)};
    if (clearance_) pass.noData = &build(fieldNoDataProgram_, fieldDefines({}) + noDataDefine);
    if (fieldRuns) {
        pass.runs = &build(fieldRunPrograms_[m][l][size_t(o.distance - 1)],
                           method + runsDefine + define("CURVATURE_RUN_DISTANCE", o.distance));
        pass.oneSample = &build(fieldSamplePrograms_[m][l], method + oneSampleDefine);
        pass.reach = o.distance;
    }
    for (gpu::Program* p : {pass.general, pass.runs, pass.oneSample})
        if (p) setFieldUniforms(*p, o);
    glBindTextureUnit(1, gradientCopyTexture_.id());
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fieldFramebuffer_.id());
    draw(pass, kRun, false);
    glScissor(scissor[0], scissor[1], scissor[2], scissor[3]);
    if (clearance_) stencil.restore();
}

analysis::CurvatureField CurvatureGpu::read() const {
    analysis::CurvatureField out;
    out.width = width_;
    out.height = height_;
    out.spacingX = spacingX_;
    out.spacingZ = spacingZ_;
    out.values.resize(size_t(width_) * size_t(height_) * analysis::kDirectionCount);
    const size_t cols = size_t(runs()), rows = size_t(height_);
    std::vector<float> layers(cols * rows * kRun * 4);
    gpu::GlStateScope scope;
    GLint packBuffer = 0;  // not part of GlState
    glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &packBuffer);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glGetTextureImage(fieldTexture_.id(), 0, GL_RGBA, GL_FLOAT,
                      GLsizei(layers.size() * sizeof(float)), layers.data());
    glBindBuffer(GL_PIXEL_PACK_BUFFER, GLuint(packBuffer));
    // Texel (i / kRun, j) of layer i % kRun to sample (i, j).
    for (size_t j = 0; j < rows; ++j) {
        for (size_t i = 0; i < size_t(width_); ++i) {
            const float* t = &layers[((i % kRun * rows + j) * cols + i / kRun) * 4];
            std::copy(t, t + 4, &out.values[(j * size_t(width_) + i) * 4]);
        }
    }
    return out;
}

}  // namespace sierra::render
