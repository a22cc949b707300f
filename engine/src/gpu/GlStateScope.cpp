#include <sierra/gpu/GlStateScope.h>

#include <sierra/core/Error.h>

namespace sierra::gpu {

namespace {

constexpr std::array<GLenum, 14> kCapabilities = {GL_DEPTH_TEST,
                                                  GL_CULL_FACE,
                                                  GL_BLEND,
                                                  GL_SCISSOR_TEST,
                                                  GL_STENCIL_TEST,
                                                  GL_PRIMITIVE_RESTART,
                                                  GL_PRIMITIVE_RESTART_FIXED_INDEX,
                                                  GL_POLYGON_OFFSET_FILL,
                                                  GL_POLYGON_OFFSET_LINE,
                                                  GL_SAMPLE_ALPHA_TO_COVERAGE,
                                                  GL_PROGRAM_POINT_SIZE,
                                                  GL_FRAMEBUFFER_SRGB,
                                                  GL_MULTISAMPLE,
                                                  GL_LINE_SMOOTH};
constexpr std::array<const char*, 14> kCapabilityNames = {"DEPTH_TEST",
                                                          "CULL_FACE",
                                                          "BLEND",
                                                          "SCISSOR_TEST",
                                                          "STENCIL_TEST",
                                                          "PRIMITIVE_RESTART",
                                                          "PRIMITIVE_RESTART_FIXED_INDEX",
                                                          "POLYGON_OFFSET_FILL",
                                                          "POLYGON_OFFSET_LINE",
                                                          "SAMPLE_ALPHA_TO_COVERAGE",
                                                          "PROGRAM_POINT_SIZE",
                                                          "FRAMEBUFFER_SRGB",
                                                          "MULTISAMPLE",
                                                          "LINE_SMOOTH"};
constexpr std::array<GLenum, 3> kTextureTargets = {GL_TEXTURE_1D, GL_TEXTURE_2D,
                                                   GL_TEXTURE_2D_ARRAY};
constexpr std::array<GLenum, 3> kTextureBindings = {GL_TEXTURE_BINDING_1D, GL_TEXTURE_BINDING_2D,
                                                    GL_TEXTURE_BINDING_2D_ARRAY};

void setEnabled(GLenum cap, GLboolean on) {
    on ? glEnable(cap) : glDisable(cap);
}

template <typename T, size_t N>
std::string list(const std::array<T, N>& a) {
    std::string s;
    for (size_t k = 0; k < N; ++k) s += msg(k ? "," : "", +a[k]);
    return s;
}

}  // namespace

GlState GlState::capture() {
    GlState s;
    for (size_t k = 0; k < kCapabilities.size(); ++k) s.enabled[k] = glIsEnabled(kCapabilities[k]);
    glGetIntegerv(GL_DEPTH_FUNC, &s.depthFunc);
    glGetBooleanv(GL_DEPTH_WRITEMASK, &s.depthMask);
    glGetBooleanv(GL_COLOR_WRITEMASK, s.colourMask.data());
    glGetIntegerv(GL_BLEND_SRC_RGB, &s.blend[0]);
    glGetIntegerv(GL_BLEND_DST_RGB, &s.blend[1]);
    glGetIntegerv(GL_BLEND_SRC_ALPHA, &s.blend[2]);
    glGetIntegerv(GL_BLEND_DST_ALPHA, &s.blend[3]);
    glGetIntegerv(GL_BLEND_EQUATION_RGB, &s.blend[4]);
    glGetIntegerv(GL_BLEND_EQUATION_ALPHA, &s.blend[5]);
    glGetIntegerv(GL_POLYGON_MODE, s.polygonMode.data());
    glGetFloatv(GL_POLYGON_OFFSET_FACTOR, &s.polygonOffsetFactor);
    glGetFloatv(GL_POLYGON_OFFSET_UNITS, &s.polygonOffsetUnits);
    glGetIntegerv(GL_CULL_FACE_MODE, &s.cullFace);
    glGetIntegerv(GL_FRONT_FACE, &s.frontFace);
    glGetIntegerv(GL_CURRENT_PROGRAM, &s.program);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &s.vertexArray);
    glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &s.arrayBuffer);
    glGetIntegerv(GL_UNIFORM_BUFFER_BINDING, &s.uniformBuffer);
    for (int k = 0; k < kUniformBindings; ++k)
        glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, GLuint(k), &s.uniformBindings[size_t(k)]);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &s.activeTexture);
    for (int unit = 0; unit < kTextureUnits; ++unit) {
        glActiveTexture(GLenum(GL_TEXTURE0 + unit));
        for (size_t t = 0; t < kTextureTargets.size(); ++t)
            glGetIntegerv(kTextureBindings[t], &s.textures[size_t(unit)][t]);
    }
    glActiveTexture(GLenum(s.activeTexture));
    glGetIntegerv(GL_PACK_ALIGNMENT, &s.packAlignment);
    glGetIntegerv(GL_UNPACK_ALIGNMENT, &s.unpackAlignment);
    glGetIntegerv(GL_VIEWPORT, s.viewport.data());
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &s.drawFramebuffer);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &s.readFramebuffer);
    glGetFloatv(GL_COLOR_CLEAR_VALUE, s.clearColour.data());
    glGetDoublev(GL_DEPTH_CLEAR_VALUE, &s.clearDepth);
    return s;
}

