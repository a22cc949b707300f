// The GeoTIFF loader of loadHeightfield (HeightfieldIO.cpp), through GDAL:
// band 1 and its no-data mask, the ground spacing in metres of a projected or
// geographic reference system, and the grid's geographic centre. Built with
// SIERRA_WITH_GDAL; without it this file is empty.
#include "HeightfieldLoaders.h"

#include "terrain/GdalSession.h"
#include "terrain/Npz.h"

#include <sierra/core/Files.h>
#include <sierra/terrain/FileIO.h>
#include <sierra/terrain/Padding.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstring>
#include <map>
#include <optional>
#include <string_view>

#ifdef SIERRA_WITH_GDAL
#include <gdal_priv.h>
#include <ogr_spatialref.h>
#endif

namespace sierra::terrain::detail {

// ---------------------------------------------------------------------------- GeoTIFF

#ifdef SIERRA_WITH_GDAL
// Ground spacing in metres of one pixel step of a geographic raster, on the
// system's ellipsoid, at the latitude of the tile's centre.
std::pair<double, double> geographicSpacing(const OGRSpatialReference& srs, const double geo[6],
                                            int height) {
    const double radiansPerUnit = srs.GetAngularUnits(nullptr);  // degrees: pi / 180
    const double inverseFlattening = srs.GetInvFlattening(nullptr);
    return ellipsoidSpacing(std::abs(geo[1]) * radiansPerUnit, std::abs(geo[5]) * radiansPerUnit,
                            (geo[3] + geo[5] * height * 0.5) * radiansPerUnit,
                            srs.GetSemiMajor(nullptr),
                            inverseFlattening > 0.0 ? 1.0 / inverseFlattening : 0.0);
}

// The raster's centre in WGS 84 degrees: a geographic system's own
// coordinates (x longitude, y latitude, as GeoTIFF stores them), a projected
// one's transformed; nothing when the transformation is not available.
std::optional<Heightfield::GeoPoint> geographicCentre(const OGRSpatialReference& srs,
                                                      const double geo[6], int width, int height) {
    double x = geo[0] + geo[1] * 0.5 * width + geo[2] * 0.5 * height;
    double y = geo[3] + geo[4] * 0.5 * width + geo[5] * 0.5 * height;
    OGRSpatialReference wgs84;
    if (wgs84.importFromEPSG(4326) != OGRERR_NONE) return std::nullopt;
    wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);  // x longitude, y latitude
    OGRSpatialReference source(srs);
    source.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    std::unique_ptr<OGRCoordinateTransformation> transform(
        OGRCreateCoordinateTransformation(&source, &wgs84));
    if (!transform || !transform->Transform(1, &x, &y) || !std::isfinite(x) || !std::isfinite(y) ||
        std::abs(y) > 90.0 || x < -180.0 || x > 360.0)
        return std::nullopt;
    return Heightfield::GeoPoint{y, x};
}

GridInfo gdalGridInfo(const std::string& path, GDALDataset& data) {
    GridInfo info;
    info.width = data.GetRasterXSize();
    info.height = data.GetRasterYSize();
    const int height = int(std::min<int64_t>(info.height, INT_MAX));
    const int width = int(std::min<int64_t>(info.width, INT_MAX));
    // Ground spacing in metres: a projected system gives it directly (in its
    // linear unit, converted to metres); a geographic one in degrees is
    // converted at the grid's central latitude. Without a system, 1 (grid units).
    double geo[6];
    const OGRSpatialReference* srs = data.GetSpatialRef();
    if (data.GetGeoTransform(geo) == CE_None && srs) {
        if (srs->IsProjected()) {
            const double metres = srs->GetLinearUnits(nullptr);
            info.spacingX = float(std::abs(geo[1]) * metres);
            info.spacingZ = float(std::abs(geo[5]) * metres);
            info.metres = true;
        } else if (srs->IsGeographic()) {
            const auto [dx, dz] = geographicSpacing(*srs, geo, height);
            if (!(dx > 0.0 && dz > 0.0 && std::isfinite(dx) && std::isfinite(dz)))
                throw Error(msg(path, ": pixel size ", geo[1], " x ", geo[5],
                                " degrees gives no usable ground spacing"));
            info.spacingX = float(dx);
            info.spacingZ = float(dz);
            info.metres = true;
        }
        info.geoCentre = geographicCentre(*srs, geo, width, height);
    }
    if (data.GetGeoTransform(geo) == CE_None) {
        Heightfield::Georeference ref;
        std::copy(geo, geo + 6, ref.geoTransform.begin());
        if (srs) {
            char* wkt = nullptr;
            if (srs->exportToWkt(&wkt) == OGRERR_NONE && wkt) ref.crsWkt = wkt;
            CPLFree(wkt);
        }
        info.georeference = std::move(ref);
    }
    return info;
}

Heightfield loadGdal(const std::string& path, const LoadOptions& options) {
    regularFileSize(path);      // a FIFO or a device is refused before GDAL opens it
    const GdalSession session;  // one message: GDAL's last error goes into the sierra::Error
    GdalDataset data(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
    if (!data) {
        std::string reason = CPLGetLastErrorMsg();
        throw Error(msg("cannot open ", path, " with GDAL: ",
                        reason.empty() ? "not a raster format GDAL recognises" : reason));
    }
    const int width = data->GetRasterXSize(), height = data->GetRasterYSize();
    checkSize(path, width, height, "GeoTIFF", options);
    GDALRasterBand* band = data->GetRasterCount() > 0 ? data->GetRasterBand(1) : nullptr;
    if (!band) throw Error(msg(path, ": GeoTIFF has no raster band"));
    Heightfield field(width, height);
    if (band->RasterIO(GF_Read, 0, 0, width, height, field.samples().data(), width, height,
                       GDT_Float32, 0, 0, nullptr) != CE_None)
        throw Error(msg(path, ": GDAL cannot read band 1: ", CPLGetLastErrorMsg()));
    // No data from the band's mask: its no-data value (NaN included), or an
    // internal mask or alpha band when the file has one.
    if (!(band->GetMaskFlags() & GMF_ALL_VALID)) {
        std::vector<uint8_t> mask(field.samples().size(), 1);
        GDALRasterBand* maskBand = band->GetMaskBand();
        if (!maskBand || maskBand->RasterIO(GF_Read, 0, 0, width, height, mask.data(), width,
                                            height, GDT_Byte, 0, 0, nullptr) != CE_None)
            throw Error(
                msg(path, ": GDAL cannot read the no-data mask of band 1: ", CPLGetLastErrorMsg()));
        bool any = false;
        for (size_t k = 0; k < mask.size(); ++k) {
            mask[k] = mask[k] != 0 ? 1 : 0;
            if (!mask[k]) {
                field.samples()[k] = 0.0f;
                any = true;
            }
        }
        if (any) {
            field.setMask(std::move(mask));
            fillNoData(field);
        }
    }
    checkFinite(path, field);
    const GridInfo geo = gdalGridInfo(path, *data);
    field.setSpacing(geo.spacingX, geo.spacingZ);
    field.setMetres(geo.metres);
    field.setGeoCentre(geo.geoCentre);
    field.setGeoreference(geo.georeference);
    return field;
}
#endif
}  // namespace sierra::terrain::detail
