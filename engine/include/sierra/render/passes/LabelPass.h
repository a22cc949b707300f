#pragma once
// Dataset labels of the terrain, per pixel, drawn into the pass's own float
// and integer targets (not the frame's) and read back in image order
// (shaders/labels.frag): the unit normal in world axes or rotated into the
// camera's, a terrain-against-sky mask, and the zone ids of a zone surface.
// The same mesh and discard as the depth pass, so the mask covers exactly the
// pixels where DepthPass has a depth.

#include <sierra/gpu/Objects.h>
#include <sierra/gpu/Program.h>
#include <sierra/render/Pass.h>
#include <sierra/render/Surface.h>

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <vector>

namespace sierra::render {

// Zone id of the pixels that show no terrain.
inline constexpr uint8_t kNoZone = 255;

struct LabelImage {
    int width = 0;
    int height = 0;
    // width * height * 3, top row first: unit normals, NaN where no terrain.
    std::vector<float> normals;
    std::vector<uint8_t> mask;  // width * height: 255 terrain, 0 sky
    // width * height: the zone id (palette index), kNoZone where no terrain;
    // all 0 on terrain when the surface has no zones.
    std::vector<uint8_t> zones;
};

class LabelPass final : public Pass {
  public:
    // zoneSurface: a surface whose zone field gives the ids (Surface::zoneIds),
    // or null (ids 0). It must outlive the pass.
    static std::unique_ptr<LabelPass> create(int width, int height,
                                             const Surface* zoneSurface = nullptr);
    const char* name() const override { return "labels"; }
    // The rotation applied to the world normals: identity (world axes, the
    // default) or a camera's world-to-camera rotation.
    void setNormalRotation(const glm::mat3& rotation) { rotation_ = rotation; }
    // Renders into the pass's own targets (the bound framebuffer is untouched).
    void draw(const FrameContext& frame) override;
    // The labels of the last draw().
    LabelImage read() const;
    int width() const { return width_; }
    int height() const { return height_; }

  private:
    int width_ = 0, height_ = 0;
    const Surface* zoneSurface_ = nullptr;
    glm::mat3 rotation_{1.0f};
    gpu::Program program_;
    gpu::Framebuffer fbo_;
    gpu::Texture normals_;
    gpu::Texture zones_;
    gpu::Texture depthBuffer_;
};

}  // namespace sierra::render
