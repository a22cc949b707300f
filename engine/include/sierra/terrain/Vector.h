#pragma once
// Vector layers over a heightfield: points, lines and polygons read through
// GDAL's OGR (GeoJSON, GeoPackage, Shapefile, and GPX or KML where the
// library has them), reprojected into the heightfield's reference system and
// expressed in its sample coordinates, so any renderer places them with the
// grid's spacing.
//
// Sample coordinates: (i, j) is the centre of sample column i, row j, as in
// Heightfield (i along +x, j along +z); a point between samples has
// fractional coordinates. A heightfield with no georeference takes the
// layer's coordinates as sample coordinates already.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace sierra::terrain {

struct GridPoint {
    double i = 0.0, j = 0.0;  // sample coordinates
    bool operator==(const GridPoint&) const = default;
};

struct VectorFeature {
    enum class Kind { Point, Line, Polygon };
    Kind kind = Kind::Point;
    // Point: one part of one point. Line: one polyline. Polygon: the outer
    // ring, then its holes (each ring closed: last point = first).
    std::vector<std::vector<GridPoint>> parts;
    std::string label;  // the label field's value ("" when none was asked for)
};

// Where the grid lies: GDAL's geotransform of pixel corners and the system's
// WKT (the same numbers a GeoTIFF holds), and the grid's size in samples.
struct GridPlacement {
    std::array<double, 6> geoTransform{0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
    std::string crsWkt;  // "" = no reference system
    int width = 0, height = 0;
};

struct VectorReadOptions {
    // The grid the layer is placed on; nullopt = coordinates are sample coordinates.
    std::optional<GridPlacement> placement;
    int width = 0, height = 0;  // the grid's size when there is no placement
    std::string where;          // an OGR SQL attribute filter, e.g. "type = 'river'"; "" = all
    std::string labelField;     // the field whose value labels each feature; "" = none
};

struct VectorLayer {
    std::string name;                     // the layer's name in its file
    std::vector<VectorFeature> features;  // multi-geometries come as one feature a part
    int64_t read = 0;                     // features the filter let through
    int64_t outside = 0;                  // of those, dropped: no part on the grid
    int64_t vertices = 0;                 // over the features kept
    bool reprojected = false;             // the layer's system differed from the grid's
    bool assumedGridSystem = false;       // the layer has no system: the grid's was assumed
};

// Reads every layer of `path` (features of all layers, in order). Throws
// sierra::Error naming the file for one GDAL cannot open as vectors, a bad
// filter, a label field the layer lacks, a system with no transformation to
// the grid's, or a file with no features at all; a layer wholly off the grid
// is not an error (outside counts it, features is empty). Built without GDAL,
// throws saying so.
VectorLayer readVectorLayer(const std::string& path, const VectorReadOptions& options);

// The sample coordinates of WGS 84 longitude and latitude (degrees) on a
// grid placed in a reference system (labels at @LON,LAT). Throws
// sierra::Error when the grid has no system or the point has no place in it.
GridPoint geographicToSamples(const GridPlacement& placement, double longitude, double latitude);

}  // namespace sierra::terrain
