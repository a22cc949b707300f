#include <sierra/render/passes/LinePass.h>

#include "render/passes/PassState.h"
#include "render/passes/QuadBatch.h"
#include <sierra/core/Error.h>
#include <sierra/gpu/GlStateScope.h>
#include <sierra/render/TerrainGpu.h>

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace sierra::render {

std::unique_ptr<LinePass> LinePass::create(const analysis::LineSet& lines,
                                           const LinePassDesc& desc) {
    SIERRA_CHECK(std::isfinite(desc.width) && desc.width > 0.0f,
                 "line pass: width must be > 0 pixels, got ", desc.width);
    auto pass = std::make_unique<LinePass>();
    pass->desc_ = desc;
    pass->program_ = gpu::Program::create({.vertex = "line.vert", .fragment = "line.frag"});
    // Two vec4 per segment: (x, z, alpha) of each end, and the polyline's rank
    // for distance thinning (line.vert's Segment): polyline k's is the
    // fractional part of k / golden ratio, so any prefix of ranks [0, f)
    // holds about a fraction f of the polylines, spread over all of them.
    constexpr double kGolden = 0.6180339887498949;  // 1 / golden ratio
    std::vector<float> data;
    for (size_t k = 0; k < lines.polylineCount(); ++k) {
        auto p = lines.polyline(k);
        // Rank 0 is below every cell's threshold: never thinned.
        const float rank = desc.thin ? float(std::fmod(double(k) * kGolden, 1.0)) : 0.0f;
        for (size_t v = 1; v < p.size(); ++v) {
            const analysis::LineVertex& a = p[v - 1];
            const analysis::LineVertex& b = p[v];
            data.insert(data.end(), {a.x, a.z, a.alpha, rank, b.x, b.z, b.alpha, 0.0f});
        }
    }
    pass->segments_ = data.size() / 8;
    if (desc.nearTexelSize > 0.0f)
        for (size_t first = 0; first < pass->segments_; first += kChunkSegments) {
            glm::vec4 box(INFINITY, INFINITY, -INFINITY, -INFINITY);
            const size_t last = std::min(pass->segments_, first + kChunkSegments);
            for (size_t q = first; q < last; ++q)
                for (size_t e : {size_t(0), size_t(4)}) {
                    const float x = data[8 * q + e], z = data[8 * q + e + 1];
                    box = {std::min(box.x, x), std::min(box.y, z), std::max(box.z, x),
                           std::max(box.w, z)};
                }
            pass->chunkBoxes_.push_back(box);
        }
    if (!data.empty())
        pass->buffer_ =
            gpu::Buffer::create({.size = data.size() * sizeof(float), .data = data.data()});
    pass->vao_ = gpu::VertexArray::create();
    pass->quadIndices_ = createQuadIndices(pass->vao_);
    return pass;
}

void LinePass::draw(const FrameContext& frame) {
    if (segments_ == 0) return;
    gpu::GlStateScope scope;
    setOverlayState();
    glUseProgram(program_.id());
    glUniform1f(program_.uniform("uWidth"), desc_.width);
    glUniform4fv(program_.uniform("uColour"), 1, glm::value_ptr(desc_.colour));
    frame.terrain.bind();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer_.id());
    glBindVertexArray(vao_.id());
    if (desc_.nearTexelSize <= 0.0f) {
        drawQuads(0, int64_t(segments_));
        drawn_ = int64_t(segments_);
    } else {
        // A run is drawn when a texel at its box's nearest point to the eye
        // (heights anywhere in the terrain's range) may exceed a pixel.
        const LodView view = frame.camera.lodView(frame.height);
        const glm::vec2 spacing = frame.terrain.spacing(), range = frame.terrain.worldRange();
        const float pixelsAtUnit = desc_.nearTexelSize * view.lambda;
        drawn_ = 0;
        int64_t runStart = -1;
        for (size_t c = 0; c <= chunkBoxes_.size(); ++c) {
            bool near = false;
            if (c < chunkBoxes_.size()) {
                const glm::vec4 b = chunkBoxes_[c];
                const glm::vec3 lo(b.x * spacing.x, range.x, b.y * spacing.y);
                const glm::vec3 hi(b.z * spacing.x, range.y, b.w * spacing.y);
                const float d = glm::length(glm::clamp(view.eye, lo, hi) - view.eye);
                near = pixelsAtUnit > d;
            }
            const int64_t first = int64_t(c) * kChunkSegments;
            if (near && runStart < 0) runStart = first;
            if (!near && runStart >= 0) {
                const int64_t count = std::min<int64_t>(first, int64_t(segments_)) - runStart;
                drawQuads(runStart, count);
                drawn_ += count;
                runStart = -1;
            }
        }
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
}

}  // namespace sierra::render
