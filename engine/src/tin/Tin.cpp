// The TIN of a heightfield (Tin.h): buildTin runs the mesher (Mesher.h) from
// its checks and initial mesh through the greedy insertion loop to the mesh
// and its zones; measureError checks a mesh against the grid. The mesher's
// triangulation edits are in MeshEdits.cpp, its error scan and heap in
// ErrorScan.cpp.
#include "Mesher.h"

#include <sierra/core/Error.h>
#include <sierra/core/Timer.h>
#include <sierra/tin/Tin.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace sierra::tin {

using detail::scanTriangle;

const char* toString(StopReason reason) {
    switch (reason) {
        case StopReason::Error:
            return "error";
        case StopReason::Triangles:
            return "triangles";
        case StopReason::Points:
            return "points";
        case StopReason::Exhausted:
            return "exhausted";
    }
    return "?";
}

const char* toString(BudgetStop rule) {
    return rule == BudgetStop::BestMax ? "best-max" : "last";
}

namespace detail {

void Mesher::floodZones(const Constraints& constraints, TinResult& result) {
    TinMesh& mesh = result.mesh;
    const int triangles = int(origin_.size() / 3);
    std::vector<int32_t>& zone = mesh.zone;
    zone.assign(size_t(triangles), -1);
    std::vector<int> queue;
    // Seeds from the borderlines inside the grid first, then from the edges on its
    // border (the frame's, and borderlines snapped onto it). A frame edge carries the
    // zone of the map's outermost pixels, which a borderline one pixel from the
    // frame leaves on the wrong side of it once snapped; so a border edge only seeds
    // triangles no inner borderline reaches, and takes the zone of its triangle
    // otherwise. Conflicts are counted between inner borderlines only.
    for (const bool border : {false, true}) {
        for (int e = 0; e < int(origin_.size()); ++e) {
            if (!constrained_[e] || zone_[e] < 0 || (twin_[e] < 0) != border) continue;
            const int t = e / 3;
            if (zone[t] >= 0) {
                if (zone[t] == zone_[e]) continue;
                if (border) {
                    zone_[e] = zone[t];
                    mesh.edgeZones[size_t(t)][size_t(e % 3)] = zone[t];
                } else {
                    ++result.stats.zoneConflicts;
                }
                continue;
            }
            zone[t] = zone_[e];
            queue.assign(1, t);
            while (!queue.empty()) {
                const int u = queue.back();
                queue.pop_back();
                for (int k = 0; k < 3; ++k) {
                    const int h = 3 * u + k;
                    if (constrained_[h] || twin_[h] < 0) continue;
                    const int n = twin_[h] / 3;
                    if (zone[n] < 0) {
                        zone[n] = zone[u];
                        queue.push_back(n);
                    }
                }
            }
        }
    }
    std::unordered_map<int32_t, std::array<int32_t, 2>> bands;
    for (const auto& band : constraints.bands) bands[band.zone] = {band.first, band.second};
    mesh.surfaces.resize(size_t(triangles));
    for (int t = 0; t < triangles; ++t) {
        if (zone[t] < 0) zone[t] = constraints.defaultZone;
        auto it = bands.find(zone[t]);
        mesh.surfaces[size_t(t)] =
            it != bands.end() ? it->second : std::array<int32_t, 2>{zone[t], zone[t]};
    }
}

// The input's checks: limits, and segments that name vertices and zones.
void Mesher::checkInput(const Constraints& constraints) const {
    SIERRA_CHECK(width_ >= 2 && height_ >= 2,
                 "sierra::tin: the heightfield must be at least 2 x 2 samples, got ", width_, " x ",
                 height_);
    SIERRA_CHECK(desc_.maxError >= 0.0 && desc_.maxErrorRel >= 0.0 && desc_.maxTriangles >= 0 &&
                     desc_.maxPoints >= 0 && desc_.snapDistance >= 0.0,
                 "sierra::tin: stop limits and snap distance must not be negative");
    for (const auto& s : constraints.segments) {
        SIERRA_CHECK(s.a >= 0 && s.b >= 0 && size_t(s.a) < constraints.vertices.size() &&
                         size_t(s.b) < constraints.vertices.size(),
                     "sierra::tin: segment (", s.a, ", ", s.b, ") names a vertex outside 0..",
                     int64_t(constraints.vertices.size()) - 1);
        SIERRA_CHECK(s.leftZone >= 0 && s.rightZone >= 0, "sierra::tin: zones must be >= 0, got ",
                     s.leftZone, " and ", s.rightZone);
    }
    for (const auto& v : constraints.vertices)
        SIERRA_CHECK(std::isfinite(v.x) && std::isfinite(v.y),
                     "sierra::tin: a borderline vertex is not finite");
}

// The mesh before the first insertion: the grid's two corner triangles, the
// borderlines recovered in it, and every triangle scanned into the heap.
void Mesher::buildInitialMesh(const Constraints& constraints) {
    // Arrays grow by doubling (amortised: no allocation in most insertions);
    // with a point or triangle budget they are sized once up front.
    int64_t expectedPoints = 1024;
    if (desc_.maxPoints > 0) expectedPoints = desc_.maxPoints;
    if (desc_.maxTriangles > 0)
        expectedPoints = std::max(expectedPoints, desc_.maxTriangles / 2 + 2);
    expectedPoints =
        std::min<int64_t>({expectedPoints, int64_t(width_) * height_, int64_t(1) << 26});
    reserve(size_t(expectedPoints));
    // The grid's corners: two triangles, split along the (0,0)-(w-1,h-1) diagonal.
    const int c00 = addVertex({0, 0}), c10 = addVertex({width_ - 1, 0});
    const int c11 = addVertex({width_ - 1, height_ - 1}), c01 = addVertex({0, height_ - 1});
    const int t0 = addTriangle(), t1 = addTriangle();
    setTriangle(t0, c00, c10, c11);
    setTriangle(t1, c00, c11, c01);
    link(3 * t0 + 2, 3 * t1 + 0);

    // Borderline vertices, snapped to the nearest sample and merged.
    std::unordered_map<int64_t, int> bySample;
    for (int v = 0; v < 4; ++v) bySample[int64_t(pt(v).y) * width_ + pt(v).x] = v;
    std::vector<int> vertexOf(constraints.vertices.size(), -1);
    for (size_t i = 0; i < constraints.vertices.size(); ++i) {
        const auto& cv = constraints.vertices[i];
        const GridPoint p{int32_t(std::clamp(std::floor(cv.x + 0.5), 0.0, double(width_ - 1))),
                          int32_t(std::clamp(std::floor(cv.y + 0.5), 0.0, double(height_ - 1)))};
        const int64_t key = int64_t(p.y) * width_ + p.x;
        auto it = bySample.find(key);
        if (it == bySample.end()) it = bySample.emplace(key, insertVertex(p)).first;
        vertexOf[i] = it->second;
    }
    for (const auto& s : constraints.segments) {
        const int a = vertexOf[size_t(s.a)], b = vertexOf[size_t(s.b)];
        if (a == b) continue;
        segments_.emplace_back(pt(a), pt(b));
        recoverSegment(a, b, s.leftZone, s.rightZone, int32_t(segments_.size()) - 1);
    }
    dataDependent_ = desc_.triangulation == Triangulation::DataDependent;

    // First scan of every triangle.
    const int initial = int(origin_.size() / 3);
    for (int t = 0; t < initial; ++t) {
        scan(t);
        heapUpdate(t);
    }
}

// The progress callback, worst in stored units.
void Mesher::report(double worst, double scale, const TinResult& result) const {
    if (!desc_.progress) return;
    desc_.progress({.points = int64_t(points_.size()),
                    .triangles = int64_t(origin_.size() / 3),
                    .worstError = worst * scale,
                    .targetError = result.stats.targetError});
}

// Where sample p lies in triangle t: exactly on edge *onEdge (a half-edge),
// or next to constrained edge *snapEdge (0..2 in t) within the snap distance
// (snap2: its square) of the input segment, or (both -1) inside.
void Mesher::placeInTriangle(int t, GridPoint p, double snap2, int* onEdge, int* snapEdge) const {
    double snapBest = snap2;
    for (int k = 0; k < 3; ++k) {
        const int e = 3 * t + k;
        const GridPoint a = at(e), b = at(nextHe(e));
        const int64_t o = orient(a, b, p);
        if (o == 0) {
            *onEdge = e;
            break;
        }
        if (!constrained_[e] || twin_[e] < 0 || snap2 <= 0.0) continue;
        // Distance from the input segment this edge comes from.
        const auto [sa, sb] = segments_[size_t(segment_[e])];
        const int64_t os = orient(sa, sb, p);
        const double len2 =
            double(sb.x - sa.x) * (sb.x - sa.x) + double(sb.y - sa.y) * (sb.y - sa.y);
        const double dist2 = double(os) * double(os) / len2;
        const int64_t dotA = int64_t(p.x - a.x) * (b.x - a.x) + int64_t(p.y - a.y) * (b.y - a.y);
        const int64_t dotB = int64_t(p.x - b.x) * (a.x - b.x) + int64_t(p.y - b.y) * (a.y - b.y);
        if (dist2 < snapBest && dotA > 0 && dotB > 0) {
            snapBest = dist2;
            *snapEdge = k;
        }
    }
}

// Greedy insertion: the worst sample of the heap's top triangle, until the
// error target is met, a budget is reached or no sample is left.
void Mesher::insertPoints(double scale, TinResult& result) {
    int64_t sinceProgress = 0;
    const double snap2 = desc_.snapDistance * desc_.snapDistance;
    result.stats.stop = StopReason::Exhausted;
    // With a budget and BudgetStop::BestMax, the mesh of smallest max error so
    // far (the heap's top before each insertion is the current mesh's max error)
    // is the checkpoint that a budget stop goes back to.
    journaling_ =
        (desc_.maxTriangles > 0 || desc_.maxPoints > 0) && desc_.budgetStop == BudgetStop::BestMax;
    struct Kept {
        double error = std::numeric_limits<double>::infinity();  // stored units
        int64_t inserted = 0, edgeSplits = 0, snapSplits = 0, flips = 0;
    } kept;
    while (!heap_.empty()) {
        const int t = heap_.front().triangle;
        const double topError = heap_.front().error;
        result.stats.worstError = topError * scale;
        if (journaling_ && topError <= kept.error) {
            checkpoint();
            kept = {topError, result.stats.inserted, result.stats.edgeSplits,
                    result.stats.snapSplits, flips_};
        }
        if (!(topError > targetStored_)) {
            result.stats.stop = StopReason::Error;
            break;
        }
        const int64_t index = candidate_[t];
        const GridPoint p{int32_t(index % width_), int32_t(index / width_)};
        int onEdge = -1, snapEdge = -1;
        placeInTriangle(t, p, snap2, &onEdge, &snapEdge);
        const int64_t newTriangles = (onEdge >= 0 && twin_[onEdge] < 0) ? 1 : 2;
        if (desc_.maxPoints > 0 && int64_t(points_.size()) + 1 > desc_.maxPoints)
            result.stats.stop = StopReason::Points;
        else if (desc_.maxTriangles > 0 &&
                 int64_t(origin_.size() / 3) + newTriangles > desc_.maxTriangles)
            result.stats.stop = StopReason::Triangles;
        if (result.stats.stop != StopReason::Exhausted) {
            result.stats.budgetInserted = result.stats.inserted;
            result.stats.budgetWorstError = result.stats.worstError;
            if (journaling_) {
                rollback();
                result.stats.worstError = kept.error * scale;
                result.stats.inserted = kept.inserted;
                result.stats.edgeSplits = kept.edgeSplits;
                result.stats.snapSplits = kept.snapSplits;
                flips_ = kept.flips;
            }
            break;
        }
        const int v = addVertex(p);
        ++stamp_;
        dirty_.clear();
        if (onEdge >= 0) {
            splitEdge(onEdge, v);
            ++result.stats.edgeSplits;
        } else if (snapEdge >= 0) {
            snapInsert(t, snapEdge, v);
            ++result.stats.snapSplits;
        } else {
            insertInTriangle(t, v);
        }
        for (int d : dirty_) {
            scan(d);
            heapUpdate(d);
        }
        ++result.stats.inserted;
        if (++sinceProgress >= desc_.progressEvery) {
            sinceProgress = 0;
            report(topError, scale, result);
        }
    }
    if (heap_.empty()) result.stats.worstError = 0.0;
    journaling_ = false;
    if (result.stats.stop != StopReason::Triangles && result.stats.stop != StopReason::Points) {
        result.stats.budgetInserted = result.stats.inserted;
        result.stats.budgetWorstError = result.stats.worstError;
    }
}

// The triangulation as the result's mesh (its zones: floodZones).
void Mesher::writeMesh(TinResult& result) const {
    TinMesh& mesh = result.mesh;
    mesh.gridWidth = width_;
    mesh.gridHeight = height_;
    mesh.spacingX = field_.spacingX();
    mesh.spacingZ = field_.spacingZ();
    mesh.vertices = points_;
    mesh.heights.resize(points_.size());
    for (size_t v = 0; v < points_.size(); ++v)
        mesh.heights[v] = float(height(points_[v].x, points_[v].y)) * field_.verticalScale();
    const int triangles = int(origin_.size() / 3);
    mesh.triangles.resize(size_t(triangles));
    mesh.constrainedEdges.resize(size_t(triangles));
    mesh.edgeZones.resize(size_t(triangles));
    for (int t = 0; t < triangles; ++t) {
        uint8_t bits = 0;
        for (int k = 0; k < 3; ++k) {
            mesh.triangles[size_t(t)][size_t(k)] = origin_[3 * t + k];
            if (constrained_[3 * t + k]) bits |= uint8_t(1u << k);
            mesh.edgeZones[size_t(t)][size_t(k)] = constrained_[3 * t + k] ? zone_[3 * t + k] : -1;
        }
        mesh.constrainedEdges[size_t(t)] = bits;
    }
}

TinResult Mesher::run(const Constraints& constraints) {
    checkInput(constraints);
    TinResult result;
    Stopwatch clock;
    smallGrid_ = std::max(width_, height_) - 1 <= detail::kInCircle64MaxExtent;
    // Error target in stored height units.
    const double scale = std::fabs(double(field_.verticalScale()));
    const auto [lo, hi] = field_.range();
    double target = desc_.maxErrorRel * (double(hi) - double(lo));
    if (desc_.maxError > 0.0)
        target = std::max(target, scale > 0.0 ? desc_.maxError / scale : 1e30);
    targetStored_ = target;
    result.stats.targetError = target * scale;
    buildInitialMesh(constraints);
    result.stats.setupMs = clock.ms();
    clock.restart();

    insertPoints(scale, result);
    result.stats.insertMs = clock.ms();
    report(result.stats.worstError / (scale > 0.0 ? scale : 1.0), scale, result);
    clock.restart();

    writeMesh(result);
    result.stats.flips = flips_;
    floodZones(constraints, result);
    result.stats.zonesMs = clock.ms();
    return result;
}

}  // namespace detail

