#include <sierra/sbt/TileCache.h>

#include <sierra/core/Error.h>

#include <algorithm>
#include <cmath>

namespace sierra::sbt {

TileCache::TileCache(const TileFile& file, const TileCacheOptions& options)
    : TiledVertices(file.info().desc()),
      file_(file),
      options_(options),
      address_(file.info().k),
      tiles_(file.info().tilesPerSide() * file.info().tilesPerSide()),
      slots_(size_t(tiles_)),
      inFlight_(size_t(tiles_), 0) {
    const uint64_t whole = file.packedBytes(file.chunkCount());
    SIERRA_CHECK(options.budgetBytes >= whole, "a tile cache of ", options.budgetBytes,
                 " bytes cannot hold one whole tile of ", whole, " bytes");
    SIERRA_CHECK(options.loaderThreads >= 1 && options.loaderThreads <= 64,
                 "a tile cache needs 1..64 loader threads, got ", options.loaderThreads);
    have_.assign(size_t(tiles_), 0);
    haveBytes_.assign(size_t(tiles_), 0);
    for (int t = 0; t < options.loaderThreads; ++t) loaders_.emplace_back([this] { loaderLoop(); });
}

TileCache::~TileCache() {
    {
        std::lock_guard lock(mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : loaders_) t.join();
}

int TileCache::residentLevels(int tx, int ty) const {
    // A tile wholly in the padding is never refined: it never holds its
    // neighbours back.
    if (!file_.stored(tx, ty)) return 2 * desc().k;
    const auto& data = slots_[size_t(ty) * size_t(tilesPerSide()) + size_t(tx)].data;
    return data ? data->levels : 0;
}

VertexRecord TileCache::vertex(uint32_t i, uint32_t j) const {
    return packedVertex(file_, address_, i, j, [&](int tx, int ty) {
        return slots_[size_t(ty) * size_t(tilesPerSide()) + size_t(tx)].data.get();
    });
}

void TileCache::beginFrame() {
    std::vector<std::pair<int, std::shared_ptr<const PackedTile>>> arrived;
    std::string error;
    {
        std::lock_guard lock(mutex_);
        arrived.swap(arrived_);
        error.swap(error_);
    }
    if (!error.empty()) throw Error(error);
    ++frame_;
    std::vector<std::pair<int, uint64_t>> freed;  // tile, bytes no longer held
    for (auto& [tile, data] : arrived) {
        Slot& s = slots_[size_t(tile)];
        if (s.data && s.data->levels >= data->levels) {
            freed.push_back({tile, data->bytes()});  // a shallower read that came late
            continue;
        }
        if (s.data) {
            freed.push_back({tile, s.data->bytes()});
            residentBytes_ -= s.data->bytes();
        } else {
            ++residentTiles_;
        }
        residentBytes_ += data->bytes();
        s.data = std::move(data);
    }
    // Over the budget (or close to it, so the loaders have room): the tiles
    // wanted least recently go first; tiles of the last refinement stay.
    const uint64_t keep = options_.budgetBytes - options_.budgetBytes / 8;
    uint64_t pending;
    {
        std::lock_guard lock(mutex_);
        pending = inFlightBytes_;
    }
    if (residentBytes_ + pending > keep) {
        std::vector<int> stale;
        for (int t = 0; t < tiles_; ++t)
            if (slots_[size_t(t)].data && slots_[size_t(t)].lastWanted < frame_ - 1)
                stale.push_back(t);
        std::sort(stale.begin(), stale.end(), [&](int a, int b) {
            return slots_[size_t(a)].lastWanted < slots_[size_t(b)].lastWanted;
        });
        for (int t : stale) {
            if (residentBytes_ + pending <= keep) break;
            Slot& s = slots_[size_t(t)];
            residentBytes_ -= s.data->bytes();
            freed.push_back({t, s.data->bytes()});
            s.data.reset();
            --residentTiles_;
        }
    }
    std::lock_guard lock(mutex_);
    for (const auto& [tile, bytes] : freed) sharedBytes_ -= bytes;
    for (int t = 0; t < tiles_; ++t) {
        const auto& data = slots_[size_t(t)].data;
        have_[size_t(t)] = data ? file_.chunksForLevels(data->levels) : 0;
        haveBytes_[size_t(t)] = data ? data->bytes() : 0;
    }
    stats_.evicted += int64_t(std::count_if(
        freed.begin(), freed.end(), [&](const auto& f) { return !slots_[size_t(f.first)].data; }));
    stats_.peakBytes = std::max(stats_.peakBytes, sharedBytes_ + inFlightBytes_);
}

void TileCache::wantForView(const TiledRefiner& refiner, const std::array<float, 3>& eye,
                            const std::array<float, 3>& prefetchEye) {
    const int P = tilesPerSide(), k = desc().k, T = 1 << k;
    const std::vector<uint8_t>& reached = refiner.reachedLevels();
    const std::vector<int>& usable = refiner.usableLevels();
    if (reached.size() != size_t(tiles_)) return;  // no refinement over this cache yet
    // What each tile needs: the levels the walk reached where it stopped short,
    // and for the balancing, w - |T - U| at every tile U around a tile T that
    // needs w (so that U no longer holds T back): a max-minus-distance
    // transform, two passes like the balancing's.
    need_.assign(size_t(tiles_), 0);
    for (int t = 0; t < tiles_; ++t)
        if (reached[size_t(t)] > usable[size_t(t)]) need_[size_t(t)] = reached[size_t(t)];
    auto at = [&](int tx, int ty) -> int& { return need_[size_t(ty) * size_t(P) + size_t(tx)]; };
    for (int ty = 0; ty < P; ++ty)
        for (int tx = 0; tx < P; ++tx) {
            if (tx > 0) at(tx, ty) = std::max(at(tx, ty), at(tx - 1, ty) - 1);
            if (ty > 0) at(tx, ty) = std::max(at(tx, ty), at(tx, ty - 1) - 1);
        }
    for (int ty = P - 1; ty >= 0; --ty)
        for (int tx = P - 1; tx >= 0; --tx) {
            if (tx + 1 < P) at(tx, ty) = std::max(at(tx, ty), at(tx + 1, ty) - 1);
            if (ty + 1 < P) at(tx, ty) = std::max(at(tx, ty), at(tx, ty + 1) - 1);
        }
    const double tileX = double(T) * desc().spacingX, tileZ = double(T) * desc().spacingZ;
    auto distance2 = [&](const std::array<float, 3>& p, int tx, int ty) {
        const double dx = (tx + 0.5) * tileX - p[0], dz = (ty + 0.5) * tileZ - p[2];
        return dx * dx + dz * dz;
    };
    const int px = int(std::floor(prefetchEye[0] / tileX)),
              pz = int(std::floor(prefetchEye[2] / tileZ));
    std::vector<Want> wants;
    for (int ty = 0; ty < P; ++ty)
        for (int tx = 0; tx < P; ++tx) {
            const int t = ty * P + tx;
            if (!file_.stored(tx, ty)) continue;
            Slot& s = slots_[size_t(t)];
            if (reached[size_t(t)] > 0) s.lastWanted = frame_;
            int levels =
                need_[size_t(t)] > 0 ? std::min(2 * k, need_[size_t(t)] + options_.extraLevels) : 0;
            float priority = float(distance2(eye, tx, ty));
            if (std::abs(tx - px) <= 1 && std::abs(ty - pz) <= 1) {
                // Where the camera is heading: whole, after what this frame lacks nearby.
                s.lastWanted = frame_;
                if (levels < 2 * k)
                    priority = std::max(priority, float(4.0 * distance2(prefetchEye, tx, ty)));
                levels = 2 * k;
            }
            if (levels == 0) continue;
            const int chunks = file_.chunksForLevels(levels);
            if (s.data && file_.chunksForLevels(s.data->levels) >= chunks) continue;
            s.lastWanted = frame_;
            wants.push_back({t, chunks, priority});
        }
    std::sort(wants.begin(), wants.end(),
              [](const Want& a, const Want& b) { return a.priority > b.priority; });
    {
        std::lock_guard lock(mutex_);
        queue_ = std::move(wants);
    }
    wake_.notify_all();
}

void TileCache::want(int tx, int ty, int levels, float priority) {
    const int t = ty * tilesPerSide() + tx;
    if (!file_.stored(tx, ty)) return;
    slots_[size_t(t)].lastWanted = frame_;
    {
        std::lock_guard lock(mutex_);
        queue_.push_back({t, file_.chunksForLevels(levels), priority});
        std::sort(queue_.begin(), queue_.end(),
                  [](const Want& a, const Want& b) { return a.priority > b.priority; });
    }
    wake_.notify_all();
}

void TileCache::loaderLoop() {
    for (;;) {
        Want w;
        uint64_t bytes = 0;
        {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, [&] { return stop_ || !queue_.empty(); });
            if (stop_) return;
            w = queue_.back();
            queue_.pop_back();
            const size_t t = size_t(w.tile);
            if (have_[t] >= w.chunks || inFlight_[t] >= w.chunks) {
                if (queue_.empty() && reading_ == 0) idle_.notify_all();
                continue;
            }
            bytes = file_.packedBytes(w.chunks);
            if (sharedBytes_ + inFlightBytes_ + bytes > options_.budgetBytes) {
                ++stats_.dropped;  // asked again next frame, after eviction
                if (queue_.empty() && reading_ == 0) idle_.notify_all();
                continue;
            }
            inFlight_[t] = w.chunks;
            inFlightBytes_ += bytes;
            ++reading_;
            stats_.peakBytes = std::max(stats_.peakBytes, sharedBytes_ + inFlightBytes_);
        }
        const int P = tilesPerSide(), tx = w.tile % P, ty = w.tile / P;
        auto data = std::make_shared<PackedTile>();
        std::string error;
        try {
            file_.readPacked(tx, ty, w.chunks, *data);
        } catch (const Error& e) {
            error = e.what();
        }
        std::lock_guard lock(mutex_);
        --reading_;
        inFlightBytes_ -= bytes;
        inFlight_[size_t(w.tile)] = 0;
        if (error.empty()) {
            sharedBytes_ += data->bytes();
            ++stats_.tilesRead;
            stats_.bytesRead += file_.tileBytes(tx, ty, w.chunks);
            arrived_.push_back({w.tile, std::move(data)});
        } else if (error_.empty()) {
            error_ = error;
        }
        if (queue_.empty() && reading_ == 0) idle_.notify_all();
    }
}

void TileCache::waitIdle() {
    {
        std::unique_lock lock(mutex_);
        idle_.wait(lock, [&] { return queue_.empty() && reading_ == 0; });
    }
    beginFrame();
}

TileCacheStats TileCache::stats() const {
    std::lock_guard lock(mutex_);
    TileCacheStats s = stats_;
    s.residentBytes = residentBytes_;
    s.residentTiles = residentTiles_;
    s.queued = int(queue_.size());
    s.inFlight = reading_;
    return s;
}

}  // namespace sierra::sbt
