#pragma once
// Frames encoded and written off the render thread: the render thread hands
// each frame read back to submit() and goes on with the next; encoder threads
// take frames from a bounded queue and write them. GL-free.
//
//   render::FrameQueue queue({});  // capacity from memory, hardware threads - 1
//   for (...) queue.submit(k, std::move(image), [path](const gpu::Image& f) {
//       render::writeImage(path, f, encoding); });
//   queue.finish();  // every frame written, or the first encoder error thrown

#include <sierra/gpu/ReadBack.h>

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace sierra::render {

// Frames a queue holds by default for frames of `frameBytes` bytes: an
// eighth of the memory available (MemAvailable), at most 16, at least 2.
int defaultQueuedFrames(size_t frameBytes);
// Encoder threads by default: the hardware threads less one for the render
// thread, at least 1.
int defaultEncoderThreads();

struct FrameQueueDesc {
    // Frames held at once (waiting and being encoded), >= 1; 0 = 2.
    int capacity = 0;
    // Encoder threads, >= 1; 0 = defaultEncoderThreads().
    int threads = 0;
};

class FrameQueue {
  public:
    using Encode = std::function<void(const gpu::Image&)>;

    explicit FrameQueue(const FrameQueueDesc& desc);
    // Without finish(): frames not yet started are dropped, those being
    // encoded are completed, errors are dropped (an exception is already on
    // its way out of the render loop).
    ~FrameQueue();
    FrameQueue(const FrameQueue&) = delete;
    FrameQueue& operator=(const FrameQueue&) = delete;

    // Queues frame `index` to be encoded by `encode` on an encoder thread
    // (frames finish in any order). Waits while the queue is full. Rethrows
    // the first encoder error, if one failed since; frames queued after a
    // failure are dropped unencoded.
    void submit(int64_t index, gpu::Image image, Encode encode);
    // Waits until every frame submitted is encoded, stops the threads and
    // rethrows the first encoder error. Call once; submit() may not follow.
    void finish();

    int capacity() const { return capacity_; }
    int threads() const { return int(workers_.size()); }
    // Frames whose encode returned (so far, without throwing).
    int64_t done() const;
    // The most frames ever held at once (waiting and being encoded).
    int highWater() const;

  private:
    struct Job {
        int64_t index;
        gpu::Image image;
        Encode encode;
    };
    void work();
    void stop();

    int capacity_;
    mutable std::mutex mutex_;
    std::condition_variable ready_;  // a job queued, or stopping
    std::condition_variable space_;  // a slot freed, or an error
    std::condition_variable idle_;   // nothing held
    std::deque<Job> jobs_;
    int held_ = 0;  // queued + being encoded
    int highWater_ = 0;
    int64_t done_ = 0;
    bool stopping_ = false;
    bool finished_ = false;
    std::exception_ptr error_;
    std::vector<std::thread> workers_;
};

}  // namespace sierra::render
