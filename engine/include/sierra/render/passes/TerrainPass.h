#pragma once
// The shaded terrain: the mesh with its albedo from one surface (see
// Surface.h), Lambert light and fog. The surface's function is compiled into
// the program (terrain.frag's "surface.glsl" resolved to its file).

#include <sierra/gpu/Program.h>
#include <sierra/render/Pass.h>
#include <sierra/render/Surface.h>

#include <memory>

namespace sierra::render {

class TerrainPass final : public Pass {
public:
    static std::unique_ptr<TerrainPass> create(std::unique_ptr<Surface> surface);
    const char* name() const override { return "terrain"; }
    void draw(const FrameContext& frame) override;

private:
    gpu::Program program_;
    std::unique_ptr<Surface> surface_;
};

}  // namespace sierra::render
