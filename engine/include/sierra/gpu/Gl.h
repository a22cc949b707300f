#pragma once
// The OpenGL 4.5 core API as Sierra uses it: prototypes straight from GLVND's
// libOpenGL (which exports every core entry point), no loader needed.

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>

#include <string>

namespace sierra::gpu {

// "GL_INVALID_ENUM" and friends, or the number in hex for unknown codes.
std::string glErrorName(GLenum error);

// Throws sierra::Error naming `what` and every pending glGetError() code, if any.
void checkGlErrors(const char* what);

}  // namespace sierra::gpu

// GL_CHECK(call): in debug builds, checks glGetError() after the call and throws
// with the call's text; in release builds it is the bare call (KHR_debug output
// catches errors in test builds at no cost to release frames).
#ifndef NDEBUG
#define GL_CHECK(call)                       \
    do {                                     \
        call;                                \
        ::sierra::gpu::checkGlErrors(#call); \
    } while (0)
#else
#define GL_CHECK(call) call
#endif
