#include <sierra/gpu/StreamRing.h>

#include <sierra/core/Error.h>
#include <sierra/core/Log.h>

namespace sierra::gpu {

namespace {
constexpr GLbitfield kMapFlags = GL_MAP_WRITE_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
}

StreamRing StreamRing::create(const StreamRingDesc& desc) {
    StreamRing ring;
    ring.allocate(std::max<size_t>(desc.regionBytes, 4096));
    return ring;
}

void StreamRing::allocate(size_t regionBytes) {
    for (Fence& f : fences_) f.wait();
    if (buffer_) glUnmapNamedBuffer(buffer_.id());
    buffer_ = Buffer::create({.size = regionBytes * kRegions, .flags = kMapFlags});
    mapped_ = static_cast<std::byte*>(
        glMapNamedBufferRange(buffer_.id(), 0, GLsizeiptr(regionBytes * kRegions), kMapFlags));
    if (!mapped_) {
        checkGlErrors("glMapNamedBufferRange (persistent stream ring)");
        throw Error("glMapNamedBufferRange returned null for the stream ring");
    }
    regionBytes_ = regionBytes;
    current_ = 0;
}

std::span<std::byte> StreamRing::beginFrame(size_t bytes) {
    if (bytes > regionBytes_) {
        // Grow by half again over the need, so a slowly rising load does not
        // reallocate every frame.
        size_t grown = std::max(bytes + bytes / 2, regionBytes_ * 2);
        log::debug("stream ring grows to ", grown * kRegions, " bytes");
        allocate(grown);
        ++grows_;
    }
    fences_[size_t(current_)].wait();
    return {mapped_ + offset(), regionBytes_};
}

void StreamRing::finishFrame() {
    fences_[size_t(current_)] = Fence::insert();
    current_ = (current_ + 1) % kRegions;
}

}  // namespace sierra::gpu
