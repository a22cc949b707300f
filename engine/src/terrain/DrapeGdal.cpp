// readDrape (terrain/Drape.h) through GDAL: the image is given the
// geotransform its placement says (a VRT copy, so the file is never
// changed), then warped into a memory raster laid over the grid's pixel
// corners, with an alpha band that is 0 where the image does not reach.
// Built with SIERRA_WITH_GDAL; without it, readDrape says so.
#include <sierra/terrain/Drape.h>

#include "terrain/GdalSession.h"

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>

#ifdef SIERRA_WITH_GDAL
#include <gdal_priv.h>
#include <gdal_utils.h>
#include <ogr_spatialref.h>
#endif

namespace sierra::terrain {

#ifndef SIERRA_WITH_GDAL
DrapeImage readDrape(const std::string& path, const DrapeOptions&) {
    throw Error(msg(path,
                    ": drapes need GDAL, and this build has none (rebuild with "
                    "libgdal-dev installed)"));
}
#else
namespace {

using Dataset = detail::GdalDataset;

using GeoTransform = std::array<double, 6>;

// Pixel corner (x, y) of a raster to its system's coordinates.
std::array<double, 2> apply(const GeoTransform& g, double x, double y) {
    return {g[0] + x * g[1] + y * g[2], g[3] + x * g[4] + y * g[5]};
}

// The grid the drape is laid over: its geotransform (identity: pixel corners
// in sample units when it has none), system and size.
struct Target {
    GeoTransform geo{0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
    std::string wkt;
    int width = 0, height = 0;
};

Target targetOf(const DrapeOptions& options) {
    Target t;
    if (options.placement) {
        t.geo = options.placement->geoTransform;
        t.wkt = options.placement->crsWkt;
        t.width = options.placement->width;
        t.height = options.placement->height;
    } else {
        t.width = options.width;
        t.height = options.height;
    }
    SIERRA_CHECK(t.width > 0 && t.height > 0, "a drape needs a grid, got ", t.width, "x", t.height);
    return t;
}

// The source's geotransform and system from the bounds, or null when its own
// georeference (or stretching) decides.
std::optional<GeoTransform> boundsTransform(const std::string& path, const DrapeBounds& b,
                                            const Target& target, int width, int height) {
    const bool finite = std::isfinite(b.left) && std::isfinite(b.right) && std::isfinite(b.top) &&
                        std::isfinite(b.bottom);
    if (!finite || b.left == b.right || b.top == b.bottom)
        throw Error(msg(path, ": drape bounds ", b.left, ", ", b.top, ", ", b.right, ", ", b.bottom,
                        " are empty or not finite"));
    double left = b.left, top = b.top, right = b.right, bottom = b.bottom;
    if (b.units == DrapeBounds::Units::Samples) {  // sample centres to the grid's pixel corners
        const auto a = apply(target.geo, left + 0.5, top + 0.5);
        const auto c = apply(target.geo, right + 0.5, bottom + 0.5);
        left = a[0], top = a[1], right = c[0], bottom = c[1];
    } else if (target.wkt.empty() && target.geo == GeoTransform{0.0, 1.0, 0.0, 0.0, 0.0, 1.0}) {
        throw Error(msg(path,
                        ": drape bounds in CRS units need a georeferenced terrain; give them "
                        "in samples"));
    }
    return GeoTransform{left, (right - left) / width, 0.0, top, 0.0, (bottom - top) / height};
}

// A VRT copy of `source` with the geotransform and system given.
Dataset withGeoreference(const std::string& path, GDALDataset& source, const GeoTransform& geo,
                         const std::string& wkt) {
    GDALDriver* vrt = GetGDALDriverManager()->GetDriverByName("VRT");
    if (!vrt) throw Error("GDAL has no VRT driver");
    Dataset copy(vrt->CreateCopy("", &source, FALSE, nullptr, nullptr, nullptr));
    if (!copy) throw Error(msg(path, ": GDAL cannot make a virtual copy: ", CPLGetLastErrorMsg()));
    GeoTransform g = geo;
    copy->SetGeoTransform(g.data());
    copy->SetProjection(wkt.c_str());
    return copy;
}

// The image's corners in the target's pixel space (pixel corners), through
// its system when it differs from the target's.
std::array<double, 4> footprint(const std::string& path, GDALDataset& source, const Target& target,
                                bool& reprojected) {
    GeoTransform g;
    source.GetGeoTransform(g.data());
    std::unique_ptr<OGRCoordinateTransformation> transform;
    const char* sourceWkt = source.GetProjectionRef();
    if (sourceWkt && *sourceWkt && !target.wkt.empty()) {
        OGRSpatialReference from, to;
        from.importFromWkt(sourceWkt);
        to.importFromWkt(target.wkt.c_str());
        from.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
        to.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
        if (!from.IsSame(&to)) {
            transform.reset(OGRCreateCoordinateTransformation(&from, &to));
            if (!transform)
                throw Error(msg(path,
                                ": no transformation from the image's system to the "
                                "terrain's: ",
                                CPLGetLastErrorMsg()));
            reprojected = true;
        }
    }
    double inverse[6];
    GeoTransform t = target.geo;
    if (!GDALInvGeoTransform(t.data(), inverse))
        throw Error("the terrain's geotransform cannot be inverted");
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    const int w = source.GetRasterXSize(), h = source.GetRasterYSize();
    // The edges at 16 points each: a reprojected footprint bends.
    for (int k = 0; k <= 64; ++k) {
        const double s = (k % 16) / 16.0;
        const int edge = std::min(k / 16, 3);
        const double px = edge == 0 ? s * w : edge == 1 ? w : edge == 2 ? (1.0 - s) * w : 0.0;
        const double py = edge == 0 ? 0.0 : edge == 1 ? s * h : edge == 2 ? h : (1.0 - s) * h;
        auto p = apply(g, px, py);
        if (transform && !transform->Transform(1, &p[0], &p[1])) continue;
        const double gx = inverse[0] + inverse[1] * p[0] + inverse[2] * p[1];
        const double gy = inverse[3] + inverse[4] * p[0] + inverse[5] * p[1];
        x0 = std::min(x0, gx), x1 = std::max(x1, gx);
        y0 = std::min(y0, gy), y1 = std::max(y1, gy);
    }
    if (!(x1 > x0 && y1 > y0))
        throw Error(msg(path, ": the image's corners do not map onto the terrain's system"));
    return {x0, y0, x1, y1};
}

// The warp's result: the image's resolution over the grid's extent, at most
// maxTexels a side.
std::array<int, 2> drapeSize(const std::array<double, 4>& fp, GDALDataset& source,
                             const Target& target, const DrapeOptions& options, DrapeImage& out) {
    const double density = std::max(source.GetRasterXSize() / (fp[2] - fp[0]),
                                    source.GetRasterYSize() / (fp[3] - fp[1]));
    double w = std::ceil(density * target.width - 1e-6),
           h = std::ceil(density * target.height - 1e-6);
    w = std::clamp(w, 1.0, 1e9), h = std::clamp(h, 1.0, 1e9);
    if (std::max(w, h) > options.maxTexels) {
        out.reducedFrom = {int(std::min(w, 2e9)), int(std::min(h, 2e9))};
        const double scale = options.maxTexels / std::max(w, h);
        w = std::max(1.0, std::floor(w * scale)), h = std::max(1.0, std::floor(h * scale));
    }
    return {int(w), int(h)};
}

void checkBands(const std::string& path, GDALDataset& source, int& colourBands, bool& alpha) {
    const int bands = source.GetRasterCount();
    if (bands < 1 || bands > 4)
        throw Error(msg(path, ": a drape is grey, grey + alpha, RGB or RGBA; this image has ",
                        bands, " bands"));
    colourBands = bands >= 3 ? 3 : 1;
    alpha = bands == 2 || bands == 4;
}

// Rows [row, row + rows) of the th-row result, warped into `rgba` (tw x rows,
// RGBA8): a memory raster whose bands are those bytes, R, G, B and alpha, or
// grey in R (copied to G and B after) and alpha.
void warpStrip(const std::string& path, GDALDriver& mem, GDALDataset& source, const Target& target,
               std::array<int, 2> size, int row, int rows, int colourBands, bool sourceAlpha,
               Resampling resampling, uint8_t* rgba) {
    const auto [tw, th] = size;
    Dataset warped(mem.Create("", tw, rows, 0, GDT_Byte, nullptr));
    if (!warped) throw Error(msg(path, ": GDAL cannot make a ", tw, "x", rows, " raster"));
    for (int b = 0; b <= colourBands; ++b) {
        const int offset = b == colourBands ? 3 : b;  // alpha last
        // CPLPrintPointer writes no terminating NUL: the buffer starts zeroed
        // and it writes at most one byte short of it.
        char pointer[64] = {};
        CPLPrintPointer(pointer, rgba + offset, sizeof pointer - 1);
        const std::string data = std::string("DATAPOINTER=") + pointer;
        const std::string line = "LINEOFFSET=" + std::to_string(int64_t(tw) * 4);
        const char* bandOptions[] = {data.c_str(), "PIXELOFFSET=4", line.c_str(), nullptr};
        if (warped->AddBand(GDT_Byte, const_cast<char**>(bandOptions)) != CE_None)
            throw Error(msg(path, ": GDAL cannot make the drape's bands: ", CPLGetLastErrorMsg()));
    }
    // The whole result's geotransform, its origin moved down `row` rows.
    const GeoTransform& g = target.geo;
    const double sx = double(target.width) / tw, sy = double(target.height) / th;
    GeoTransform dst{g[0] + g[2] * sy * row, g[1] * sx, g[2] * sy,
                     g[3] + g[5] * sy * row, g[4] * sx, g[5] * sy};
    warped->SetGeoTransform(dst.data());
    warped->SetProjection(target.wkt.c_str());
    std::vector<const char*> args{"-r", resampling == Resampling::Cubic ? "cubic" : "bilinear",
                                  "-dstalpha"};
    if (sourceAlpha) args.push_back("-srcalpha");
    args.push_back(nullptr);
    GDALWarpAppOptions* warpOptions =
        GDALWarpAppOptionsNew(const_cast<char**>(args.data()), nullptr);
    GDALDatasetH sources[] = {GDALDataset::ToHandle(&source)};
    int usageError = 0;
    GDALDatasetH result = GDALWarp(nullptr, GDALDataset::ToHandle(warped.get()), 1, sources,
                                   warpOptions, &usageError);
    GDALWarpAppOptionsFree(warpOptions);
    if (!result) throw Error(msg(path, ": GDAL cannot warp the drape: ", CPLGetLastErrorMsg()));
    warped->FlushCache();
    if (colourBands == 1)
        for (size_t k = 0; k < size_t(tw) * size_t(rows) * 4; k += 4)
            rgba[k + 1] = rgba[k + 2] = rgba[k];
}

}  // namespace

DrapeImage readDrapeStrips(const std::string& path, const DrapeOptions& options, size_t stripBytes,
                           const std::function<void(const DrapeImage&)>& onSize,
                           const std::function<void(const DrapeStrip&)>& onStrip) {
    regularFileSize(path);  // missing files and devices are refused before GDAL opens them
    const detail::GdalSession session;
    Dataset file(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
    if (!file) {
        const std::string reason = CPLGetLastErrorMsg();
        throw Error(msg("cannot read the drape ", path, ": ",
                        reason.empty() ? "not an image format GDAL recognises" : reason));
    }
    int colourBands = 0;
    bool sourceAlpha = false;
    checkBands(path, *file, colourBands, sourceAlpha);
    const Target target = targetOf(options);
    const int w = file->GetRasterXSize(), h = file->GetRasterYSize();
    DrapeImage out;

    // The source as it is placed: bounds, its own georeference, or stretched.
    GeoTransform own;
    const bool georeferenced = file->GetGeoTransform(own.data()) == CE_None;
    const char* ownWkt = file->GetProjectionRef();
    std::optional<GeoTransform> placed;
    std::string placedWkt = target.wkt;
    if (options.bounds) {
        placed = boundsTransform(path, *options.bounds, target, w, h);
    } else if (!georeferenced || !options.placement) {
        placed = GeoTransform{target.geo[0], target.geo[1] * target.width / w, 0.0, target.geo[3],
                              0.0,           target.geo[5] * target.height / h};
        out.stretched = true;
    } else if (!(ownWkt && *ownWkt) || target.wkt.empty()) {
        placed = own;  // no system on one side: the geotransforms alone place it
    } else {
        placedWkt = ownWkt;
    }
    Dataset placedCopy;
    GDALDataset* source = file.get();
    if (placed) {
        placedCopy = withGeoreference(path, *file, *placed, target.wkt.empty() ? "" : placedWkt);
        source = placedCopy.get();
    }
    const auto fp = footprint(path, *source, target, out.reprojected);
    const auto [tw, th] = drapeSize(fp, *source, target, options, out);

    out.width = tw;
    out.height = th;
    onSize(out);

    // GDAL's block cache holds what the warp reads of the source: capped while
    // it reads, so a large image is not cached whole beside the strips.
    const GIntBig cache = GDALGetCacheMax64();
    GDALSetCacheMax64(std::min<GIntBig>(cache, GIntBig(64) << 20));
    struct RestoreCache {
        GIntBig bytes;
        ~RestoreCache() { GDALSetCacheMax64(bytes); }
    } restoreCache{cache};
    GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
    if (!mem) throw Error("GDAL has no MEM driver");
    const int rows = int(std::clamp<size_t>(stripBytes / (size_t(tw) * 4), size_t(1), size_t(th)));
    std::vector<uint8_t> strip(size_t(tw) * size_t(rows) * 4);
    size_t reached = 0;
    for (int row = 0; row < th; row += rows) {
        const int n = std::min(rows, th - row);
        std::fill(strip.begin(), strip.end(), uint8_t(0));
        warpStrip(path, *mem, *source, target, {tw, th}, row, n, colourBands, sourceAlpha,
                  options.resampling, strip.data());
        for (size_t k = 3; k < size_t(tw) * size_t(n) * 4; k += 4) reached += strip[k] > 0;
        onStrip({row, n, tw, strip.data()});
    }
    out.coverage = double(reached) / (double(tw) * th);
    if (reached == 0) throw Error(msg(path, ": the drape lies wholly outside the terrain"));
    return out;
}

DrapeImage readDrape(const std::string& path, const DrapeOptions& options) {
    DrapeImage image;
    DrapeImage header = readDrapeStrips(
        path, options, SIZE_MAX,
        [&](const DrapeImage& size) {
            image.rgba.assign(size_t(size.width) * size_t(size.height) * 4, 0);
        },
        [&](const DrapeStrip& s) {
            std::copy(s.rgba, s.rgba + size_t(s.width) * size_t(s.rows) * 4,
                      image.rgba.begin() + ptrdiff_t(s.row) * s.width * 4);
        });
    header.rgba = std::move(image.rgba);
    return header;
}
#endif

}  // namespace sierra::terrain
