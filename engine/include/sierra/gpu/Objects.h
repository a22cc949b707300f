#pragma once
// Move-only RAII wrappers for OpenGL objects. Copies are deleted (two owners of
// one GL name would delete it twice); moves leave the source empty. id() reads
// the name, release() gives up ownership, and the adopting constructor wraps a
// name created elsewhere (interop).

#include <sierra/gpu/Gl.h>

#include <cstddef>
#include <string>
#include <utility>

namespace sierra::gpu {

struct AdoptTag {};
inline constexpr AdoptTag kAdopt{};

template <typename Derived, void (*Destroy)(GLuint)>
class GlObject {
  public:
    GlObject() = default;
    GlObject(GLuint id, AdoptTag) : id_(id) {}
    GlObject(const GlObject&) = delete;
    GlObject& operator=(const GlObject&) = delete;
    GlObject(GlObject&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
    GlObject& operator=(GlObject&& other) noexcept {
        if (this != &other) {
            reset();
            id_ = std::exchange(other.id_, 0);
        }
        return *this;
    }
    ~GlObject() { reset(); }

    GLuint id() const { return id_; }
    explicit operator bool() const { return id_ != 0; }
    // Gives up ownership: the caller deletes the name.
    [[nodiscard]] GLuint release() { return std::exchange(id_, 0); }
    void reset() {
        if (id_) Destroy(id_);
        id_ = 0;
    }

  protected:
    GLuint id_ = 0;
};

namespace detail {
void deleteBuffer(GLuint id);
void deleteVertexArray(GLuint id);
void deleteTexture(GLuint id);
void deleteFramebuffer(GLuint id);
void deleteProgram(GLuint id);
void deleteQuery(GLuint id);
}  // namespace detail

struct BufferDesc {
    size_t size = 0;             // bytes
    const void* data = nullptr;  // initial contents, or null
    GLbitfield flags = 0;        // glBufferStorage flags; 0 = immutable, GPU only
};

class Buffer : public GlObject<Buffer, detail::deleteBuffer> {
  public:
    using GlObject::GlObject;
    static Buffer create(const BufferDesc& desc);
    size_t size() const { return size_; }

  private:
    size_t size_ = 0;
};

class VertexArray : public GlObject<VertexArray, detail::deleteVertexArray> {
  public:
    using GlObject::GlObject;
    static VertexArray create();
};

struct TextureDesc {
    GLenum target = GL_TEXTURE_2D;  // GL_TEXTURE_1D, _2D, _2D_ARRAY or _2D_MULTISAMPLE
    GLenum format = GL_RGBA8;       // sized internal format
    int width = 1;
    int height = 1;             // ignored for 1D
    int layers = 0;             // for GL_TEXTURE_2D_ARRAY
    int levels = 1;             // mip levels (non-multisample); > 1 with GL_LINEAR = trilinear
    int samples = 0;            // for GL_TEXTURE_2D_MULTISAMPLE
    GLenum filter = GL_LINEAR;  // min and mag filter
    GLenum wrap = GL_CLAMP_TO_EDGE;
};

class Texture : public GlObject<Texture, detail::deleteTexture> {
  public:
    using GlObject::GlObject;
    static Texture create(const TextureDesc& desc);
    // Uploads a whole level-0 image: `format`/`type` describe `pixels`.
    void upload(GLenum format, GLenum type, const void* pixels);
    // Uploads level 0 of one layer of a GL_TEXTURE_2D_ARRAY.
    void uploadLayer(int layer, GLenum format, GLenum type, const void* pixels);
    // Fills the mip levels below 0 from level 0.
    void generateMipmaps();
    int width() const { return width_; }
    int height() const { return height_; }
    GLenum target() const { return target_; }

  private:
    int width_ = 0;
    int height_ = 0;
    GLenum target_ = GL_TEXTURE_2D;
    int layers_ = 1;
};

class Framebuffer : public GlObject<Framebuffer, detail::deleteFramebuffer> {
  public:
    using GlObject::GlObject;
    static Framebuffer create();
    void attach(GLenum attachment, const Texture& texture);
    // Throws sierra::Error unless the framebuffer is complete.
    void checkComplete(const char* what) const;
};

class Query : public GlObject<Query, detail::deleteQuery> {
  public:
    using GlObject::GlObject;
    static Query create(GLenum target);
};

// A GLsync fence, move-only.
class Fence {
  public:
    Fence() = default;
    static Fence insert();
    Fence(const Fence&) = delete;
    Fence& operator=(const Fence&) = delete;
    Fence(Fence&& other) noexcept : sync_(std::exchange(other.sync_, nullptr)) {}
    Fence& operator=(Fence&& other) noexcept;
    ~Fence();
    explicit operator bool() const { return sync_ != nullptr; }
    // Blocks until the GPU has passed the fence (flushing first); returns at once
    // for an empty fence.
    void wait();

  private:
    GLsync sync_ = nullptr;
};

}  // namespace sierra::gpu
