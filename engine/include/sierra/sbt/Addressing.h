#pragma once
// Sierpinski binary triangle tree (SBT) addressing, computed instead of stored.
//
// The grid has (2^n + 1)^2 samples, side S = 2^n, vertex (i, j) with i along x
// (column) and j along z (row). Levels 0..2n; level l holds 2^(l+1) right
// isosceles triangles, kept by the paper as one 2D array [r, c] per level.
// Sierra keeps that addressing but computes everything from (level, r, c) in
// O(1); nothing is stored per triangle.
//
// Shapes (each dimension doubles every second level):
//   rows(l) = 2^floor((l+1)/2),  cols(l) = 2^(floor(l/2)+1)
//   level 0: 1x2, 1: 2x2, 2: 2x4, 3: 4x4, 4: 4x8, ...
//
// Even level l = 2k: the square is cut into 2^k x 2^k squares of side S/2^k,
// each split by one diagonal (the 4-8 pattern: square (qx, qy) takes the main
// diagonal (low-low to high-high) when qx + qy is even, else the anti
// diagonal). Cell [r, c] = square (qx = c/2, qy = r), half c%2 (0 = the half
// holding the square's left edge, 1 = the half holding its right edge).
// The right angle sits at a corner of the square.
//
// Odd level l = 2k+1: the same squares cut by both diagonals into four
// quarter triangles whose right angle is the square centre and whose
// hypotenuse is one edge of the square. Cell [r, c] = square (c/2, r/2),
// quarter (r%2, c%2): (0,0) hypotenuse on the low-j edge, (0,1) on the high-i
// edge, (1,1) on the high-j edge, (1,0) on the low-i edge.
//
// Levels 0..3 are fixed patterns; for l >= 4 level l is level l-2 replicated
// four times: type(l, r, c) == type(l-2, r % rows(l-2), c % cols(l-2)).
//
// Vertices are numbered 0, 1, 2 counter-clockwise in the (i, j) plane (i to
// the right, j up): vertex 0 is the right-angle apex, vertices 1 and 2 are the
// hypotenuse endpoints. (The paper numbers them 1..3.)
//
// Sierpinski order (the paper's Algorithm 4): the curve enters every triangle
// at one hypotenuse endpoint and leaves at the other; leftChild is the child
// holding the entry vertex and is visited first. Entry = vertex 1 on even
// levels, vertex 2 on odd levels.
//
// i-neighbour (the same-size neighbour not sharing vertex i), as the paper:
// on even levels all three are found by +-1 on r or on c. On odd levels the
// two leg neighbours (i = 1, 2) are +-1 on r or on c, and the hypotenuse
// neighbour (i = 0) is +-1 on r AND +-1 on c. No layout can do better: with
// the replication rule the four types of level 1 repeat with period 2 in r and
// c, a unit step flips exactly one of (r%2, c%2), and the four quarter types
// are pairwise adjacent (K4), which the 4-cycle of parity classes cannot hold.

#include <cstdint>

namespace sierra::sbt {

// A triangle of the tree: level 0..2n, row r, column c.
struct TriangleId {
    int level = 0;
    int r = 0;
    int c = 0;
    friend bool operator==(const TriangleId&, const TriangleId&) = default;
};

// A grid vertex (i = column along x, j = row along z).
struct GridVertex {
    int i = 0;
    int j = 0;
    friend bool operator==(const GridVertex&, const GridVertex&) = default;
};

// The 8 orientations. Even levels (right angle at a corner of its square,
// named by the direction of that corner from the square centre):
//   kCornerMinusMinus, kCornerPlusMinus, kCornerPlusPlus, kCornerMinusPlus.
// Odd levels (right angle at the square centre, named by the edge holding the
// hypotenuse): kEdgeMinusJ, kEdgePlusI, kEdgePlusJ, kEdgeMinusI.
enum class TriangleType : uint8_t {
    kCornerMinusMinus = 0,
    kCornerPlusMinus = 1,
    kCornerPlusPlus = 2,
    kCornerMinusPlus = 3,
    kEdgeMinusJ = 4,
    kEdgePlusI = 5,
    kEdgePlusJ = 6,
    kEdgeMinusI = 7,
};
inline constexpr int kTriangleTypeCount = 8;

class Addressing {
  public:
    // n >= 1: grid side 2^n + 1 samples.
    constexpr explicit Addressing(int n) : n_(n), side_(1 << n) {}

    constexpr int n() const { return n_; }
    constexpr int levelCount() const { return 2 * n_ + 1; }  // levels 0..2n
    constexpr int finestLevel() const { return 2 * n_; }
    constexpr int samplesPerSide() const { return side_ + 1; }

    static constexpr int rows(int level) { return 1 << ((level + 1) >> 1); }
    static constexpr int cols(int level) { return 1 << ((level >> 1) + 1); }
    static constexpr int64_t triangleCount(int level) { return int64_t(1) << (level + 1); }
    constexpr bool valid(TriangleId t) const {
        return t.level >= 0 && t.level <= finestLevel() && t.r >= 0 && t.r < rows(t.level) &&
               t.c >= 0 && t.c < cols(t.level);
    }

