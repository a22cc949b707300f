#include "render/SbtBridge.h"

#include <sierra/core/Error.h>
#include <sierra/sbt/Morph.h>
#include <sierra/sbt/Refiner.h>
#include <sierra/sbt/VertexErrors.h>

namespace sierra::render {

struct SbtBridge::State {
    sbt::VertexErrors errors;
    std::vector<float> morphBase;
    std::unique_ptr<sbt::Refiner> refiner;
    sbt::StripMesh mesh;  // reused every frame
    const terrain::Heightfield* field = nullptr;
};

SbtBridge::SbtBridge(const terrain::Heightfield& field, int threads)
    : state_(std::make_unique<State>()) {
    state_->field = &field;
    state_->errors = sbt::computeVertexErrors(field, threads);
    state_->morphBase = sbt::buildMorphBase(field, threads);
    state_->refiner =
        std::make_unique<sbt::Refiner>(field, state_->errors, sbt::RefinerDesc{.threads = threads});
}

namespace {
// The refiner's view for a renderer's: geomorphing refines at
// sbt::refinementTau(tau).
sbt::ViewParams refinerView(const SbtView& view) {
    sbt::ViewParams params;
    params.eye = {view.eye.x, view.eye.y, view.eye.z};
    params.lambda = view.lambda;
    params.tau = view.geomorph ? sbt::refinementTau(view.tau) : view.tau;
    params.cull = view.cull;
    for (size_t k = 0; k < 6; ++k)
        params.planes[k] = {view.planes[k].x, view.planes[k].y, view.planes[k].z, view.planes[k].w};
    return params;
}
}  // namespace

void SbtBridge::prepareView(const SbtView& view) {
    const sbt::ViewParams params = refinerView(view);
    state_->refiner->prepareView(double(params.lambda) / double(params.tau));
}

SbtBridge::~SbtBridge() = default;
std::span<const float> SbtBridge::errors() const {
    return state_->errors.error;
}
const terrain::Heightfield& SbtBridge::field() const {
    return *state_->field;
}
std::span<const float> SbtBridge::radii() const {
    return state_->errors.radius;
}
std::span<const float> SbtBridge::morphBase() const {
    return state_->morphBase;
}
size_t SbtBridge::keyBytes() const {
    return state_->refiner->keyBytes();
}
void SbtBridge::releaseMorphBase() {
    std::vector<float>().swap(state_->morphBase);
}

uint64_t SbtBridge::refineView(const SbtView& view, std::vector<uint32_t>& out, int threads) {
    const sbt::ViewParams params = refinerView(view);
    state_->refiner->setThreads(threads);
    // Refine into the bridge's own mesh and swap buffers with the caller, so
    // both vectors keep their capacity from frame to frame.
    state_->mesh.indices.swap(out);
    state_->refiner->refineView(params, state_->mesh);
    state_->mesh.indices.swap(out);
    return uint64_t(state_->mesh.triangleCount);
}

int64_t SbtBridge::lastCulledSubtrees() const {
    return state_->mesh.culledSubtrees;
}

int SbtBridge::lastThreads() const {
    return state_->mesh.threads;
}

std::vector<uint32_t> SbtBridge::fullGridTriangles() const {
    sbt::StripMesh full;
    state_->refiner->refineFixed(-1.0f, full);
    std::vector<std::array<uint32_t, 3>> triangles = sbt::decodeStrip(full.indices);
    std::vector<uint32_t> flat;
    flat.reserve(triangles.size() * 3);
    for (const auto& t : triangles) flat.insert(flat.end(), t.begin(), t.end());
    return flat;
}

}  // namespace sierra::render
