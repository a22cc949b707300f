#pragma once
// SBT refinement in Lindstrom and Pascucci's style: a top-down recursion over
// vertex coordinates (nothing stored per triangle), flat arrays, no virtual
// calls, no allocation per frame once the buffers have grown (output and
// per-chunk buffers are reused; parallelChunks' helper threads are started once
// and kept).
//
// Output: generalized triangle strips in Sierpinski-curve order (the paper's
// Algorithm 4): the leaves of the tree are visited along the curve, left child
// (the one holding the triangle's entry vertex) first. A vertex is appended
// when it is not one of the last two; when the level parity of the append
// equals the parity of the previous one, the second-to-last vertex is re-sent
// first so the strip turns (Lindstrom and Pascucci's tstrip-append).
//
// Threads: small refinements (fewer than kParallelTriangles triangles the
// previous time) run serially. Otherwise the tree is cut at a fixed level
// (RefinerDesc::chunkLevel) into disjoint subtrees taken in Sierpinski order;
// each is refined on its own into its own strip and the strips are joined in
// that order (the copies in parallel) with primitive restart
// (kRestartIndex), or continued through degenerate triangles where consecutive
// subtrees meet along the curve. The cut does not depend on the thread count,
// so the output is byte-identical for any number of threads.
//
// Winding: every decoded triangle (GL rule: odd positions swap their first two
// vertices) is clockwise in the (i, j) plane, which is counter-clockwise seen
// from above (+y) with x = i and z = j: front faces point up under GL's default
// glFrontFace(GL_CCW).

