#pragma once
// Tiles of a TileFile streamed from disk by loader threads into a cache of
// bounded size, for TiledRefiner: a frame never waits for a read.
//
// Each frame, on the render thread:
//   cache.beginFrame();                 // what has arrived becomes resident
//   refiner.refineView(view, mesh);     // over what is resident
//   cache.wantForView(refiner, eye, prefetchEye);  // what to read next
// Loader threads read the wanted tiles nearest the eye first, each to the
// levels the refinement reached beyond what it had (and a few more), and
// hand them over; beginFrame makes them resident and evicts the tiles wanted
// least recently while the cache is over its budget. The resident set
// changes only in beginFrame, so the refinement reads a fixed set without
// locks. A tile that has not arrived is drawn from its coarser levels
// (TiledRefiner's balancing keeps that crack-free); TiledMesh::coarseTiles
// counts them.
//
// The budget bounds the packed tiles held plus those being read: a far tile
// needs a few levels (bytes), a near one all (about 12 bytes a sample). A
// want that would not fit while the cache holds only tiles wanted this
// frame is dropped, nearest kept.

#include <sierra/sbt/TileFile.h>
#include <sierra/sbt/TiledRefiner.h>

#include <array>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace sierra::sbt {

struct TileCacheOptions {
    uint64_t budgetBytes = uint64_t(768) << 20;  // packed tiles held and in flight
    int loaderThreads = 2;                       // >= 1
    // Levels read beyond those a refinement reached, so a tile coming closer
    // does not ask again every frame.
    int extraLevels = 4;
};

struct TileCacheStats {
    uint64_t residentBytes = 0;
    uint64_t peakBytes = 0;  // largest resident + in-flight bytes so far
    int residentTiles = 0;
    int queued = 0;    // wants waiting for a loader
    int inFlight = 0;  // being read
    int64_t tilesRead = 0;
    uint64_t bytesRead = 0;  // file bytes
    int64_t evicted = 0;
    int64_t dropped = 0;  // wants refused for the budget
};

class TileCache : public TiledVertices {
  public:
    // Keeps a reference to `file`, which must outlive the cache. Throws
    // sierra::Error for a budget below one whole tile.
    TileCache(const TileFile& file, const TileCacheOptions& options = {});
    ~TileCache() override;
    TileCache(const TileCache&) = delete;
    TileCache& operator=(const TileCache&) = delete;

    int residentLevels(int tx, int ty) const override;
    const VertexRecord* tileRecords(int tx, int ty) const override {
        const PackedTile* t = packed(tx, ty);
        return t ? t->records.data() : nullptr;
    }
    VertexRecord corner(uint32_t i, uint32_t j) const override { return file_.corner(i, j); }
    // Vertex (i, j) of a resident level (tests and tools).
    VertexRecord vertex(uint32_t i, uint32_t j) const;

    // The resident data of tile (tx, ty), or null (valid until the next beginFrame).
    const PackedTile* packed(int tx, int ty) const {
        return slots_[size_t(ty) * size_t(tilesPerSide()) + size_t(tx)].data.get();
    }

    // Makes the tiles the loaders finished resident and evicts over the
    // budget. Never waits for a read. Rethrows a loader's read error (a
    // corrupt tile) as sierra::Error.
    void beginFrame();

    // The wants of the refinement just made (its wantedLevels), each raised to
    // what its neighbours' balancing needs, nearest to `eye` (world) first;
    // then the tiles around `prefetchEye` (where the camera is heading),
    // whole. Replaces the wants not yet started.
    void wantForView(const TiledRefiner& refiner, const std::array<float, 3>& eye,
                     const std::array<float, 3>& prefetchEye);
    // Wants tile (tx, ty) to at least `levels` (tests, warm-up).
    void want(int tx, int ty, int levels, float priority = 0.0f);

    // Blocks until no want is queued or being read, then beginFrame (tests,
    // and a first frame that chooses to wait).
    void waitIdle();

    TileCacheStats stats() const;
    const TileFile& file() const { return file_; }

  private:
    struct Want {
        int tile = 0;  // ty * tiles + tx
        int chunks = 0;
        float priority = 0.0f;
    };
    struct Slot {
        std::shared_ptr<const PackedTile> data;
        int64_t lastWanted = 0;  // frame
    };
    void loaderLoop();

    const TileFile& file_;
    const TileCacheOptions options_;
    const TileAddressing address_;
    const int tiles_;
    // Render thread only: what the refinement reads.
    std::vector<Slot> slots_;
    int64_t frame_ = 0;
    uint64_t residentBytes_ = 0;
    int residentTiles_ = 0;
    std::vector<int> need_;  // scratch of wantForView

    // Shared with the loaders, under mutex_.
    mutable std::mutex mutex_;
    std::condition_variable wake_, idle_;
    std::vector<Want> queue_;  // sorted: nearest last
    std::vector<std::pair<int, std::shared_ptr<const PackedTile>>> arrived_;
    std::vector<int> inFlight_;  // chunks per tile being read, 0 = none
    std::vector<int> have_;      // chunks per tile resident (as of beginFrame)
    std::vector<uint64_t> haveBytes_;
    uint64_t sharedBytes_ = 0;  // resident and arrived, not yet made resident
    uint64_t inFlightBytes_ = 0;
    int reading_ = 0;
    std::string error_;
    bool stop_ = false;
    TileCacheStats stats_;
    std::vector<std::thread> loaders_;
};

}  // namespace sierra::sbt
