#include <sierra/render/SbtStream.h>

#include "render/SbtBridge.h"
#include <sierra/core/Error.h>
#include <sierra/core/Timer.h>
#include <sierra/render/TerrainGpu.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include <sched.h>

namespace sierra::render {

Lod parseLod(const std::string& name) {
    if (name == "sbt") return Lod::Sbt;
    if (name == "full") return Lod::Full;
    throw Error(msg("unknown level of detail '", name, "': use sbt or full"));
}

const char* lodName(Lod lod) {
    return lod == Lod::Sbt ? "sbt" : lod == Lod::Full ? "full" : "tin";
}

void MeshDraw::draw() const {
    glVertexArrayElementBuffer(vertexArray, elementBuffer);
    glBindVertexArray(vertexArray);
    glEnable(GL_PRIMITIVE_RESTART_FIXED_INDEX);  // 0xFFFFFFFF joins strips
    GL_CHECK(
        glDrawElements(mode, count, GL_UNSIGNED_INT, reinterpret_cast<const void*>(byteOffset)));
}

SbtStream SbtStream::create() {
    SbtStream s;
    s.vao_ = gpu::VertexArray::create();
    s.ring_ = gpu::StreamRing::create();
    return s;
}

MeshDraw SbtStream::prepare(TerrainGpu& terrain, const Camera& camera, int width, int height,
                            const LodSettings& lod, MeshStats& stats) {
    SIERRA_CHECK(lod.tau > 0.0f && std::isfinite(lod.tau),
                 "tau must be a positive number of pixels, got ", lod.tau);
    SIERRA_CHECK(!pending_, "SbtStream::prepare called twice without finishFrame");
    MeshDraw mesh;
    mesh.vertexArray = vao_.id();
    if (lod.lod == Lod::Sbt) {
        float aspect = float(width) / float(height);
        LodView lv = camera.lodView(height);
        SbtView view;
        view.eye = lv.eye;
        view.lambda = lv.lambda;
        view.tau = lod.tau;
        view.cull = lod.cull;
        view.geomorph = lod.geomorph;
        view.planes = camera.frustumPlanes(aspect);
        terrain.prepareSbtView(view);  // once, not counted in the frame's refinement
        Stopwatch sw;
        stats.triangles = terrain.sbt().refineView(view, strip_, lod.threads);
        stats.refineMs = sw.ms();
        stats.refineThreads = terrain.sbt().lastThreads();
        stats.refineCpu = sched_getcpu();
        sw.restart();
        size_t bytes = strip_.size() * sizeof(uint32_t);
        std::span<std::byte> region = ring_.beginFrame(std::max<size_t>(bytes, 4));
        std::memcpy(region.data(), strip_.data(), bytes);
        stats.uploadMs = sw.ms();
        stats.indices = strip_.size();
        stats.bytesUploaded = bytes;
        mesh.mode = GL_TRIANGLE_STRIP;
        mesh.elementBuffer = ring_.buffer();
        mesh.byteOffset = ring_.offset();
        mesh.count = GLsizei(strip_.size());
        pending_ = true;
    } else if (lod.lod == Lod::Mesh) {
        SIERRA_CHECK(terrain.meshIndexCount() > 0,
                     "level of detail 'tin' needs a mesh (TerrainGpu::setMesh)");
        mesh.elementBuffer = terrain.meshIndices().id();
        mesh.count = GLsizei(terrain.meshIndexCount());
        stats.indices = terrain.meshIndexCount();
        stats.triangles = stats.indices / 3;
    } else {
        mesh.elementBuffer = terrain.fullGridIndices().id();
        mesh.count = GLsizei(terrain.fullGridIndexCount());
        stats.indices = terrain.fullGridIndexCount();
        stats.triangles = stats.indices / 3;
    }
    return mesh;
}

void SbtStream::finishFrame() {
    if (pending_) ring_.finishFrame();
    pending_ = false;
}

}  // namespace sierra::render