    // Orientation of [level][r, c]: depends only on level parity and (r, c)
    // modulo (2, 4) on even levels, (2, 2) on odd ones.
    static constexpr TriangleType type(TriangleId t) {
        if ((t.level & 1) == 0) {
            bool main = (((t.c >> 1) + t.r) & 1) == 0;
            int h = t.c & 1;
            if (main)
                return h == 0 ? TriangleType::kCornerMinusPlus : TriangleType::kCornerPlusMinus;
            return h == 0 ? TriangleType::kCornerMinusMinus : TriangleType::kCornerPlusPlus;
        }
        constexpr TriangleType quarter[2][2] = {
            {TriangleType::kEdgeMinusJ, TriangleType::kEdgePlusI},
            {TriangleType::kEdgeMinusI, TriangleType::kEdgePlusJ}};
        return quarter[t.r & 1][t.c & 1];
    }

    // Side of the squares of a level, in grid steps (S / 2^floor(level/2)).
    constexpr int squareSide(int level) const { return side_ >> (level >> 1); }

    // Vertex k (0 = right-angle apex, 1 and 2 = hypotenuse endpoints, CCW).
    constexpr GridVertex vertex(TriangleId t, int k) const {
        int s = squareSide(t.level);
        if ((t.level & 1) == 0) {
            int x0 = (t.c >> 1) * s, z0 = t.r * s, x1 = x0 + s, z1 = z0 + s;
            GridVertex v[3];
            switch (type(t)) {
                case TriangleType::kCornerMinusPlus:
                    v[0] = {x0, z1}, v[1] = {x0, z0}, v[2] = {x1, z1};
                    break;
                case TriangleType::kCornerPlusMinus:
                    v[0] = {x1, z0}, v[1] = {x1, z1}, v[2] = {x0, z0};
                    break;
                case TriangleType::kCornerMinusMinus:
                    v[0] = {x0, z0}, v[1] = {x1, z0}, v[2] = {x0, z1};
                    break;
                default:
                    v[0] = {x1, z1}, v[1] = {x0, z1}, v[2] = {x1, z0};
                    break;
            }
            return v[k];
        }
        int x0 = (t.c >> 1) * s, z0 = (t.r >> 1) * s, x1 = x0 + s, z1 = z0 + s;
        if (k == 0) return {x0 + s / 2, z0 + s / 2};
        GridVertex v1, v2;
        switch (type(t)) {
            case TriangleType::kEdgeMinusJ:
                v1 = {x0, z0}, v2 = {x1, z0};
                break;
            case TriangleType::kEdgePlusI:
                v1 = {x1, z0}, v2 = {x1, z1};
                break;
            case TriangleType::kEdgePlusJ:
                v1 = {x1, z1}, v2 = {x0, z1};
                break;
            default:
                v1 = {x0, z1}, v2 = {x0, z0};
                break;
        }
        return k == 1 ? v1 : v2;
    }
    constexpr GridVertex apex(TriangleId t) const { return vertex(t, 0); }
    // The vertex the hypotenuse is split at (its midpoint); only for level < 2n.
    constexpr GridVertex splitVertex(TriangleId t) const {
        GridVertex a = vertex(t, 1), b = vertex(t, 2);
        return {(a.i + b.i) / 2, (a.j + b.j) / 2};
    }
    // Where the Sierpinski curve enters and leaves the triangle.
    constexpr GridVertex entryVertex(TriangleId t) const {
        return vertex(t, (t.level & 1) ? 2 : 1);
    }
    constexpr GridVertex exitVertex(TriangleId t) const { return vertex(t, (t.level & 1) ? 1 : 2); }

    // Children (level + 1, requires level < 2n): leftChild holds the entry
    // vertex and comes first along the Sierpinski curve.
    static constexpr TriangleId leftChild(TriangleId t) { return child(t, 0); }
    static constexpr TriangleId rightChild(TriangleId t) { return child(t, 1); }

    // Parent (requires level > 0).
    static constexpr TriangleId parent(TriangleId t) {
        if ((t.level & 1) == 1) {
            int qx = t.c >> 1, qy = t.r >> 1;
            bool main = ((qx + qy) & 1) == 0;
            TriangleType q = type(t);
            int h;
            if (main)
                h = (q == TriangleType::kEdgeMinusI || q == TriangleType::kEdgePlusJ) ? 0 : 1;
            else
                h = (q == TriangleType::kEdgeMinusJ || q == TriangleType::kEdgeMinusI) ? 0 : 1;
            return {t.level - 1, qy, 2 * qx + h};
        }
        int qx = t.c >> 1, qy = t.r, h = t.c & 1;
        int dx = qx & 1, dy = qy & 1;
        // quarter (a, b) of the parent square: 0,0 low-j; 0,1 high-i; 1,1 high-j; 1,0 low-i
        int a, b;
        if (dx == 0 && dy == 0)
            a = h ? 0 : 1, b = 0;  // B -> low-i, A -> low-j
        else if (dx == 1 && dy == 0)
            a = 0, b = h ? 1 : 0;  // C -> low-j, D -> high-i
        else if (dx == 0 && dy == 1)
            a = 1, b = h ? 1 : 0;  // C -> low-i, D -> high-j
        else
            a = h ? 0 : 1, b = 1;  // B -> high-j, A -> high-i
        return {t.level - 1, 2 * (qy >> 1) + a, 2 * (qx >> 1) + b};
    }

