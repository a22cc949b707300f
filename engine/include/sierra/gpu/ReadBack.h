#pragma once
// Reading the frame back to memory as RGBA8 in image order (top row first).

#include <sierra/gpu/Objects.h>

#include <cstdint>
#include <vector>

namespace sierra::gpu {

struct Image {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> rgba;  // width * height * 4, top row first
};

// Reads the colour buffer of the framebuffer bound for reading, synchronously.
Image readFramebuffer(int width, int height);

// Asynchronous read-back through two pixel-buffer objects: start() copies the
// current frame into one PBO, and the frame started one call earlier is
// mapped and returned, so the copy overlaps the next frame's work.
class PixelReader {
  public:
    PixelReader(int width, int height);
    // Starts reading the bound read framebuffer; returns true and fills `out`
    // with the previously started frame when there was one.
    bool start(Image& out);
    // Returns the last started frame, if any (end of a sequence).
    bool finish(Image& out);

  private:
    void collect(int slot, Image& out);

    int width_, height_;
    Buffer pbos_[2];
    Fence fences_[2];
    int next_ = 0;
    int pending_ = -1;
};

}  // namespace sierra::gpu