TinResult buildTin(const terrain::Heightfield& field, const Constraints& constraints,
                   const TinDesc& desc) {
    SIERRA_CHECK(!field.empty(), "sierra::tin: the heightfield is empty");
    detail::Mesher mesher(field, desc);
    return mesher.run(constraints);
}

ErrorStats measureError(const TinMesh& mesh, const terrain::Heightfield& field) {
    SIERRA_CHECK(mesh.gridWidth == field.width() && mesh.gridHeight == field.height(),
                 "sierra::tin::measureError: the mesh is for a ", mesh.gridWidth, " x ",
                 mesh.gridHeight, " grid, the heightfield is ", field.width(), " x ",
                 field.height());
    const int w = field.width();
    std::vector<uint8_t> seen(size_t(field.sampleCount()), 0);
    ErrorStats stats;
    double sum = 0.0;
    const double scale = field.verticalScale();
    for (const auto& tri : mesh.triangles) {
        const GridPoint a = mesh.vertices[size_t(tri[0])], b = mesh.vertices[size_t(tri[1])],
                        c = mesh.vertices[size_t(tri[2])];
        const double za = mesh.heights[size_t(tri[0])], zb = mesh.heights[size_t(tri[1])],
                     zc = mesh.heights[size_t(tri[2])];
        const double ux = b.x - a.x, uy = b.y - a.y, uz = zb - za;
        const double vx = c.x - a.x, vy = c.y - a.y, vz = zc - za;
        const double nz = ux * vy - uy * vx;
        if (nz == 0.0) continue;
        const double gx = -(uy * vz - uz * vy) / nz, gy = -(uz * vx - ux * vz) / nz;
        scanTriangle(a, b, c, [&](int y, int x0, int x1) {
            for (int x = x0; x <= x1; ++x) {
                const size_t i = size_t(y) * size_t(w) + size_t(x);
                if (seen[i]) continue;
                seen[i] = 1;
                const double err = std::fabs(double(field.at(x, y)) * scale -
                                             (za + gx * (x - a.x) + gy * (y - a.y)));
                stats.maxError = std::max(stats.maxError, err);
                sum += err * err;
                ++stats.samples;
            }
        });
    }
    stats.rmsError = stats.samples > 0 ? std::sqrt(sum / double(stats.samples)) : 0.0;
    return stats;
}

}  // namespace sierra::tin