#include <sierra/sbt/VertexErrors.h>
#include <sierra/terrain/Heightfield.h>

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace sierra::sbt {

// Primitive-restart index between strips (glPrimitiveRestartIndex or
// GL_PRIMITIVE_RESTART_FIXED_INDEX with 32-bit indices).
inline constexpr uint32_t kRestartIndex = 0xFFFFFFFFu;

struct StripMesh {
    // Linear vertex indices j * side + i; kRestartIndex separates strips.
    std::vector<uint32_t> indices;
    int64_t triangleCount = 0;  // leaf triangles emitted (non-degenerate)
    int stripCount = 0;
    // View mode with culling: subtrees dropped whole because the split-vertex
    // sphere of their root triangle lies outside a frustum plane (0 without
    // culling and in fixed mode). The same for any thread count.
    int64_t culledSubtrees = 0;
    // 1 when the refinement ran on the calling thread alone; else the thread
    // count it ran with (given, or sierra::defaultThreadCount()): helpers
    // took part, though with more threads than chunks not every one of them.
    int threads = 1;
    double indicesPerTriangle() const {
        return triangleCount ? double(indices.size()) / double(triangleCount) : 0.0;
    }
};

// A plane a*x + b*y + c*z + d, >= 0 inside, (a, b, c) unit length, world units.
struct Plane {
    float a = 0, b = 0, c = 0, d = 0;
};

struct ViewParams {
    std::array<float, 3> eye{0, 0, 0};  // camera position, world units
    // lambda = viewport height in pixels / (2 tan(fovy / 2)); see projectionLambda.
    float lambda = 1.0f;
    float tau = 1.0f;  // screen-space error threshold in pixels, default 1
    // Frustum planes (inside: a*x + b*y + c*z + d >= 0, normalised); order free.
    std::array<Plane, 6> planes{};
    bool cull = true;  // false: no frustum culling (planes ignored)
};

// lambda for a viewport `viewportHeightPx` pixels high and a vertical field of
// view `fovyRadians`.
float projectionLambda(float viewportHeightPx, float fovyRadians);

// The 6 normalised planes of the frustum of a column-major (OpenGL) 4x4
// view-projection matrix (Gribb and Hartmann), clip space -w <= x, y, z <= w.
std::array<Plane, 6> frustumPlanes(const float viewProjection[16]);

// The view of a perspective look-at camera (+y up) at `eye` looking at
// `target` (world units): vertical field of view `fovyRadians`, `aspect` =
// width / height, a viewport `viewportHeightPx` pixels high, clip planes at
// `nearPlane` and `farPlane` along the view (world units), tau in pixels. For
// tools and tests; the renderer builds its view from its own camera.
ViewParams lookAtView(const std::array<float, 3>& eye, const std::array<float, 3>& target,
                      float fovyRadians, float aspect, float viewportHeightPx, float nearPlane,
                      float farPlane, float tau = 1.0f, bool cull = true);

// A refinement whose previous call in the same mode made fewer triangles runs
// on the calling thread alone, whatever the thread count (the output is the
// same either way).
inline constexpr int64_t kParallelTriangles = int64_t(1) << 17;

// The default thread count (threads 0) adapts to the machine's load: a
// refinement that may use sierra::defaultThreadCount() threads runs on one
// unless the recent ones in its mode ran at least 10% faster per triangle on
// several (median wall time per triangle, measured; a near tie goes to one
// thread, whose times scatter less; the other way is tried again every few
// refinements).
// With the other core busy, two threads can lose to one (the helper shares a
// core with the caller); the default never keeps the slower way for long.
// An explicit count is used as given (tests and benchmarks compare them).
struct ThreadChoice {
    // Seconds per triangle of the last kKept counted refinements on one
    // thread ([0]) and on several ([1]), and their median (estimate: a
    // refinement slowed once, by a page fault storm or a preempted helper,
    // does not turn the choice).
    static constexpr int kKept = 5;
    // Before it chooses, the two ways alternate (several threads first) until
    // each has run kLearn counted refinements: a choice made from one
    // refinement each way could follow one slowed refinement for kProbeFar
    // refinements (a whole short run).
    static constexpr int kLearn = 3;
    double recent[2][kKept] = {};
    int64_t samples[2] = {0, 0};  // refinements each way so far (the first is not counted)
    int sinceProbe = 0;
    double estimate(int way) const;
    // True: run the next refinement on one thread.
    bool serial();
    void record(bool parallel, double seconds, int64_t triangles);
};

struct RefinerDesc {
    int threads = 0;      // 0 = sierra::defaultThreadCount(), adaptive (ThreadChoice)
    int chunkLevel = -1;  // level of the parallel subtrees; -1 = clamp(2n - 10, 0, 6)
};

class Refiner {
  public:
    // Keeps pointers to `field` and `errors`: both must outlive the refiner and
    // stay unchanged. errors must come from computeVertexErrors(field).
    Refiner(const terrain::Heightfield& field, const VertexErrors& errors, RefinerDesc desc = {});
    ~Refiner();
    Refiner(const Refiner&) = delete;
    Refiner& operator=(const Refiner&) = delete;

    // Fixed-error mesh: a triangle splits while level < 2n and the saturated
    // error of its hypotenuse midpoint is > epsilon (world height units).
    // epsilon < 0 gives the full grid. `out` is overwritten, its capacity reused.
    void refineFixed(float epsilon, StripMesh& out);

    // View-dependent mesh: vertex m is active iff
    //   (lambda * e(m) / tau + r(m))^2 > |p(m) - eye|^2,
    // i.e. lambda * e / (d - r) > tau; a triangle splits while level < 2n and
    // its split vertex is active. With culling, a triangle whose split-vertex
    // sphere lies fully outside a plane is not emitted (the sphere holds both
    // triangles of the pair and all their descendants), and below a sphere
    // fully inside all planes no plane is tested again.
    //
    // Decisions are taken in float where the float result provably equals the
    // double-precision one (a guard band around every threshold, double inside
    // it): the output is byte-identical to refineViewReference.
    void refineView(const ViewParams& view, StripMesh& out);

    // The baseline of refineView: the same recursion with every test in double
    // on the three separate arrays (height, error, radius). For tests and
    // benchmarks.
    void refineViewReference(const ViewParams& view, StripMesh& out);

    // Builds what refineView builds on its first call (the view keys: about
    // 0.1 s on one thread and 8 bytes per sample at 2049^2), so that a
    // renderer pays it with the terrain's other preprocessing rather than in
    // its first frame. lambdaOverTau: the lambda / tau the renderer will refine
    // with (0: not known yet; the first refineView then makes the reach keys).
    // Does nothing when the keys exist.
    void prepareView(double lambdaOverTau = 0.0);
    // The lambda / tau the view keys' reaches were made for (0: none yet).
    double reachKeyFactor() const { return keyReachFactor_; }
    // Bytes held by the keys built so far (split keys: refineFixed; view keys:
    // refineView or prepareView).
    size_t keyBytes() const;
    // Bytes held by the working buffers of the refinements so far (the chunks'
    // strips and recursion records; capacities, which later refinements reuse).
    size_t bufferBytes() const;

    int n() const { return n_; }
    int side() const { return side_; }
    int chunkLevel() const { return chunkLevel_; }
    void setThreads(int threads) { threads_ = threads; }  // 0: the adaptive default
    // What the adaptive default has learned in view (true) or fixed mode; a
    // benchmark that builds a refiner per run carries it over, as a
    // renderer's refiner keeps it from frame to frame.
    ThreadChoice& threadChoice(bool view) { return view ? viewThreads_ : fixedThreads_; }

    struct Op;     // implementation detail (top-level recursion record)
    struct Chunk;  // implementation detail (one subtree's strip)
    struct Frame;  // implementation detail (one refinement's working data)
    struct Copy {  // implementation detail (one strip's place in the output)
        const uint32_t* src;
        int64_t length;
        int64_t dst;   // offset in the output
        bool restart;  // a restart index goes at dst - 1
    };

  private:
    template <bool kView, bool kFast = false>
    void run(const ViewParams* view, float epsilon, StripMesh& out);
    // The steps of run (Refiner.cpp; chooseThreads: ThreadPolicy.cpp).
    int takeFrame(bool* helperBusy);
    template <typename W>
    void setUpWalker(W& proto, const ViewParams* view, float epsilon, Frame& frame);
    template <typename W>
    void setUpViewKeys(W& proto, double magnitude, Frame& frame);
    void followReachFactor(double lambdaOverTau);
    int chooseThreads(bool view, bool helperBusy, bool* adaptive);
    void buildSplitKeys();
    void buildViewKeys();
    void buildReachKeys(double lambdaOverTau);
    template <typename Visit>
    void forEachNode(Visit&& visit);
    void measureMagnitude();

    const terrain::Heightfield* field_;
    const VertexErrors* errors_;
    int n_ = 0;
    int side_ = 0;
    int threads_ = 0;
    int chunkLevel_ = 0;
    // Two sets of per-refinement data (recursion records, chunk strips, the
    // walker's set-up): a helper thread preempted inside a chunk may still be
    // reading one after its refinement has returned (the caller ran that chunk
    // again, see parallelRescuedChunks), so the next refinement takes the
    // other, on one thread. busyFrame_: the set such a helper may hold, -1 none.
    std::unique_ptr<Frame> frames_[2];
    int busyFrame_ = -1;
    std::vector<Copy> copies_;
    // Split keys for refineFixed: per triangle of levels 0..2n-1, the top 16 bits
    // of its split vertex's error (a monotone, conservative bfloat16), in tree
    // order: the two level-0 triangles are nodes 0 and 1, the children of node k
    // are 2k + 2 (left) and 2k + 3 (right), so every level is contiguous and in
    // Sierpinski order, and the recursion reads each level front to back instead
    // of hopping across the row-major error array. A key above (below) the key of
    // epsilon decides the split exactly; equal keys fall back to the float error.
    // Memory: 2 * (2^(2n+1) - 2) bytes, about 4 bytes per grid sample, on top of
    // the 8 of VertexErrors. Empty (exact path only) when an error is NaN or negative.
    std::vector<uint16_t> splitKeys_;
    bool keysBuilt_ = false;  // built by the first refineFixed() with epsilon >= 0
    // View keys for refineView below spheres fully inside the frustum: per
    // triangle of levels 0..2n-1, in the tree order of splitKeys_, two 16-bit
    // keys of its split vertex, stored per pair of siblings (nodes 2p, 2p + 1:
    // heights, then reaches, each left then right, 8 bytes) so that both
    // children of a triangle are tested at once. The reach is
    // lambda / tau * e + r for the lambda / tau of keyReachFactor_, computed
    // in double as the baseline does, as a length key (lengthKey in
    // engine/src/sbt/Keys.h: 5 exponent and 11 mantissa bits of the float above a base
    // 32 binades below the largest reach, keyReachBase_; the reach lies
    // between the floats of its key and of the next key). The height key is
    // the world height in steps of 1/65535 of the grid's height range
    // (keyYBase_ + key * keyYStep_, within keyYError_ of the exact one) whose
    // low 2 bits are the vertex's ratio class c: its radius is at most
    // 2^(-12 + 4 c) times its reach. A view with another lambda / tau, s
    // times the keys', has a reach between (s - max(s - 1, 0) rho) and
    // (s + max(1 - s, 0) rho) times the keys' bounds, rho = 2^(-12 + 4 c):
    // nearly s times them where the error dominates the reach, as it does on
    // most vertices. After kReachRebuildAfter refinements in a row with one
    // other factor the keys are made again for it (Refiner::followReachFactor). The keys
    // decide all but the vertices near the threshold (about 0.06% on a rough
    // 2049^2 fractal at tau = 1), which read the exact arrays, and a
    // subtree's keys sit together level by level instead of scattered over
    // three row-major arrays.
    // Memory: 4 * (2^(2n+1) - 2) bytes, about 8 bytes per grid sample. Built
    // by prepareView() or the first refineView(); empty (exact path only) when a height is not
    // finite or an error or radius is NaN or negative.
    std::vector<uint16_t> viewKeys_;
    float keyYBase_ = 0, keyYStep_ = 0, keyYError_ = 0;  // world units
    double keyReachFactor_ = 0.0;  // lambda / tau of the reach keys; 0: not made yet
    uint32_t keyReachBase_ = 0;    // float bit pattern
    // The other factor the last refinements asked for, and how many in a row.
    double otherReachFactor_ = 0.0;
    int otherReachCount_ = 0;
    // Largest |world coordinate| or radius of the grid (world units), measured
    // by prepareView() or the first refineView(); -1 until then.
    double magnitude_ = -1.0;
    // Triangles of the last refinement in each mode (-1: none yet), the work
    // estimate that keeps small refinements serial (see kParallelTriangles).
    int64_t lastViewTriangles_ = -1;
    int64_t lastFixedTriangles_ = -1;
    int64_t lastViewIndices_ = 0, lastFixedIndices_ = 0;  // strip indices of the last refinement
    // The default thread count's choice in each mode.
    ThreadChoice viewThreads_, fixedThreads_;
    // Per subtree at the chunk level (tree order), the triangles it made in the
    // last refinement in each mode: chunks are handed out largest first.
    std::vector<int64_t> viewChunkWork_;
    std::vector<int64_t> fixedChunkWork_;
};

// Triangles of a strip (kRestartIndex-separated), 3 indices each, degenerate
// ones dropped, GL's winding rule applied (odd positions swap their first two).
std::vector<std::array<uint32_t, 3>> decodeStrip(const std::vector<uint32_t>& indices);

// Number of distinct vertices referenced by `indices` (restarts ignored).
int64_t countDistinctVertices(const std::vector<uint32_t>& indices, int side);

// The largest |grid world height - mesh height| over all grid samples, the
// mesh interpolated linearly over each triangle on the samples it covers
// (triangles are linear indices j * side + i into `field`). Multithreaded.
double maxVerticalDistance(const terrain::Heightfield& field,
                           const std::vector<std::array<uint32_t, 3>>& triangles, int threads = 0);

}  // namespace sierra::sbt
