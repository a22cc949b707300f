#version 450 core
// Horizon angles and the sun's visibility by the sweep of
// analysis/Relief.cpp (Stewart, "Fast Horizon Computation at All Points of a
// Terrain With Visibility and Shading Applications", 1998): one invocation
// per digital line of an azimuth, walking it farthest point first and keeping
// the upper convex hull, in (t, h), of the casting points behind the current
// one in a stack of its own in the scratch buffer. A workgroup holds
// HORIZON_GROUP consecutive lines of one azimuth; they step through the
// major indices together, so neighbouring invocations read neighbouring
// samples, and their stacks are interleaved (entry s of lane L at
// base + s * HORIZON_GROUP + L) so that equal depths are adjacent words.
//
// Points are kept as doubled (major, minor) indices (a cell centre of a
// diagonal lies at odd ones) and a height: distances are differences of
// integers times the azimuth's per-index steps, so they keep float's
// relative precision at any distance from the grid's origin.

#ifndef HORIZON_GROUP
#define HORIZON_GROUP 64
#endif
layout(local_size_x = HORIZON_GROUP) in;

layout(binding = 0) uniform sampler2D uHeights;  // stored heights (R32F), world = stored * uScale
layout(binding = 1) uniform usampler2D uMask;    // R8UI, 0 = no data; read only with uHasMask
uniform float uScale;
uniform bool uHasMask;

// One azimuth's digital lines (analysis/Relief.cpp, makeLines): line o holds
// the samples (major m, minor o + r(m)); t runs along the azimuth, w across
// it, both in world units per unit of major and minor index.
struct Direction {
    vec4 steps;   // dt/dmajor, dt/dminor, dw/dmajor, dw/dminor
    ivec4 lines;  // i is the major axis (1/0), look (+1: the azimuth points to increasing
                  // major index), diagonal (1/0: cell centres join the profile), major count
    ivec4 more;   // minor count, offset of r(0) in offsets[], output layer, slope > 0 (1/0)
    vec4 limit;   // search radius along the azimuth in world units (0 = the whole line)
};
layout(std430, binding = 0) readonly buffer Directions { Direction directions[]; };

// A workgroup's lines [firstLine, firstLine + lines) of a direction, and the
// major indices [majorBegin, majorEnd) where any of them lies in the region.
struct Group {
    int direction, firstLine, lines, majorBegin, majorEnd;
    uint base;  // its scratch entries start here
    int unused0, unused1;
};
layout(std430, binding = 1) readonly buffer Groups { Group groups[]; };
uniform uint uFirstGroup;  // this dispatch's first group
layout(std430, binding = 2) readonly buffer Offsets { int offsets[]; };  // r(m) per direction
layout(std430, binding = 3) buffer Scratch { uvec2 scratch[]; };

// Angles in layer `more.z` of uHorizons; a direction with layer -1 is the
// sun's, whose visibility goes to uSunVisibility (one dispatch may hold both).
layout(r32f, binding = 0) uniform writeonly image2DArray uHorizons;
layout(r32f, binding = 1) uniform writeonly image2D uSunVisibility;
uniform vec2 uSun;    // the disc centre's altitude and the disc's radius, radians
uniform bool uNight;  // the whole disc below the horizontal: 0 wherever there is data

const float kHalfPi = 1.5707963267948966;

// The invocation's line.
Direction gDir;
int gLine, gMinorCount, gOffsets, gMajorBegin, gMajorEnd, gLayer;
uint gBase;

struct Point {
    int m2, n2;  // doubled major and minor index
    float h;     // world height
};

