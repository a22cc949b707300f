#include <sierra/gpu/ReadBack.h>

#include <sierra/core/Error.h>

#include <cstring>

namespace sierra::gpu {

namespace {
// GL's rows run bottom-up; images run top-down.
void flipRows(const uint8_t* src, Image& out) {
    size_t row = size_t(out.width) * 4;
    out.rgba.resize(row * size_t(out.height));
    for (int y = 0; y < out.height; ++y)
        std::memcpy(out.rgba.data() + size_t(y) * row, src + size_t(out.height - 1 - y) * row, row);
}
}  // namespace

Image readFramebuffer(int width, int height) {
    std::vector<uint8_t> raw(size_t(width) * height * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, raw.data());
    checkGlErrors("glReadPixels");
    Image image{width, height, {}};
    flipRows(raw.data(), image);
    return image;
}

PixelReader::PixelReader(int width, int height) : width_(width), height_(height) {
    size_t bytes = size_t(width) * height * 4;
    for (Buffer& b : pbos_) b = Buffer::create({.size = bytes, .flags = GL_MAP_READ_BIT});
}

void PixelReader::collect(int slot, Image& out) {
    fences_[slot].wait();
    size_t bytes = size_t(width_) * height_ * 4;
    const void* data =
        glMapNamedBufferRange(pbos_[slot].id(), 0, GLsizeiptr(bytes), GL_MAP_READ_BIT);
    if (!data) throw Error("glMapNamedBufferRange failed on a read-back pixel buffer");
    out.width = width_;
    out.height = height_;
    flipRows(static_cast<const uint8_t*>(data), out);
    glUnmapNamedBuffer(pbos_[slot].id());
}

bool PixelReader::start(Image& out) {
    int slot = next_;
    glBindBuffer(GL_PIXEL_PACK_BUFFER, pbos_[slot].id());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    fences_[slot] = Fence::insert();
    next_ = 1 - next_;
    bool had = pending_ >= 0;
    if (had) collect(pending_, out);
    pending_ = slot;
    return had;
}

bool PixelReader::finish(Image& out) {
    if (pending_ < 0) return false;
    collect(pending_, out);
    pending_ = -1;
    return true;
}

}  // namespace sierra::gpu
