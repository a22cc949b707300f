#include <sierra/render/FrameQueue.h>

#include <sierra/core/Error.h>

#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>

namespace sierra::render {

namespace {

// Bytes of memory available without swapping: MemAvailable of /proc/meminfo,
// else the free physical pages; 0 when neither is known.
uint64_t availableMemory() {
    std::ifstream meminfo("/proc/meminfo");
    std::string line;
    while (std::getline(meminfo, line)) {
        if (line.rfind("MemAvailable:", 0) != 0) continue;
        std::istringstream fields(line.substr(13));
        uint64_t kib = 0;
        if (fields >> kib) return kib * 1024;
    }
    const long pages = sysconf(_SC_AVPHYS_PAGES), pageSize = sysconf(_SC_PAGESIZE);
    return pages > 0 && pageSize > 0 ? uint64_t(pages) * uint64_t(pageSize) : 0;
}

}  // namespace

int defaultQueuedFrames(size_t frameBytes) {
    constexpr uint64_t kMost = 16, kLeast = 2;
    const uint64_t memory = availableMemory();
    if (memory == 0 || frameBytes == 0) return int(kLeast);
    return int(std::clamp<uint64_t>(memory / 8 / frameBytes, kLeast, kMost));
}

int defaultEncoderThreads() {
    const unsigned hardware = std::thread::hardware_concurrency();
    return hardware > 1 ? int(hardware) - 1 : 1;
}

FrameQueue::FrameQueue(const FrameQueueDesc& desc)
    : capacity_(desc.capacity > 0 ? desc.capacity : 2) {
    SIERRA_CHECK(desc.capacity >= 0 && desc.threads >= 0,
                 "a frame queue needs a capacity and a thread count >= 0 (0 = default), got ",
                 desc.capacity, " and ", desc.threads);
    const int threads = desc.threads > 0 ? desc.threads : defaultEncoderThreads();
    workers_.reserve(size_t(threads));
    for (int t = 0; t < threads; ++t) workers_.emplace_back([this] { work(); });
}

FrameQueue::~FrameQueue() {
    {
        std::lock_guard lock(mutex_);
        held_ -= int(jobs_.size());
        jobs_.clear();
    }
    stop();
}

void FrameQueue::stop() {
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
    }
    ready_.notify_all();
    for (std::thread& worker : workers_)
        if (worker.joinable()) worker.join();
}

void FrameQueue::submit(int64_t index, gpu::Image image, Encode encode) {
    std::unique_lock lock(mutex_);
    SIERRA_CHECK(!finished_, "FrameQueue::submit after finish()");
    space_.wait(lock, [&] { return held_ < capacity_ || error_; });
    if (error_) std::rethrow_exception(error_);
    jobs_.push_back({index, std::move(image), std::move(encode)});
    ++held_;
    highWater_ = std::max(highWater_, held_);
    lock.unlock();
    ready_.notify_one();
}

void FrameQueue::finish() {
    std::unique_lock lock(mutex_);
    SIERRA_CHECK(!finished_, "FrameQueue::finish called twice");
    finished_ = true;
    idle_.wait(lock, [&] { return held_ == 0; });
    lock.unlock();
    stop();
    if (error_) std::rethrow_exception(error_);
}

int64_t FrameQueue::done() const {
    std::lock_guard lock(mutex_);
    return done_;
}

int FrameQueue::highWater() const {
    std::lock_guard lock(mutex_);
    return highWater_;
}

void FrameQueue::work() {
    for (;;) {
        std::unique_lock lock(mutex_);
        ready_.wait(lock, [&] { return stopping_ || !jobs_.empty(); });
        if (jobs_.empty()) return;  // stopping, nothing left
        Job job = std::move(jobs_.front());
        jobs_.pop_front();
        lock.unlock();
        std::exception_ptr failure;
        try {
            job.encode(job.image);
        } catch (...) {
            failure = std::current_exception();
        }
        job.image = {};  // the frame's memory back before its slot
        lock.lock();
        if (failure) {
            if (!error_) error_ = failure;
            // After a failure the run stops: frames not yet started are dropped.
            held_ -= int(jobs_.size());
            jobs_.clear();
        } else {
            ++done_;
        }
        --held_;
        const bool idle = held_ == 0;
        lock.unlock();
        space_.notify_one();
        if (failure) space_.notify_all();
        if (idle) idle_.notify_all();
    }
}

}  // namespace sierra::render