uvec2 pack(Point p) {
    return uvec2(uint(p.m2) | (uint(p.n2) << 16), floatBitsToUint(p.h));
}
Point unpack(uvec2 v) {
    return Point(int(v.x & 0xffffu), int(v.x >> 16), uintBitsToFloat(v.y));
}
// Twice the distance from a to b along the azimuth, and across it.
float dt2(Point a, Point b) {
    return float(b.m2 - a.m2) * gDir.steps.x + float(b.n2 - a.n2) * gDir.steps.y;
}
float dw2(Point a, Point b) {
    return float(b.m2 - a.m2) * gDir.steps.z + float(b.n2 - a.n2) * gDir.steps.w;
}
// True when b lies on or below the line from p to c, t_p < t_b and t_p < t_c:
// b is then the horizon of neither p nor any point before it. Float is
// enough: the distances keep their relative precision (see above), and where
// two hull vertices are tangent from p within it, either gives the horizon
// within 1e-7 rad on rough terrain (tests/gl/relief_gpu_test.cpp).
bool notAbove(Point p, Point b, Point c) {
    return (b.h - p.h) * dt2(p, c) <= (c.h - p.h) * dt2(p, b);
}
// tan of the elevation of q seen from p, at their true horizontal distance.
float slopeTo(Point p, Point q) {
    const float dt = dt2(p, q), dw = dw2(p, q);
    return (q.h - p.h) / (0.5 * sqrt(dt * dt + dw * dw));
}

ivec2 sampleAt(int m, int n) {
    return gDir.lines.x != 0 ? ivec2(m, n) : ivec2(n, m);
}
bool hasData(ivec2 ij) {
    return !uHasMask || texelFetch(uMask, ij, 0).r != 0u;
}
float heightAt(ivec2 ij) {
    return texelFetch(uHeights, ij, 0).r * uScale;
}
int minorOf(int m) {
    return gLine + offsets[gOffsets + m];
}
int majorOfStep(int c) {
    return gDir.lines.y > 0 ? gMajorEnd - 1 - c : gMajorBegin + c;
}

// The centre of the cell between samples (m, n) and (pm, pn) of a diagonal:
// the midpoint of the cell's drawn diagonal (the 4-8 mesh splits cell
// (ci, cj) by its main diagonal when ci + cj is even, else by the other one),
// which casts when both its ends have data.
// `crossing`: the drawn diagonal crosses the line (else it joins the two
// samples, and the centre lies on the segment between them).
Point cellCentre(int m, int n, int pm, int pn, out bool casts, out bool crossing) {
    const ivec2 ij = sampleAt(m, n), pij = sampleAt(pm, pn);
    const ivec2 c = min(ij, pij);
    const bool even = ((c.x + c.y) & 1) == 0;
    crossing = even != (gDir.more.w != 0);
    const ivec2 a = even ? c : ivec2(c.x + 1, c.y);
    const ivec2 b = even ? c + 1 : ivec2(c.x, c.y + 1);
    casts = hasData(a) && hasData(b);
    // precise: a multiply-add fused across the two products would move the
    // height by an ulp, which a near horizon's elevation feels by 1e-6 rad.
    precise float h = 0.5 * (texelFetch(uHeights, a, 0).r * uScale +
                             texelFetch(uHeights, b, 0).r * uScale);
    return Point(m + pm, n + pn, h);
}

// atan for any float (+-inf included), absolute error below 2e-7 rad: the
// CPU's fastAtan (analysis/Relief.cpp), so that both round alike: atan(z) on
// [0, 1] by the degree-17 polynomial of Abramowitz and Stegun, "Handbook of
// Mathematical Functions" (1964), 4.4.49, and pi/2 - atan(1/x) beyond.
float fastAtan(float x) {
    const float ax = abs(x);
    const float z = min(ax, 1.0 / ax);
    const float z2 = z * z;
    const float p =
        z * (1.0 +
             z2 * (-0.3333314528 +
                   z2 * (0.1999355085 +
                         z2 * (-0.1420889944 +
                               z2 * (0.1065626393 +
                                     z2 * (-0.0752896400 +
                                           z2 * (0.0429096138 +
                                                 z2 * (-0.0161657367 + z2 * 0.0028662257))))))));
    const float r = ax > 1.0 ? 1.5707963267948966 - p : p;
    return x < 0.0 ? -r : r;
}

