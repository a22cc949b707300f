#include <sierra/gpu/Objects.h>

#include <sierra/core/Error.h>

namespace sierra::gpu {

namespace detail {
void deleteBuffer(GLuint id) {
    glDeleteBuffers(1, &id);
}
void deleteVertexArray(GLuint id) {
    glDeleteVertexArrays(1, &id);
}
void deleteTexture(GLuint id) {
    glDeleteTextures(1, &id);
}
void deleteFramebuffer(GLuint id) {
    glDeleteFramebuffers(1, &id);
}
void deleteProgram(GLuint id) {
    glDeleteProgram(id);
}
void deleteQuery(GLuint id) {
    glDeleteQueries(1, &id);
}
}  // namespace detail

Buffer Buffer::create(const BufferDesc& desc) {
    SIERRA_CHECK(desc.size > 0, "buffer size must be positive");
    GLuint id = 0;
    glCreateBuffers(1, &id);
    Buffer buffer(id, kAdopt);
    glNamedBufferStorage(id, GLsizeiptr(desc.size), desc.data, desc.flags);
    checkGlErrors("glNamedBufferStorage");
    buffer.size_ = desc.size;
    return buffer;
}

VertexArray VertexArray::create() {
    GLuint id = 0;
    glCreateVertexArrays(1, &id);
    return VertexArray(id, kAdopt);
}

Texture Texture::create(const TextureDesc& desc) {
    SIERRA_CHECK(desc.width > 0 && desc.height > 0, "texture size ", desc.width, "x", desc.height);
    GLuint id = 0;
    glCreateTextures(desc.target, 1, &id);
    Texture texture(id, kAdopt);
    texture.width_ = desc.width;
    texture.height_ = desc.target == GL_TEXTURE_1D ? 1 : desc.height;
    texture.target_ = desc.target;
    texture.layers_ = desc.target == GL_TEXTURE_2D_ARRAY ? desc.layers : 1;
    switch (desc.target) {
        case GL_TEXTURE_1D:
            glTextureStorage1D(id, desc.levels, desc.format, desc.width);
            break;
        case GL_TEXTURE_2D:
            glTextureStorage2D(id, desc.levels, desc.format, desc.width, desc.height);
            break;
        case GL_TEXTURE_2D_ARRAY:
            SIERRA_CHECK(desc.layers > 0, "a texture array needs layers, got ", desc.layers);
            glTextureStorage3D(id, desc.levels, desc.format, desc.width, desc.height, desc.layers);
            break;
        case GL_TEXTURE_2D_MULTISAMPLE:
            glTextureStorage2DMultisample(id, desc.samples, desc.format, desc.width, desc.height,
                                          GL_TRUE);
            break;
        default:
            throw Error(msg("unsupported texture target 0x", std::hex, desc.target));
    }
    if (desc.target != GL_TEXTURE_2D_MULTISAMPLE) {
        // With mip levels the minification filter is trilinear; the magnification
        // filter never uses mips.
        GLenum minFilter =
            desc.levels > 1 && desc.filter == GL_LINEAR ? GL_LINEAR_MIPMAP_LINEAR : desc.filter;
        glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GLint(minFilter));
        glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GLint(desc.filter));
        glTextureParameteri(id, GL_TEXTURE_WRAP_S, GLint(desc.wrap));
        glTextureParameteri(id, GL_TEXTURE_WRAP_T, GLint(desc.wrap));
    }
    checkGlErrors("texture creation");
    return texture;
}

namespace {
// Rows of tightly packed pixels for the calls inside; the caller's unpack
// alignment is set again afterwards.
template <typename Fn>
void packedRows(const Fn& upload) {
    GLint alignment = 4;
    glGetIntegerv(GL_UNPACK_ALIGNMENT, &alignment);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    upload();
    glPixelStorei(GL_UNPACK_ALIGNMENT, alignment);
}
}  // namespace

void Texture::uploadLayer(int layer, GLenum format, GLenum type, const void* pixels) {
    SIERRA_CHECK(target_ == GL_TEXTURE_2D_ARRAY && layer >= 0 && layer < layers_, "layer ", layer,
                 " of a texture with ", layers_, " layers");
    packedRows([&] {
        glTextureSubImage3D(id_, 0, 0, 0, layer, width_, height_, 1, format, type, pixels);
    });
    checkGlErrors("texture layer upload");
}

void Texture::generateMipmaps() {
    glGenerateTextureMipmap(id_);
    checkGlErrors("mipmap generation");
}

void Texture::upload(GLenum format, GLenum type, const void* pixels) {
    packedRows([&] {
        if (target_ == GL_TEXTURE_1D)
            glTextureSubImage1D(id_, 0, 0, width_, format, type, pixels);
        else
            glTextureSubImage2D(id_, 0, 0, 0, width_, height_, format, type, pixels);
    });
    checkGlErrors("texture upload");
}

Framebuffer Framebuffer::create() {
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    return Framebuffer(id, kAdopt);
}

void Framebuffer::attach(GLenum attachment, const Texture& texture) {
    glNamedFramebufferTexture(id_, attachment, texture.id(), 0);
}

void Framebuffer::checkComplete(const char* what) const {
    GLenum status = glCheckNamedFramebufferStatus(id_, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        throw Error(msg(what, ": framebuffer incomplete (status 0x", std::hex, status, ")"));
}

Query Query::create(GLenum target) {
    GLuint id = 0;
    glCreateQueries(target, 1, &id);
    return Query(id, kAdopt);
}

Fence Fence::insert() {
    Fence fence;
    fence.sync_ = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    return fence;
}

Fence& Fence::operator=(Fence&& other) noexcept {
    if (this != &other) {
        if (sync_) glDeleteSync(sync_);
        sync_ = std::exchange(other.sync_, nullptr);
    }
    return *this;
}

Fence::~Fence() {
    if (sync_) glDeleteSync(sync_);
}

void Fence::wait() {
    if (!sync_) return;
    // One second per wait, flushing on the first: a driver that never signals is
    // reported rather than hanging the frame loop.
    constexpr GLuint64 kTimeoutNs = 1'000'000'000;
    GLenum result = glClientWaitSync(sync_, GL_SYNC_FLUSH_COMMANDS_BIT, kTimeoutNs);
    for (int tries = 0; result == GL_TIMEOUT_EXPIRED && tries < 30; ++tries)
        result = glClientWaitSync(sync_, 0, kTimeoutNs);
    if (result == GL_WAIT_FAILED || result == GL_TIMEOUT_EXPIRED)
        throw Error("glClientWaitSync: the GPU did not reach a stream fence");
    glDeleteSync(sync_);
    sync_ = nullptr;
}

}  // namespace sierra::gpu
