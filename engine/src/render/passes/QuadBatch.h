#pragma once
// Screen-space quads (curvature line segments) drawn as indexed triangles
// instead of instances: quad q is the vertices 4q..4q+3 (the
// shader reads quad = gl_VertexID >> 2, corner = gl_VertexID & 3, corners in
// triangle-strip order), two triangles (0, 1, 2) and (2, 1, 3). One shared
// index buffer of kQuadsPerBatch quads is drawn again with a base vertex for
// every further batch, so its size does not grow with the grid.
//
// Why not instancing: llvmpipe (Mesa 22.3) runs its vertex pipeline once per
// instance, and with one 4-vertex instance per quad that set-up was most of
// the cost of a pass with many quads: hatch strokes drawn so added 42-49% to
// a 1080p frame on a 257^2 terrain, 19-38% as indexed batches (sierra-bench
// frames --overlay-costs, docs/presets.md), with the same pixels. (Hatches
// have since gone further: one point per stroke, hatch_geom.glsl.)

#include <sierra/gpu/Gl.h>
#include <sierra/gpu/Objects.h>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace sierra::render {

inline constexpr GLsizei kQuadsPerBatch = 16384;  // 65536 vertices: 16-bit indices

// The index buffer of one batch, attached to `vao` as its element buffer.
inline gpu::Buffer createQuadIndices(const gpu::VertexArray& vao) {
    std::vector<uint16_t> indices;
    indices.reserve(size_t(kQuadsPerBatch) * 6);
    for (uint32_t q = 0; q < uint32_t(kQuadsPerBatch); ++q)
        for (uint32_t corner : {0u, 1u, 2u, 2u, 1u, 3u})
            indices.push_back(uint16_t(4 * q + corner));
    gpu::Buffer buffer =
        gpu::Buffer::create({.size = indices.size() * sizeof(uint16_t), .data = indices.data()});
    glVertexArrayElementBuffer(vao.id(), buffer.id());
    return buffer;
}

// Draws quads begin..begin+count-1 with the VAO of createQuadIndices() bound.
inline void drawQuads(int64_t begin, int64_t count) {
    for (int64_t first = begin; first < begin + count; first += kQuadsPerBatch) {
        const GLsizei n = GLsizei(std::min<int64_t>(kQuadsPerBatch, begin + count - first));
        glDrawElementsBaseVertex(GL_TRIANGLES, 6 * n, GL_UNSIGNED_SHORT, nullptr, GLint(4 * first));
    }
}

}  // namespace sierra::render
