#pragma once
// A persistently mapped buffer (glBufferStorage with MAP_PERSISTENT |
// MAP_COHERENT) cut into a ring of regions guarded by fences: each frame writes
// its data into the next region while the GPU may still read the previous
// ones. A frame that needs more than a region holds grows the ring.

#include <sierra/gpu/Objects.h>

#include <array>
#include <cstddef>
#include <span>

namespace sierra::gpu {

struct StreamRingDesc {
    size_t regionBytes = 4u << 20;            // initial bytes per region, default 4 MiB
    GLenum target = GL_ELEMENT_ARRAY_BUFFER;  // for documentation; binding is the caller's
};

class StreamRing {
  public:
    static constexpr int kRegions = 3;

    static StreamRing create(const StreamRingDesc& desc = {});

    // Waits until the next region is free (its fence passed), growing the ring
    // if `bytes` exceeds a region, and returns it for writing. Call
    // finishFrame() after issuing the draws that read it.
    std::span<std::byte> beginFrame(size_t bytes);
    // Byte offset of the region returned by the last beginFrame().
    size_t offset() const { return size_t(current_) * regionBytes_; }
    // Fences the current region and moves to the next.
    void finishFrame();

    GLuint buffer() const { return buffer_.id(); }
    size_t regionBytes() const { return regionBytes_; }
    // Times the ring grew since creation.
    int growCount() const { return grows_; }

  private:
    void allocate(size_t regionBytes);

    Buffer buffer_;
    std::byte* mapped_ = nullptr;
    size_t regionBytes_ = 0;
    int current_ = 0;
    int grows_ = 0;
    std::array<Fence, kRegions> fences_;
};

}  // namespace sierra::gpu