// The result at a receiving point p whose tangent point is q (none: nothing
// casts ahead, the angle is -pi/2).
void finish(Point p, bool any, Point q) {
    const float angle = any ? fastAtan(slopeTo(p, q)) : -kHalfPi;
    const ivec2 ij = sampleAt(p.m2 >> 1, p.n2 >> 1);
    if (gLayer >= 0) {
        imageStore(uHorizons, ivec3(ij, gLayer), vec4(angle));
        return;
    }
    // The area of the disc above a horizontal line at the horizon's height y
    // (in disc radii over its centre): the circular segment
    // (acos y - y sqrt(1 - y^2)) / pi.
    const float y = (angle - uSun.x) / uSun.y;
    // acos from fastAtan: a driver's acos may be off by 1e-5 and more.
    const float s = sqrt(max(1.0 - y * y, 0.0));
    const float arc = kHalfPi - fastAtan(y / s);
    float v = y <= -1.0 ? 1.0 : (y >= 1.0 ? 0.0 : (arc - y * s) / 3.14159265358979);
    if (uNight) v = 0.0;
    imageStore(uSunVisibility, ij, vec4(v));
}

uint entry(int region, int s) {
    return gBase + uint(region + s) * uint(HORIZON_GROUP);
}

// The whole line (no radius): each point pops the hull vertices that lie on
// or under the line from it to the vertex below, finds its tangent point on
// top, and is pushed if it casts; every point is pushed and popped at most
// once. The top vertex stays in registers.
void sweepWhole() {
    int top = 0;
    Point topPoint = Point(0, 0, 0.0);
    bool started = false;
    int pm = 0, pn = 0;
    const int steps = gMajorEnd - gMajorBegin;
    for (int c = 0; c < steps; ++c) {
        const int m = majorOfStep(c), n = minorOf(m);
        if (n < 0 || n >= gMinorCount) {
            if (started) break;  // the line's samples are contiguous
            continue;
        }
        for (int part = (gDir.lines.z != 0 && started) ? 0 : 1; part < 2; ++part) {
            bool casts;
            Point p;
            if (part == 0) {
                // A centre on the segment between two samples cannot change
                // the hull (the CPU leaves it out too): crossing ones only.
                bool crossing;
                p = cellCentre(m, n, pm, pn, casts, crossing);
                if (!casts || !crossing) continue;
            } else {
                const ivec2 ij = sampleAt(m, n);
                casts = hasData(ij);
                if (!casts) continue;  // no data: NaN, cleared before
                p = Point(2 * m, 2 * n, heightAt(ij));
            }
            while (top >= 2) {
                const Point below = unpack(scratch[entry(0, top - 2)]);
                if (!notAbove(p, topPoint, below)) break;
                topPoint = below;
                --top;
            }
            if (part == 1) finish(p, top > 0, topPoint);
            scratch[entry(0, top)] = pack(p);
            topPoint = p;
            ++top;
        }
        started = true;
        pm = m;
        pn = n;
    }
}

// With a radius: point k of the line's profile in sweep order (on a
// diagonal, samples at even k and cell centres at odd k), from the line's
// first step `first`.
int gFirst;
Point profilePoint(int k, out bool casts, out bool receives) {
    const bool diagonal = gDir.lines.z != 0;
    const int s = diagonal ? (k + 1) >> 1 : k;
    const int m = majorOfStep(gFirst + s), n = minorOf(m);
    if (diagonal && (k & 1) == 1) {
        const int pm = m + gDir.lines.y;
        receives = false;
        bool crossing;
        return cellCentre(m, n, pm, minorOf(pm), casts, crossing);
    }
    const ivec2 ij = sampleAt(m, n);
    casts = hasData(ij);
    receives = casts;
    return Point(2 * m, 2 * n, heightAt(ij));
}

const uvec2 kNone = uvec2(0xffffffffu, 0u);  // no tangent point (indices never reach 0xffff)

