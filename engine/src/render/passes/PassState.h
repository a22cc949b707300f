#pragma once
// The GL state the passes draw with, each set inside the pass's own GlStateScope.

#include <sierra/gpu/Gl.h>

namespace sierra::render {

// Opaque meshes (the terrain, its debug colourings, the depth pass): depth
// tested and written, the nearest fragment wins, both faces drawn, no blending.
inline void setOpaqueMeshState() {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
}

// Overlays: depth-tested against the terrain without writing depth (equal
// depths pass, so lines on the mesh itself show), no face culling, and straight
// alpha blending with the destination's alpha kept for RGBA output.
inline void setOverlayState() {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    glDisable(GL_CULL_FACE);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
}

}  // namespace sierra::render
