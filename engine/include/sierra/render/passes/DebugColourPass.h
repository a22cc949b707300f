#pragma once
// Debug colourings of the terrain in place of its shaded surface: each
// triangle in one flat, unlit colour for its SBT level or for the screen-space
// error of its split vertex (a heat map), computed per triangle in a geometry
// stage from the three grid indices (see shaders/debug_colour_geom.glsl).

#include <sierra/gpu/Program.h>
#include <sierra/render/Pass.h>

#include <memory>
#include <string>

namespace sierra::render {

enum class ColourBy { Surface, Level, Error };

// "surface", "level" or "error"; throws otherwise.
ColourBy parseColourBy(const std::string& name);
const char* colourByName(ColourBy mode);

class DebugColourPass final : public Pass {
  public:
    static std::unique_ptr<DebugColourPass> create();
    const char* name() const override { return "debug-colour"; }
    void setMode(ColourBy mode) { mode_ = mode; }
    void draw(const FrameContext& frame) override;

  private:
    gpu::Program program_;
    GLint modeLocation_ = -1;
    ColourBy mode_ = ColourBy::Level;
};

}  // namespace sierra::render