// The CPU's sweepRadius: the occluders of p are the points q with
// 0 < t_q - t_p <= R. The profile is cut into blocks of length R in t; p's
// occluders are those ahead of it in its own block (the whole-line sweep with
// the stack emptied at each block start) and the part of the previous block
// within R, an upper hull grown in increasing t as p walks its block
// backwards and queried by binary search. Scratch regions of `capacity`
// entries each: the stack, that hull, and each point's tangent point so far.
void sweepRadius(int capacity) {
    const int steps = gMajorEnd - gMajorBegin;
    int last = -1;
    gFirst = -1;
    for (int c = 0; c < steps; ++c) {
        const int n = minorOf(majorOfStep(c));
        if (n >= 0 && n < gMinorCount) {
            if (gFirst < 0) gFirst = c;
            last = c;
        } else if (gFirst >= 0) {
            break;
        }
    }
    if (gFirst < 0) return;
    const int count = gDir.lines.z != 0 ? 2 * (last - gFirst) + 1 : last - gFirst + 1;
    const float radius = gDir.limit.x;
    bool casts, receives;
    const Point origin = profilePoint(0, casts, receives);
    // The block of a point: floor((t_0 - t) / R), made exact at its ends.
    int prevBegin = -1, prevEnd = -1, prevBlock = -2;
    const int kStack = 0, kHull = capacity, kBest = 2 * capacity;
    int begin = 0;
    while (begin < count) {
        const float d0 = 0.5 * dt2(profilePoint(begin, casts, receives), origin);
        int b = int(floor(d0 / radius));
        if (float(b + 1) * radius <= d0) ++b;
        if (float(b) * radius > d0) --b;
        const float blockEnd = float(b + 1) * radius;
        // (a) the own block
        int top = 0, end = begin;
        for (; end < count; ++end) {
            const Point p = profilePoint(end, casts, receives);
            if (end > begin && 0.5 * dt2(p, origin) >= blockEnd) break;
            scratch[entry(kBest, end)] = kNone;
            if (!casts) continue;
            while (top >= 2 && notAbove(p, unpack(scratch[entry(kStack, top - 1)]),
                                        unpack(scratch[entry(kStack, top - 2)])))
                --top;
            if (top > 0) scratch[entry(kBest, end)] = scratch[entry(kStack, top - 1)];
            scratch[entry(kStack, top++)] = pack(p);
        }
        // (b) the previous block, if it is the adjacent one
        if (prevBlock == b - 1) {
            int size = 0, q = prevEnd - 1;
            for (int k = end - 1; k >= begin; --k) {
                const Point p = profilePoint(k, casts, receives);
                if (!receives) continue;
                for (; q >= prevBegin; --q) {
                    bool qCasts, qReceives;
                    const Point pq = profilePoint(q, qCasts, qReceives);
                    if (0.5 * dt2(p, pq) > radius) break;
                    if (!qCasts) continue;
                    while (size >= 2 && notAbove(unpack(scratch[entry(kHull, size - 2)]),
                                                 unpack(scratch[entry(kHull, size - 1)]), pq))
                        --size;
                    scratch[entry(kHull, size++)] = pack(pq);
                }
                if (size == 0) continue;
                // The slope from p along the hull rises, then falls.
                int lo = 0, hi = size - 1;
                while (lo < hi) {
                    const int mid = (lo + hi) / 2;
                    if (!notAbove(p, unpack(scratch[entry(kHull, mid + 1)]),
                                  unpack(scratch[entry(kHull, mid)])))
                        lo = mid + 1;
                    else
                        hi = mid;
                }
                const uvec2 best = scratch[entry(kBest, k)];
                const Point h = unpack(scratch[entry(kHull, lo)]);
                if (best == kNone || !notAbove(p, h, unpack(best)))
                    scratch[entry(kBest, k)] = pack(h);
            }
        }
        for (int k = begin; k < end; ++k) {
            const Point p = profilePoint(k, casts, receives);
            if (!receives) continue;
            const uvec2 best = scratch[entry(kBest, k)];
            finish(p, best != kNone, unpack(best));
        }
        prevBlock = b;
        prevBegin = begin;
        prevEnd = end;
        begin = end;
    }
}

void main() {
    const Group g = groups[uFirstGroup + gl_WorkGroupID.x];
    const int lane = int(gl_LocalInvocationID.x);
    if (lane >= g.lines) return;
    gDir = directions[g.direction];
    gLine = g.firstLine + lane;
    gMinorCount = gDir.more.x;
    gOffsets = gDir.more.y;
    gLayer = gDir.more.z;
    gMajorBegin = g.majorBegin;
    gMajorEnd = g.majorEnd;
    gBase = g.base + uint(lane);
    const int capacity = (gMajorEnd - gMajorBegin) * (gDir.lines.z != 0 ? 2 : 1);
    if (gDir.limit.x > 0.0)
        sweepRadius(capacity);
    else
        sweepWhole();
}