    // The same-size neighbour that does not share vertex k (k = 0 across the
    // hypotenuse, k = 1 across the leg apex-v2, k = 2 across apex-v1), or
    // nullopt-like {-1,-1,-1} (see hasNeighbour) at the domain border.
    static constexpr TriangleId neighbour(TriangleId t, int k) {
        int dr = 0, dc = 0;
        if ((t.level & 1) == 0) {
            switch (type(t)) {
                case TriangleType::kCornerMinusPlus:
                    dr = k == 1 ? 1 : 0, dc = k == 0 ? 1 : k == 2 ? -1 : 0;
                    break;
                case TriangleType::kCornerPlusMinus:
                    dr = k == 1 ? -1 : 0, dc = k == 0 ? -1 : k == 2 ? 1 : 0;
                    break;
                case TriangleType::kCornerMinusMinus:
                    dr = k == 2 ? -1 : 0, dc = k == 0 ? 1 : k == 1 ? -1 : 0;
                    break;
                default:
                    dr = k == 2 ? 1 : 0, dc = k == 0 ? -1 : k == 1 ? 1 : 0;
                    break;
            }
        } else {
            constexpr int kDr[4][3] = {{-1, 0, 1}, {1, 1, 0}, {1, 0, -1}, {-1, -1, 0}};
            constexpr int kDc[4][3] = {{1, 1, 0}, {1, 0, -1}, {-1, -1, 0}, {-1, 0, 1}};
            int q = int(type(t)) - 4;
            dr = kDr[q][k], dc = kDc[q][k];
        }
        TriangleId nb{t.level, t.r + dr, t.c + dc};
        if (nb.r < 0 || nb.r >= rows(t.level) || nb.c < 0 || nb.c >= cols(t.level))
            return {-1, -1, -1};
        return nb;
    }
    static constexpr bool hasNeighbour(TriangleId t, int k) { return neighbour(t, k).level >= 0; }

  private:
    static constexpr TriangleId child(TriangleId t, int which) {
        int l = t.level + 1;
        if ((t.level & 1) == 0) {
            int qx = t.c >> 1, qy = t.r;
            // quarter cells (a, b) in the square's 2x2 block at level l
            int a0, b0, a1, b1;  // left child, right child
            switch (type(t)) {
                case TriangleType::kCornerMinusPlus:
                    a0 = 1, b0 = 0, a1 = 1, b1 = 1;
                    break;  // W, N
                case TriangleType::kCornerPlusMinus:
                    a0 = 0, b0 = 1, a1 = 0, b1 = 0;
                    break;  // E, S
                case TriangleType::kCornerMinusMinus:
                    a0 = 0, b0 = 0, a1 = 1, b1 = 0;
                    break;  // S, W
                default:
                    a0 = 1, b0 = 1, a1 = 0, b1 = 1;
                    break;  // N, E
            }
            return which == 0 ? TriangleId{l, 2 * qy + a0, 2 * qx + b0}
                              : TriangleId{l, 2 * qy + a1, 2 * qx + b1};
        }
        int qx = t.c >> 1, qy = t.r >> 1;
        // children: (quadrant dx, dy, half h) in the level-l squares (2qx+dx, 2qy+dy)
        int dx0, dy0, h0, dx1, dy1, h1;
        switch (type(t)) {
            case TriangleType::kEdgeMinusJ:
                dx0 = 1, dy0 = 0, h0 = 0, dx1 = 0, dy1 = 0, h1 = 1;
                break;
            case TriangleType::kEdgePlusI:
                dx0 = 1, dy0 = 1, h0 = 1, dx1 = 1, dy1 = 0, h1 = 1;
                break;
            case TriangleType::kEdgePlusJ:
                dx0 = 0, dy0 = 1, h0 = 1, dx1 = 1, dy1 = 1, h1 = 0;
                break;
            default:
                dx0 = 0, dy0 = 0, h0 = 0, dx1 = 0, dy1 = 1, h1 = 0;
                break;
        }
        return which == 0 ? TriangleId{l, 2 * qy + dy0, 2 * (2 * qx + dx0) + h0}
                          : TriangleId{l, 2 * qy + dy1, 2 * (2 * qx + dx1) + h1};
    }

    int n_;
    int side_;
};

}  // namespace sierra::sbt