void GlState::restore() const {
    for (size_t k = 0; k < kCapabilities.size(); ++k) setEnabled(kCapabilities[k], enabled[k]);
    glDepthFunc(GLenum(depthFunc));
    glDepthMask(depthMask);
    glColorMask(colourMask[0], colourMask[1], colourMask[2], colourMask[3]);
    glBlendFuncSeparate(GLenum(blend[0]), GLenum(blend[1]), GLenum(blend[2]), GLenum(blend[3]));
    glBlendEquationSeparate(GLenum(blend[4]), GLenum(blend[5]));
    // Core profile sets both faces at once; the two values are always equal there.
    glPolygonMode(GL_FRONT_AND_BACK, GLenum(polygonMode[0]));
    glPolygonOffset(polygonOffsetFactor, polygonOffsetUnits);
    glCullFace(GLenum(cullFace));
    glFrontFace(GLenum(frontFace));
    // A program deleted while it was current lives on only as long as it stays
    // current: once a pass has used another, its name is gone and binding it
    // again is an error. The state then is no program, as GL itself leaves it.
    glUseProgram(program != 0 && glIsProgram(GLuint(program)) ? GLuint(program) : 0);
    // Any other object deleted in the meantime was unbound by GL itself, from
    // every binding of this context; binding its name again would be an error
    // (or bind an unrelated object that has reused the name). Its binding
    // stays 0, as GL left it.
    auto live = [](GLint name, GLboolean (*isObject)(GLuint)) {
        return name != 0 && isObject(GLuint(name)) ? GLuint(name) : 0u;
    };
    glBindVertexArray(live(vertexArray, glIsVertexArray));
    glBindBuffer(GL_ARRAY_BUFFER, live(arrayBuffer, glIsBuffer));
    for (int k = 0; k < kUniformBindings; ++k)
        glBindBufferBase(GL_UNIFORM_BUFFER, GLuint(k),
                         live(uniformBindings[size_t(k)], glIsBuffer));
    glBindBuffer(GL_UNIFORM_BUFFER, live(uniformBuffer, glIsBuffer));
    for (int unit = 0; unit < kTextureUnits; ++unit) {
        glActiveTexture(GLenum(GL_TEXTURE0 + unit));
        for (size_t t = 0; t < kTextureTargets.size(); ++t)
            glBindTexture(kTextureTargets[t], live(textures[size_t(unit)][t], glIsTexture));
    }
    glActiveTexture(GLenum(activeTexture));
    glPixelStorei(GL_PACK_ALIGNMENT, packAlignment);
    glPixelStorei(GL_UNPACK_ALIGNMENT, unpackAlignment);
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, live(drawFramebuffer, glIsFramebuffer));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, live(readFramebuffer, glIsFramebuffer));
    glClearColor(clearColour[0], clearColour[1], clearColour[2], clearColour[3]);
    glClearDepth(clearDepth);
}

std::string GlState::differences(const GlState& o) const {
    std::string out;
    auto field = [&](const char* name, const auto& a, const auto& b) {
        if (!(a == b)) out += msg(name, ": ", a, " -> ", b, "\n");
    };
    auto array = [&](const char* name, const auto& a, const auto& b) {
        if (!(a == b)) out += msg(name, ": ", list(a), " -> ", list(b), "\n");
    };
    for (size_t k = 0; k < enabled.size(); ++k)
        field(kCapabilityNames[k], int(enabled[k]), int(o.enabled[k]));
    field("depth func", depthFunc, o.depthFunc);
    field("depth mask", int(depthMask), int(o.depthMask));
    array("colour mask", colourMask, o.colourMask);
    array("blend", blend, o.blend);
    array("polygon mode", polygonMode, o.polygonMode);
    field("polygon offset factor", polygonOffsetFactor, o.polygonOffsetFactor);
    field("polygon offset units", polygonOffsetUnits, o.polygonOffsetUnits);
    field("cull face", cullFace, o.cullFace);
    field("front face", frontFace, o.frontFace);
    field("program", program, o.program);
    field("vertex array", vertexArray, o.vertexArray);
    field("array buffer", arrayBuffer, o.arrayBuffer);
    field("uniform buffer", uniformBuffer, o.uniformBuffer);
    array("uniform bindings", uniformBindings, o.uniformBindings);
    field("active texture", activeTexture, o.activeTexture);
    for (int unit = 0; unit < kTextureUnits; ++unit)
        if (textures[size_t(unit)] != o.textures[size_t(unit)])
            out += msg("texture unit ", unit, " (1D,2D,2D array): ", list(textures[size_t(unit)]),
                       " -> ", list(o.textures[size_t(unit)]), "\n");
    field("pack alignment", packAlignment, o.packAlignment);
    field("unpack alignment", unpackAlignment, o.unpackAlignment);
    array("viewport", viewport, o.viewport);
    field("draw framebuffer", drawFramebuffer, o.drawFramebuffer);
    field("read framebuffer", readFramebuffer, o.readFramebuffer);
    array("clear colour", clearColour, o.clearColour);
    field("clear depth", clearDepth, o.clearDepth);
    return out;
}

}  // namespace sierra::gpu
