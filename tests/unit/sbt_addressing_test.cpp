// SBT addressing against brute-force geometry on grids n = 1..6.
#include <sierra/sbt/Addressing.h>
#include <sierra/sbt/VertexErrors.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <map>
#include <set>
#include <utility>
#include <vector>

namespace {

using sierra::sbt::Addressing;
using sierra::sbt::GridVertex;
using sierra::sbt::TriangleId;

int64_t cross(GridVertex o, GridVertex a, GridVertex b) {
    return int64_t(a.i - o.i) * (b.j - o.j) - int64_t(a.j - o.j) * (b.i - o.i);
}

std::pair<int64_t, int64_t> key(GridVertex a, GridVertex b) {
    int64_t ka = int64_t(a.j) * 100000 + a.i, kb = int64_t(b.j) * 100000 + b.i;
    return {std::min(ka, kb), std::max(ka, kb)};
}

std::vector<TriangleId> levelCells(int l) {
    std::vector<TriangleId> cells;
    for (int r = 0; r < Addressing::rows(l); ++r)
        for (int c = 0; c < Addressing::cols(l); ++c) cells.push_back({l, r, c});
    return cells;
}

TEST(SbtAddressing, ShapesHoldTwoToTheLevelPlusOneTriangles) {
    for (int l = 0; l <= 12; ++l) {
        EXPECT_EQ(int64_t(Addressing::rows(l)) * Addressing::cols(l), Addressing::triangleCount(l));
        if (l >= 2) {
            EXPECT_EQ(Addressing::rows(l), 2 * Addressing::rows(l - 2));
            EXPECT_EQ(Addressing::cols(l), 2 * Addressing::cols(l - 2));
        }
    }
}

TEST(SbtAddressing, LevelIsLevelMinusTwoReplicatedFourTimes) {
    for (int l = 4; l <= 12; ++l)
        for (const TriangleId& t : levelCells(l)) {
            TriangleId src{l - 2, t.r % Addressing::rows(l - 2), t.c % Addressing::cols(l - 2)};
            ASSERT_EQ(Addressing::type(t), Addressing::type(src)) << l << " " << t.r << " " << t.c;
        }
}

TEST(SbtAddressing, GeometryOfEveryLevel) {
    for (int n = 1; n <= 6; ++n) {
        Addressing ad(n);
        const int S = 1 << n;
        std::set<int> typesSeen;
        for (int l = 0; l <= ad.finestLevel(); ++l) {
            int64_t area2 = 0;
            std::map<int, std::pair<GridVertex, GridVertex>> shapeOfType;  // legs per type
            for (const TriangleId& t : levelCells(l)) {
                GridVertex v0 = ad.vertex(t, 0), v1 = ad.vertex(t, 1), v2 = ad.vertex(t, 2);
                for (GridVertex v : {v0, v1, v2}) {
                    ASSERT_TRUE(v.i >= 0 && v.i <= S && v.j >= 0 && v.j <= S);
                }
                int64_t c = cross(v0, v1, v2);
                ASSERT_GT(c, 0) << "vertices must be counter-clockwise";
                // right angle at vertex 0, equal legs
                int64_t dot =
                    int64_t(v1.i - v0.i) * (v2.i - v0.i) + int64_t(v1.j - v0.j) * (v2.j - v0.j);
                ASSERT_EQ(dot, 0);
                int64_t l1 =
                    int64_t(v1.i - v0.i) * (v1.i - v0.i) + int64_t(v1.j - v0.j) * (v1.j - v0.j);
                int64_t l2 =
                    int64_t(v2.i - v0.i) * (v2.i - v0.i) + int64_t(v2.j - v0.j) * (v2.j - v0.j);
                ASSERT_EQ(l1, l2);
                area2 += c;
                int type = int(Addressing::type(t));
                typesSeen.insert(type);
                EXPECT_EQ(type >= 4, (l & 1) == 1) << "even levels use types 0-3, odd 4-7";
                // the same type always has the same orientation
                GridVertex d1{v1.i - v0.i, v1.j - v0.j}, d2{v2.i - v0.i, v2.j - v0.j};
                auto [it, fresh] = shapeOfType.try_emplace(type, d1, d2);
                if (!fresh) {
                    EXPECT_EQ(it->second.first, d1);
                    EXPECT_EQ(it->second.second, d2);
                }
            }
            EXPECT_EQ(area2, 2 * int64_t(S) * S) << "areas of level " << l << " sum to the square";
        }
        if (n >= 2) {
            EXPECT_EQ(typesSeen.size(), 8u);
        }
    }
}

TEST(SbtAddressing, ChildrenAndParentRoundTrip) {
    for (int n = 1; n <= 6; ++n) {
        Addressing ad(n);
        for (int l = 0; l < ad.finestLevel(); ++l) {
            std::set<std::pair<int, int>> reached;
            for (const TriangleId& t : levelCells(l)) {
                TriangleId lc = Addressing::leftChild(t), rc = Addressing::rightChild(t);
                ASSERT_TRUE(ad.valid(lc) && ad.valid(rc));
                EXPECT_EQ(Addressing::parent(lc), t);
                EXPECT_EQ(Addressing::parent(rc), t);
                reached.insert({lc.r, lc.c});
                reached.insert({rc.r, rc.c});
                // geometry: children are the halves split at the hypotenuse midpoint
                GridVertex m = ad.splitVertex(t);
                EXPECT_EQ(ad.apex(lc), m);
                EXPECT_EQ(ad.apex(rc), m);
                GridVertex a = ad.entryVertex(t), q = ad.apex(t), b = ad.exitVertex(t);
                // left child: entry a, exit q; right child: entry q, exit b (Sierpinski curve)
                EXPECT_EQ(ad.entryVertex(lc), a);
                EXPECT_EQ(ad.exitVertex(lc), q);
                EXPECT_EQ(ad.entryVertex(rc), q);
                EXPECT_EQ(ad.exitVertex(rc), b);
            }
            EXPECT_EQ(int64_t(reached.size()), Addressing::triangleCount(l + 1));
        }
    }
}

TEST(SbtAddressing, NeighboursShareTheEdgeOppositeTheirVertex) {
    for (int n = 1; n <= 6; ++n) {
        Addressing ad(n);
        const int S = 1 << n;
        for (int l = 0; l <= ad.finestLevel(); ++l) {
            std::map<std::pair<int64_t, int64_t>, std::vector<TriangleId>> byEdge;
            for (const TriangleId& t : levelCells(l))
                for (int k = 0; k < 3; ++k)
                    byEdge[key(ad.vertex(t, (k + 1) % 3), ad.vertex(t, (k + 2) % 3))].push_back(t);
            for (const TriangleId& t : levelCells(l)) {
                for (int k = 0; k < 3; ++k) {
                    GridVertex e0 = ad.vertex(t, (k + 1) % 3), e1 = ad.vertex(t, (k + 2) % 3);
                    const auto& sharing = byEdge[key(e0, e1)];
                    TriangleId expected{-1, -1, -1};
                    for (const TriangleId& o : sharing)
                        if (!(o == t)) expected = o;
                    TriangleId nb = Addressing::neighbour(t, k);
                    ASSERT_EQ(nb, expected)
                        << "n " << n << " level " << l << " [" << t.r << "," << t.c << "] k " << k;
                    bool onBorder = (e0.i == e1.i && (e0.i == 0 || e0.i == S)) ||
                                    (e0.j == e1.j && (e0.j == 0 || e0.j == S));
                    EXPECT_EQ(Addressing::hasNeighbour(t, k), !onBorder);
                    if (nb.level < 0) continue;
                    // same size, and the neighbour does not hold vertex k
                    EXPECT_EQ(cross(ad.vertex(nb, 0), ad.vertex(nb, 1), ad.vertex(nb, 2)),
                              cross(ad.vertex(t, 0), ad.vertex(t, 1), ad.vertex(t, 2)));
                    for (int v = 0; v < 3; ++v) EXPECT_FALSE(ad.vertex(nb, v) == ad.vertex(t, k));
                    // +-1 on r or on c; on odd levels the hypotenuse neighbour is +-1 on both
                    int dr = std::abs(nb.r - t.r), dc = std::abs(nb.c - t.c);
                    if ((l & 1) == 1 && k == 0)
                        EXPECT_TRUE(dr == 1 && dc == 1);
                    else
                        EXPECT_EQ(dr + dc, 1);
                }
            }
        }
    }
}

// The paper's Algorithm 4: post-order traversal down to drawLevel.
void sierpinski(const Addressing& ad, TriangleId t, int drawLevel, std::vector<TriangleId>& out) {
    if (t.level < drawLevel) {
        sierpinski(ad, Addressing::leftChild(t), drawLevel, out);
        sierpinski(ad, Addressing::rightChild(t), drawLevel, out);
    } else {
        out.push_back(t);
    }
}

TEST(SbtAddressing, SierpinskiTraversalIsAContinuousCurve) {
    for (int n = 1; n <= 5; ++n) {
        Addressing ad(n);
        for (int level = 0; level <= ad.finestLevel(); ++level) {
            std::vector<TriangleId> order;
            sierpinski(ad, {0, 0, 0}, level, order);
            sierpinski(ad, {0, 0, 1}, level, order);
            ASSERT_EQ(int64_t(order.size()), Addressing::triangleCount(level));
            for (size_t k = 0; k < order.size(); ++k) {
                const TriangleId& t = order[k];
                const TriangleId& u = order[(k + 1) % order.size()];
                EXPECT_EQ(ad.exitVertex(t), ad.entryVertex(u));
                int shared = 0;
                for (int a = 0; a < 3; ++a)
                    for (int b = 0; b < 3; ++b) shared += ad.vertex(t, a) == ad.vertex(u, b);
                if (order.size() > 1) {
                    EXPECT_EQ(shared, 2) << "consecutive leaves share an edge";
                }
            }
        }
    }
}

TEST(SbtAddressing, SplitVerticesKnowTheirHypotenuseAndLevel) {
    for (int n = 1; n <= 6; ++n) {
        Addressing ad(n);
        for (int l = 0; l < ad.finestLevel(); ++l)
            for (const TriangleId& t : levelCells(l)) {
                GridVertex m = ad.splitVertex(t);
                EXPECT_EQ(sierra::sbt::vertexLevel(m.i, m.j, n), l);
                int ai, aj, bi, bj;
                ASSERT_TRUE(sierra::sbt::hypotenuseEndpoints(m.i, m.j, n, &ai, &aj, &bi, &bj));
                GridVertex a{ai, aj}, b{bi, bj}, v1 = ad.vertex(t, 1), v2 = ad.vertex(t, 2);
                EXPECT_TRUE((a == v1 && b == v2) || (a == v2 && b == v1));
            }
        const int S = 1 << n;
        for (GridVertex c :
             {GridVertex{0, 0}, GridVertex{S, 0}, GridVertex{0, S}, GridVertex{S, S}}) {
            int ai, aj, bi, bj;
            EXPECT_FALSE(sierra::sbt::hypotenuseEndpoints(c.i, c.j, n, &ai, &aj, &bi, &bj));
            EXPECT_EQ(sierra::sbt::vertexLevel(c.i, c.j, n), -1);
        }
    }
}

}  // namespace
