#pragma once
// View-dependent SBT refinement of a grid held in tiles, some of them absent
// or only partly loaded: the refinement of Refiner::refineView over the data
// that is there, conforming across tile borders whatever is missing.
//
// Tiles: a (2^n+1)^2 grid cut into 2^(n-k) x 2^(n-k) tiles of 2^k cells
// ((2^k+1)^2 samples, neighbours sharing their border samples). A tile is the
// pair of SBT triangles of level 2(n-k) on its square, so every triangle of a
// finer level lies in one tile. The vertices of levels < 2(n-k) are the tile
// corners: always readable. A tile's own vertices (levels 2(n-k) .. 2n-1, its
// interior and its border edges) are loaded coarse levels first: a tile with
// d resident levels has its vertices of levels 2(n-k) .. 2(n-k)+d-1.
//
// Crack-freeness. Refinement is nested (a vertex's error and sphere hold its
// descendants'), so a vertex is split only if all its ancestors are. A vertex
// the data lacks is not split, so "usable" must be nested too: a vertex's
// parents, one level up, lie in a tile that holds the vertex, on its interior
// or on its border with an edge neighbour. With the resident depths d(T)
// lowered to D(T) = min over tiles U of (d(U) + |tx - ux| + |ty - uy|), the
// depths of edge neighbours differ by at most one level, and a vertex of
// tile level l (its level - 2(n-k)) is usable iff l < D(T) for every tile T
// holding it: then each parent, of level l - 1, is usable as well. A tile
// whose refinement reaches a vertex it cannot use is drawn from its coarser
// levels: the mesh stays conforming, and such tiles are counted as coarse.
//
// With every tile wholly resident the decisions are those of
// Refiner::refineViewReference (the same tests in double, on the same
// numbers) and the triangles are the same, in the same Sierpinski order.
// The walk is serial. Above the tiles it reads the corners in double; inside
// a tile it reads the tile's records straight from its level-ordered array
// and takes each test in float with the guard bands of Refiner::refineView's
// fast walk, recomputing in double only inside the band.

#include <sierra/sbt/Refiner.h>
#include <sierra/sbt/VertexErrors.h>
#include <sierra/terrain/Heightfield.h>

#include <array>
#include <cstdint>
#include <vector>

namespace sierra::sbt {

// What the refinement reads of a vertex: its stored height (world y =
// height * verticalScale) and its saturated error and radius in world units,
// over the whole grid (as computeVertexErrors gives them).
struct VertexRecord {
    float height = 0.0f;
    float error = 0.0f;
    float radius = 0.0f;
};

struct TiledGridDesc {
    int n = 1;  // grid side 2^n + 1
    int k = 1;  // tiles of 2^k cells, 1 <= k <= n
    float spacingX = 1.0f, spacingZ = 1.0f, verticalScale = 1.0f;
};

// The tiles as the refinement sees them: what is resident, and a vertex's record.
class TiledVertices {
  public:
    explicit TiledVertices(const TiledGridDesc& desc);
    virtual ~TiledVertices() = default;

    const TiledGridDesc& desc() const { return desc_; }
    int tilesPerSide() const { return 1 << (desc_.n - desc_.k); }
    // Levels of tile (tx, ty) resident, 0..2k (2k: all).
    virtual int residentLevels(int tx, int ty) const = 0;
    // Tile (tx, ty)'s records of its resident levels in level order (the
    // file's order, TileAddressing::index), or null when the tile holds none
    // (a tile wholly in the padding: its records read as zero).
    virtual const VertexRecord* tileRecords(int tx, int ty) const = 0;
    // The record of a tile corner (i, j multiples of 2^k): always there.
    virtual VertexRecord corner(uint32_t i, uint32_t j) const = 0;

  private:
    TiledGridDesc desc_;
};

// Restart marker of TiledMesh::strip.
inline constexpr uint64_t kTiledRestart = ~uint64_t(0);

struct TiledMesh {
    // Generalized triangle strips of packed vertices i | j << 32 (64-bit, so
    // grids past 32-bit linear indices fit), kTiledRestart between strips.
    std::vector<uint64_t> strip;
    int64_t triangleCount = 0;
    int64_t culledSubtrees = 0;
    // Tiles whose refinement reached a vertex beyond their usable levels:
    // drawn from coarser data this time.
    int coarseTiles = 0;
};

class TiledRefiner {
  public:
    // Keeps a reference to `tiles`, which must outlive the refiner.
    explicit TiledRefiner(const TiledVertices& tiles);

    // Refines for `view` over the resident data (residentLevels is read once
    // per call). `out` is overwritten.
    void refineView(const ViewParams& view, TiledMesh& out);

    // Per tile (row-major ty * tiles + tx), the levels usable in the last
    // refinement: the resident depths, balanced as above.
    const std::vector<int>& usableLevels() const { return usable_; }
    // Per tile, the tile levels the last refinement reached: those it read,
    // and one beyond where it stopped at a vertex it could not use (then
    // above usableLevels: the tile was drawn coarse). What a streaming cache
    // keeps and reads next (TileCache::wantForView).
    const std::vector<uint8_t>& reachedLevels() const { return reached_; }

  private:
    struct Walk;
    const TiledVertices& tiles_;
    double magnitude_ = 1.0;  // the largest world coordinate or radius (the float slack's scale)
    std::vector<size_t> levelStart_;   // per tile level: its first record
    std::vector<VertexRecord> zeros_;  // the records of a tile that holds none
    std::vector<int> usable_;
    std::vector<uint8_t> reached_;
};

// Triangles of a TiledMesh strip as linear indices j * side + i (GL's winding
// rule, degenerate ones dropped), for grids that fit 32 bits (tests).
std::vector<std::array<uint32_t, 3>> decodeTiledStrip(const std::vector<uint64_t>& strip, int side);

// TiledVertices over a (2^n+1)^2 field in memory and its computeVertexErrors,
// each tile's residency set by hand: the tiled refinement's tests and
// benchmarks against Refiner. Keeps pointers to both, and every tile's
// records packed in level order (12 bytes a vertex).
class InMemoryTiles : public TiledVertices {
  public:
    InMemoryTiles(const terrain::Heightfield& field, const VertexErrors& errors, int k);
    int residentLevels(int tx, int ty) const override;
    const VertexRecord* tileRecords(int tx, int ty) const override;
    VertexRecord corner(uint32_t i, uint32_t j) const override;
    // Every tile resident to `levels` (0..2k).
    void setAllResident(int levels);
    void setResident(int tx, int ty, int levels);
    // Vertex (i, j), resident or not.
    VertexRecord vertex(uint32_t i, uint32_t j) const;

  private:
    const terrain::Heightfield& field_;
    const VertexErrors& errors_;
    std::vector<std::vector<VertexRecord>> packed_;  // per tile
    std::vector<int> resident_;
};

}  // namespace sierra::sbt
