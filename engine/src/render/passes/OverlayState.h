#pragma once
// The GL state every overlay pass draws with (inside its own GlStateScope):
// depth-tested against the terrain without writing depth (equal depths pass,
// so lines on the mesh itself show), no face culling, and straight alpha
// blending with the destination's alpha kept for RGBA output.

#include <sierra/gpu/Gl.h>

namespace sierra::render {

inline void setOverlayState() {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    glDisable(GL_CULL_FACE);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
}

}  // namespace sierra::render
