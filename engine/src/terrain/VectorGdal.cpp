// readVectorLayer (terrain/Vector.h) through GDAL's OGR. Built with
// SIERRA_WITH_GDAL; without it, readVectorLayer says so.
#include <sierra/terrain/Vector.h>

#include "terrain/GdalSession.h"

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>

#include <algorithm>
#include <cmath>
#include <memory>

#ifdef SIERRA_WITH_GDAL
#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>
#endif

namespace sierra::terrain {

#ifndef SIERRA_WITH_GDAL
VectorLayer readVectorLayer(const std::string& path, const VectorReadOptions&) {
    throw Error(msg(path,
                    ": vector layers need GDAL, and this build has none (rebuild with "
                    "libgdal-dev installed)"));
}
#else
namespace {

// Maps the layer's coordinates to sample coordinates and keeps the parts of
// each geometry that touch the grid.
class Converter {
  public:
    Converter(const VectorReadOptions& options) {
        if (options.placement) {
            const auto& g = options.placement->geoTransform;
            double forward[6];
            std::copy(g.begin(), g.end(), forward);
            if (!GDALInvGeoTransform(forward, inverse_))
                throw Error(msg("the grid's geotransform (", g[1], ", ", g[2], ", ", g[4], ", ",
                                g[5], ") cannot be inverted"));
            placed_ = true;
            width_ = options.placement->width;
            height_ = options.placement->height;
        } else {
            width_ = options.width;
            height_ = options.height;
        }
        SIERRA_CHECK(width_ > 0 && height_ > 0, "vector layers need a grid, got ", width_, "x",
                     height_);
    }

    GridPoint sample(double x, double y) const {
        if (!placed_) return {x, y};
        // GDAL's pixel corners to sample centres: half a pixel less.
        return {inverse_[0] + inverse_[1] * x + inverse_[2] * y - 0.5,
                inverse_[3] + inverse_[4] * x + inverse_[5] * y - 0.5};
    }
    bool onGrid(const std::vector<GridPoint>& part) const {
        double i0 = INFINITY, i1 = -INFINITY, j0 = INFINITY, j1 = -INFINITY;
        for (const GridPoint& p : part) {
            if (!std::isfinite(p.i) || !std::isfinite(p.j)) return false;
            i0 = std::min(i0, p.i), i1 = std::max(i1, p.i);
            j0 = std::min(j0, p.j), j1 = std::max(j1, p.j);
        }
        return !part.empty() && i1 >= 0.0 && j1 >= 0.0 && i0 <= width_ - 1.0 && j0 <= height_ - 1.0;
    }

    std::vector<GridPoint> points(const OGRSimpleCurve& curve) const {
        std::vector<GridPoint> out(size_t(curve.getNumPoints()));
        for (int k = 0; k < curve.getNumPoints(); ++k)
            out[size_t(k)] = sample(curve.getX(k), curve.getY(k));
        return out;
    }

    // Appends the parts of `g` that touch the grid; returns the parts seen.
    int collect(const OGRGeometry& g, const std::string& label,
                std::vector<VectorFeature>& out) const {
        using Kind = VectorFeature::Kind;
        const OGRwkbGeometryType type = wkbFlatten(g.getGeometryType());
        if (type == wkbPoint) {
            const auto& p = *g.toPoint();
            if (p.IsEmpty()) return 0;
            VectorFeature f{Kind::Point, {{sample(p.getX(), p.getY())}}, label};
            if (onGrid(f.parts[0])) out.push_back(std::move(f));
            return 1;
        }
        if (type == wkbLineString || type == wkbLinearRing) {
            VectorFeature f{Kind::Line, {points(*g.toSimpleCurve())}, label};
            if (f.parts[0].size() < 2) return 0;
            if (onGrid(f.parts[0])) out.push_back(std::move(f));
            return 1;
        }
        if (type == wkbPolygon) {
            const auto& polygon = *g.toPolygon();
            if (polygon.IsEmpty()) return 0;
            VectorFeature f{Kind::Polygon, {}, label};
            f.parts.push_back(points(*polygon.getExteriorRing()));
            for (int k = 0; k < polygon.getNumInteriorRings(); ++k)
                f.parts.push_back(points(*polygon.getInteriorRing(k)));
            if (onGrid(f.parts[0])) out.push_back(std::move(f));
            return 1;
        }
        if (OGR_GT_IsSubClassOf(type, wkbGeometryCollection)) {  // multi-*, collections
            int seen = 0;
            for (const OGRGeometry* part : *g.toGeometryCollection())
                if (part) seen += collect(*part, label, out);
            return seen;
        }
        if (g.hasCurveGeometry()) {  // arcs and curved polygons, as line segments
            std::unique_ptr<OGRGeometry> linear(g.getLinearGeometry());
            return linear ? collect(*linear, label, out) : 0;
        }
        return 0;  // surfaces, TINs: nothing to draw
    }

