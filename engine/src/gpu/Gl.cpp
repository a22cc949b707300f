#include <sierra/gpu/Gl.h>

#include <sierra/core/Error.h>

namespace sierra::gpu {

std::string glErrorName(GLenum error) {
    switch (error) {
        case GL_NO_ERROR:
            return "GL_NO_ERROR";
        case GL_INVALID_ENUM:
            return "GL_INVALID_ENUM";
        case GL_INVALID_VALUE:
            return "GL_INVALID_VALUE";
        case GL_INVALID_OPERATION:
            return "GL_INVALID_OPERATION";
        case GL_INVALID_FRAMEBUFFER_OPERATION:
            return "GL_INVALID_FRAMEBUFFER_OPERATION";
        case GL_OUT_OF_MEMORY:
            return "GL_OUT_OF_MEMORY";
        case GL_STACK_OVERFLOW:
            return "GL_STACK_OVERFLOW";
        case GL_STACK_UNDERFLOW:
            return "GL_STACK_UNDERFLOW";
        default:
            return msg("GL error 0x", std::hex, error);
    }
}

void checkGlErrors(const char* what) {
    std::string errors;
    for (GLenum e = glGetError(); e != GL_NO_ERROR; e = glGetError()) {
        if (!errors.empty()) errors += ", ";
        errors += glErrorName(e);
    }
    if (!errors.empty()) throw Error(msg(what, ": ", errors));
}

}  // namespace sierra::gpu
