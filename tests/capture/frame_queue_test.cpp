// render::FrameQueue: every frame submitted is encoded once, the queue never
// holds more than its capacity, the render thread waits when it is full, and
// the first encoder error comes back on the submitting thread.
#include <sierra/core/Error.h>
#include <sierra/render/FrameQueue.h>

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <thread>

using namespace sierra;
using namespace std::chrono_literals;

namespace {

gpu::Image frameOf(int value) {
    return {2, 1, std::vector<uint8_t>(8, uint8_t(value))};
}

}  // namespace

TEST(FrameQueue, EncodesEveryFrameOnceWhateverTheOrder) {
    std::mutex mutex;
    std::multiset<int> seen;
    render::FrameQueue queue({.capacity = 3, .threads = 4});
    EXPECT_EQ(queue.threads(), 4);
    for (int k = 0; k < 200; ++k)
        queue.submit(k, frameOf(k % 256), [&, k](const gpu::Image& image) {
            // The image that arrives is the one submitted with this index.
            ASSERT_EQ(image.rgba.size(), 8u);
            EXPECT_EQ(image.rgba[0], uint8_t(k % 256));
            std::lock_guard lock(mutex);
            seen.insert(k);
        });
    queue.finish();
    EXPECT_EQ(queue.done(), 200);
    ASSERT_EQ(seen.size(), 200u);
    for (int k = 0; k < 200; ++k) EXPECT_EQ(seen.count(k), 1u) << k;
}

TEST(FrameQueue, HoldsAtMostItsCapacityAndTheSubmitterWaits) {
    std::atomic<int> inside{0}, most{0};
    std::atomic<bool> open{false};
    render::FrameQueue queue({.capacity = 3, .threads = 2});
    auto slow = [&](const gpu::Image&) {
        int now = ++inside;
        int seen = most.load();
        while (now > seen && !most.compare_exchange_weak(seen, now)) {
        }
        while (!open) std::this_thread::sleep_for(1ms);
        --inside;
    };
    // Three frames fit; the fourth submit waits until an encoder finishes.
    for (int k = 0; k < 3; ++k) queue.submit(k, frameOf(k), slow);
    std::atomic<bool> fourthIn{false};
    std::thread producer([&] {
        queue.submit(3, frameOf(3), slow);
        fourthIn = true;
    });
    std::this_thread::sleep_for(100ms);
    EXPECT_FALSE(fourthIn) << "submit did not wait for a free slot";
    EXPECT_EQ(queue.highWater(), 3);
    open = true;
    producer.join();
    EXPECT_TRUE(fourthIn);
    queue.finish();
    EXPECT_EQ(queue.done(), 4);
    EXPECT_LE(queue.highWater(), 3);
    EXPECT_LE(most.load(), 2) << "more frames encoded at once than there are threads";
}

TEST(FrameQueue, RethrowsTheFirstEncoderErrorOnTheSubmittingThread) {
    render::FrameQueue queue({.capacity = 2, .threads = 1});
    std::atomic<int> encoded{0};
    queue.submit(0, frameOf(0), [&](const gpu::Image&) { ++encoded; });
    queue.submit(1, frameOf(1), [](const gpu::Image&) { throw Error("cannot write f_0001.png"); });
    // A later submit (or finish) sees the failure; frames after it are dropped.
    bool thrown = false;
    try {
        for (int k = 2; k < 1000; ++k) {
            queue.submit(k, frameOf(k), [&](const gpu::Image&) { ++encoded; });
            std::this_thread::sleep_for(1ms);
        }
        queue.finish();
    } catch (const Error& e) {
        thrown = true;
        EXPECT_STREQ(e.what(), "cannot write f_0001.png");
    }
    EXPECT_TRUE(thrown) << "the encoder's error was lost";
    EXPECT_LT(encoded.load(), 998) << "the queue went on encoding after the failure";
}

TEST(FrameQueue, FinishRethrowsAnErrorOfTheLastFrames) {
    render::FrameQueue queue({.capacity = 4, .threads = 2});
    queue.submit(0, frameOf(0), [](const gpu::Image&) {});
    queue.submit(1, frameOf(1), [](const gpu::Image&) { throw Error("disk full"); });
    EXPECT_THROW(queue.finish(), Error);
}

TEST(FrameQueue, DestructorWithoutFinishCompletesStartedFramesAndDropsTheRest) {
    std::atomic<int> encoded{0};
    std::atomic<bool> started{false};
    {
        render::FrameQueue queue({.capacity = 8, .threads = 1});
        queue.submit(0, frameOf(0), [&](const gpu::Image&) {
            started = true;
            std::this_thread::sleep_for(50ms);
            ++encoded;
        });
        for (int k = 1; k < 8; ++k)
            queue.submit(k, frameOf(k), [&](const gpu::Image&) { ++encoded; });
        while (!started) std::this_thread::sleep_for(1ms);
    }
    EXPECT_EQ(encoded.load(), 1) << "the frame being encoded completes, the queued ones do not";
}

TEST(FrameQueue, DefaultsFollowMemoryAndCores) {
    // A frame larger than an eighth of any machine's memory: the floor of 2.
    EXPECT_EQ(render::defaultQueuedFrames(size_t(1) << 60), 2);
    // A tiny frame: the ceiling of 16.
    EXPECT_EQ(render::defaultQueuedFrames(16), 16);
    const int threads = render::defaultEncoderThreads();
    EXPECT_GE(threads, 1);
    const unsigned hardware = std::thread::hardware_concurrency();
    if (hardware > 1) {
        EXPECT_EQ(threads, int(hardware) - 1);
    }
    EXPECT_THROW(render::FrameQueue({.capacity = -1}), Error);
}