  private:
    bool placed_ = false;
    double inverse_[6] = {0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
    int width_ = 0, height_ = 0;
};

struct TransformDeleter {
    void operator()(OGRCoordinateTransformation* t) const {
        OGRCoordinateTransformation::DestroyCT(t);
    }
};

// The layer's transformation into the grid's system, or null when none is needed.
std::unique_ptr<OGRCoordinateTransformation, TransformDeleter> toGrid(
    const std::string& path, OGRLayer& layer, const OGRSpatialReference* grid,
    VectorLayer& result) {
    const OGRSpatialReference* source = layer.GetSpatialRef();
    if (!grid) return nullptr;
    if (!source) {
        result.assumedGridSystem = true;
        return nullptr;
    }
    OGRSpatialReference from(*source);
    from.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    if (from.IsSame(grid)) return nullptr;
    std::unique_ptr<OGRCoordinateTransformation, TransformDeleter> t(
        OGRCreateCoordinateTransformation(&from, grid));
    if (!t)
        throw Error(msg(path, ": layer ", layer.GetName(), ": no transformation from its system (",
                        from.GetName() ? from.GetName() : "unnamed",
                        ") to the terrain's: ", CPLGetLastErrorMsg()));
    result.reprojected = true;
    return t;
}

}  // namespace

VectorLayer readVectorLayer(const std::string& path, const VectorReadOptions& options) {
    regularFileSize(path);  // missing files and devices are refused before GDAL opens them
    const detail::GdalSession session;
    detail::GdalDataset data(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
    if (!data) {
        const std::string reason = CPLGetLastErrorMsg();
        throw Error(msg("cannot open ", path, " as a vector layer: ",
                        reason.empty() ? "not a vector format GDAL recognises" : reason));
    }
    std::unique_ptr<OGRSpatialReference> grid;
    if (options.placement && !options.placement->crsWkt.empty()) {
        grid = std::make_unique<OGRSpatialReference>();
        if (grid->importFromWkt(options.placement->crsWkt.c_str()) != OGRERR_NONE)
            throw Error(msg(path, ": the terrain's reference system is not valid WKT"));
        grid->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    }
    const Converter converter(options);
    VectorLayer result;
    for (OGRLayer* layer : data->GetLayers()) {
        if (result.name.empty()) result.name = layer->GetName();
        if (layer->SetAttributeFilter(options.where.empty() ? nullptr : options.where.c_str()) !=
            OGRERR_NONE)
            throw Error(msg(path, ": the filter \"", options.where,
                            "\" is not valid OGR SQL for layer ", layer->GetName(), ": ",
                            CPLGetLastErrorMsg()));
        int labelField = -1;
        if (!options.labelField.empty()) {
            labelField = layer->GetLayerDefn()->GetFieldIndex(options.labelField.c_str());
            if (labelField < 0) {
                std::string fields;
                for (int k = 0; k < layer->GetLayerDefn()->GetFieldCount(); ++k)
                    fields += std::string(k ? ", " : "") +
                              layer->GetLayerDefn()->GetFieldDefn(k)->GetNameRef();
                throw Error(msg(path, ": layer ", layer->GetName(), " has no field \"",
                                options.labelField,
                                "\" (its fields: ", fields.empty() ? "none" : fields, ")"));
            }
        }
        const auto transform = toGrid(path, *layer, grid.get(), result);
        layer->ResetReading();
        for (auto& feature : *layer) {
            const OGRGeometry* geometry = feature->GetGeometryRef();
            if (!geometry) continue;
            ++result.read;
            std::unique_ptr<OGRGeometry> moved;
            if (transform) {
                moved.reset(geometry->clone());
                if (moved->transform(transform.get()) != OGRERR_NONE) {
                    ++result.outside;  // beyond the target system's domain
                    continue;
                }
                geometry = moved.get();
            }
            const std::string label =
                labelField >= 0 ? feature->GetFieldAsString(labelField) : std::string();
            const size_t before = result.features.size();
            converter.collect(*geometry, label, result.features);
            if (result.features.size() == before) ++result.outside;
        }
    }
    if (result.read == 0)
        throw Error(options.where.empty()
                        ? msg(path, ": the file has no features with a geometry")
                        : msg(path, ": no feature matches the filter \"", options.where, "\""));
    for (const VectorFeature& f : result.features)
        for (const auto& part : f.parts) result.vertices += int64_t(part.size());
    return result;
}

GridPoint geographicToSamples(const GridPlacement& placement, double longitude, double latitude) {
    if (placement.crsWkt.empty())
        throw Error(msg("a position at ", longitude, ", ", latitude,
                        " (longitude, latitude) needs a terrain with a reference system"));
    if (!(std::abs(latitude) <= 90.0 && std::isfinite(longitude)))
        throw Error(msg("latitude ", latitude, " is not within -90..90 degrees"));
    OGRSpatialReference wgs84, grid;
    wgs84.SetWellKnownGeogCS("WGS84");
    wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    if (grid.importFromWkt(placement.crsWkt.c_str()) != OGRERR_NONE)
        throw Error("the terrain's reference system is not valid WKT");
    grid.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    std::unique_ptr<OGRCoordinateTransformation, TransformDeleter> t(
        OGRCreateCoordinateTransformation(&wgs84, &grid));
    double x = longitude, y = latitude;
    if (!t || !t->Transform(1, &x, &y))
        throw Error(msg("longitude ", longitude, ", latitude ", latitude,
                        " has no place in the terrain's reference system"));
    VectorReadOptions options{.placement = placement};
    return Converter(options).sample(x, y);
}
#endif

}  // namespace sierra::terrain
