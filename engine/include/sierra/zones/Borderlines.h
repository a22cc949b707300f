#pragma once
// Vectorised borderlines (section 4 of 002_b56d55d1c6f1d101.txt): the pixel
// boundaries between zones as vertices and directed edges, each edge carrying
// the zone on its left and on its right; the paper's rules 1-3; the optional
// doubling into transition bands. This struct is what the TIN consumes.
//
// Coordinates: zone-map pixel units, origin at the top-left corner of the map,
// x to the right, y down; pixel (i, j) covers [i, i+1] x [j, j+1]. Seen from
// above (world +y up, x east, z = map y) the left of an edge in the image is
// the left in the world.

#include <sierra/zones/ZoneMap.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace sierra::zones {

// Zone number on the outer side of the frame edges (outside the map).
constexpr int32_t kOutside = -1;

struct Vertex {
    double x = 0.0;
    double y = 0.0;
};

struct Edge {
    uint32_t from = 0;
    uint32_t to = 0;
    int32_t left = kOutside;   // zone on the left of from -> to (as drawn: x right, y down)
    int32_t right = kOutside;  // zone on the right
};

struct Zone {
    int32_t id = 0;                // == index in Borderlines::zones
    std::string name;              // surface name; a band zone is "a|b"
    Colour colour = 0;             // 0xRRGGBB; a band zone gets the mean of its two zones
    int32_t bandOf[2] = {-1, -1};  // for a band zone: the two zones it blends (lower id first)
};

struct Borderlines {
    std::vector<Vertex> vertices;
    std::vector<Edge> edges;  // borderlines plus the frame (edges with kOutside on one side)
    std::vector<Zone> zones;  // base zones (palette order), then band zones
    // The frame: the domain the zone polygons tile. Touching layout: the whole
    // map, [0, width] x [0, height]. Figure 1 layout: the polygon through the
    // centres of the outer pixels, [0.5, width - 0.5] x [0.5, height - 0.5]
    // (the half-pixel margin outside it takes the zone of the nearest frame edge).
    double frameX0 = 0, frameY0 = 0, frameX1 = 0, frameY1 = 0;
    int mapWidth = 0;
    int mapHeight = 0;
    ZoneLayout layout = ZoneLayout::Touching;
};

// Raw vectorising. Touching layout: every unit pixel edge between two zones,
// and every unit edge of the map's border, becomes an edge between lattice
// vertices. Figure 1 layout: every pair of 4-neighbouring borderline pixels,
// and every pair of diagonal ones with no borderline pixel as a common
// 4-neighbour, becomes an edge between the pixel centres; the frame joins the
// outer pixel centres. Vertices are created once per position (rule 1 holds),
// no other rule is applied. Edges whose two sides are the same zone (a stray
// spur of borderline pixels) are dropped.
Borderlines vectorise(const ZoneMap& map, const Palette& palette);

// Rule 1: vertices at the same position (exactly) become one; edges are
// renumbered, edges reduced to a point and repeated edges are removed.
void removeDuplicateVertices(Borderlines& lines);

// A vertex is a junction (pinned by rules 2 and 3) unless it has exactly two
// edges carrying the same pair of zones; the four frame corners are junctions.
std::vector<bool> junctions(const Borderlines& lines);

// Rule 2: a non-junction vertex between two collinear edges is removed and its
// two edges become one.
void removeCollinearVertices(Borderlines& lines);

// Rule 3, per arc (the chain of edges between two junctions; a closed loop with
// none is pinned at its first vertex and the vertex farthest from it): a vertex
// is removed when it lies within `epsilon` (pixels) of the segment that
// replaces it, applied as Douglas-Peucker so every removed vertex ends within
// epsilon of the final simplified arc. Both zones of an arc share its edges, so
// zones never open gaps or overlap. epsilon <= 0 does nothing.
void simplifyArcs(Borderlines& lines, double epsilon);

// Doubles every borderline (edges between two zones, not the frame) into two
// copies offset by +-width/2 along the mitred normals of the arc simplified at
// width/4 (so wiggles smaller than the band do not fold it), with a new band zone
// "a|b" between them (one per zone pair). The band has the full width along
// the arc and narrows to the junction vertex over the last min(2 width,
// length/3) pixels of an arc end that is a junction. Where a band would not
// fit (a strip narrower than the band, a tight bend) and its copies would cross
// other lines, that arc's band is narrowed to width/2, then width/4, and at
// last the arc is left single: the result is always a valid subdivision.
// width <= 0 does nothing. `snap`, when given, moves every vertex of the
// copies (e.g. onto the samples of a mesh's grid) before that check, so the
// result is a valid subdivision with the snapped positions; consecutive copy
// vertices that snap to one position become one.
void doubleBorderlines(Borderlines& lines, double width,
                       const std::function<Vertex(const Vertex&)>& snap = {});

struct BorderlineDesc {
    double epsilon = 0.0;    // rule 3 tolerance, zone-map pixels; 0 = rules 1-2 only
    double bandWidth = 0.0;  // transition band width, zone-map pixels; 0 = no band
};

// vectorise, rules 1-2, rule 3 (epsilon), then doubling (bandWidth).
Borderlines buildBorderlines(const ZoneMap& map, const Palette& palette,
                             const BorderlineDesc& desc = {});

// Area of each zone from the edges (index = zone id), square pixels: the
// shoelace terms (x0 y1 - x1 y0) / 2 of the edges with the zone on their right
// minus those of the edges with it on their left (y points down). Exact for
// lattice coordinates; a zone overlapped by a band that does not fit comes out
// smaller, even negative.
std::vector<double> zoneAreas(const Borderlines& lines);

// An SVG of the edges drawn over the zone map image `imageHref` (a path or a
// data URI; empty = no image): borderlines in red, band copies in yellow, the
// frame in blue, vertices as dots.
std::string borderlinesToSvg(const Borderlines& lines, const std::string& imageHref);

// "data:image/png;base64,..." of PNG bytes, for embedding the map in the SVG.
std::string pngDataUri(const std::vector<uint8_t>& png);

}  // namespace sierra::zones
