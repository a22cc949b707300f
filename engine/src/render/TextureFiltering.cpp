#include "render/TextureFiltering.h"

#include <algorithm>
#include <cstring>

namespace sierra::render {

namespace {

// GL_TEXTURE_MAX_ANISOTROPY (core in 4.6, the same value as the EXT extension's).
constexpr GLenum kMaxAnisotropy = 0x84FE;
constexpr GLenum kMaxAnisotropyLimit = 0x84FF;

bool hasExtension(const char* name) {
    GLint count = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &count);
    for (GLint k = 0; k < count; ++k)
        if (std::strcmp(reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(k))),
                        name) == 0)
            return true;
    return false;
}

}  // namespace

void applyMipmapFiltering(const gpu::Texture& texture, int levels) {
    const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const bool llvmpipe = renderer && std::strstr(renderer, "llvmpipe") != nullptr;
    if (llvmpipe && levels > 1)
        glTextureParameteri(texture.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_NEAREST);
    if (!llvmpipe && levels > 1 &&
        (hasExtension("GL_EXT_texture_filter_anisotropic") ||
         hasExtension("GL_ARB_texture_filter_anisotropic"))) {
        float limit = 1.0f;
        glGetFloatv(kMaxAnisotropyLimit, &limit);
        glTextureParameterf(texture.id(), kMaxAnisotropy, std::min(8.0f, limit));
    }
}

}  // namespace sierra::render
