// The GDAL window reader of GridReader.h: one raster, or several mosaicked by
// a VRT built in memory (gdalbuildvrt's rules: the first file's resolution and
// reference system, later files over earlier ones where they overlap). Built
// with SIERRA_WITH_GDAL; without it this file is empty.
#include "HeightfieldLoaders.h"

#ifdef SIERRA_WITH_GDAL
#include "terrain/GdalSession.h"

#include <sierra/core/Files.h>

#include <cmath>
#include <mutex>
#include <vector>

#include <gdal_priv.h>
#include <gdal_utils.h>

namespace sierra::terrain::detail {
namespace {

class GdalGridReader : public GridReader {
  public:
    GdalGridReader(std::string name, GdalDataset data)
        : name_(std::move(name)), data_(std::move(data)) {
        info_ = gdalGridInfo(name_, *data_);
        band_ = data_->GetRasterCount() > 0 ? data_->GetRasterBand(1) : nullptr;
        if (!band_) throw Error(msg(name_, ": the raster has no band"));
        info_.hasNoData = !(band_->GetMaskFlags() & GMF_ALL_VALID);
        const GDALDataType type = band_->GetRasterDataType();
        if (type == GDT_Byte || type == GDT_Int16) info_.int16Offset = 0.0;
        if (type == GDT_UInt16) info_.int16Offset = 32768.0;
    }

    void read(int64_t x0, int64_t y0, int w, int h, float* heights, uint8_t* valid) const override {
        // One dataset, so one reader at a time: GDAL's datasets are not
        // thread-safe. The build's threads overlap their other work with it.
        std::lock_guard lock(mutex_);
        const GdalSession session;
        if (band_->RasterIO(GF_Read, int(x0), int(y0), w, h, heights, w, h, GDT_Float32, 0, 0,
                            nullptr) != CE_None)
            throw Error(msg(name_, ": GDAL cannot read rows ", y0, "..", y0 + h - 1, ": ",
                            CPLGetLastErrorMsg()));
        const size_t count = size_t(w) * size_t(h);
        if (valid) {
            if (info_.hasNoData) {
                GDALRasterBand* mask = band_->GetMaskBand();
                if (!mask || mask->RasterIO(GF_Read, int(x0), int(y0), w, h, valid, w, h, GDT_Byte,
                                            0, 0, nullptr) != CE_None)
                    throw Error(
                        msg(name_, ": GDAL cannot read the no-data mask: ", CPLGetLastErrorMsg()));
                for (size_t k = 0; k < count; ++k) valid[k] = valid[k] != 0 ? 1 : 0;
            } else {
                std::fill(valid, valid + count, uint8_t(1));
            }
        }
        for (size_t k = 0; k < count; ++k)
            if (!std::isfinite(heights[k]) && (!valid || valid[k]))
                throw Error(msg(name_, ": sample (", x0 + int64_t(k % size_t(w)), ", ",
                                y0 + int64_t(k / size_t(w)), ") is ", heights[k],
                                " and not marked no-data; heights must be finite"));
    }

  private:
    std::string name_;
    GdalDataset data_;
    GDALRasterBand* band_ = nullptr;
    mutable std::mutex mutex_;
};

}  // namespace

std::unique_ptr<GridReader> openGdalGridReader(std::span<const std::string> paths) {
    for (const std::string& path : paths) regularFileSize(path);  // missing, FIFO: refused first
    const GdalSession session;
    if (paths.size() == 1) {
        GdalDataset data(GDALDataset::Open(paths[0].c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
        if (!data) {
            std::string reason = CPLGetLastErrorMsg();
            throw Error(msg("cannot open ", paths[0], " with GDAL: ",
                            reason.empty() ? "not a raster format GDAL recognises" : reason));
        }
        return std::make_unique<GdalGridReader>(paths[0], std::move(data));
    }
    std::vector<const char*> names;
    for (const std::string& path : paths) names.push_back(path.c_str());
    GDALBuildVRTOptions* options = GDALBuildVRTOptionsNew(nullptr, nullptr);
    int usageError = 0;
    GDALDatasetH vrt =
        GDALBuildVRT("", int(names.size()), nullptr, names.data(), options, &usageError);
    GDALBuildVRTOptionsFree(options);
    if (!vrt) {
        std::string reason = CPLGetLastErrorMsg();
        throw Error(msg("cannot mosaic ", paths.size(), " inputs (", paths[0], " ...) with GDAL: ",
                        reason.empty() ? "they do not form one raster" : reason));
    }
    GdalDataset data(GDALDataset::FromHandle(vrt));
    if (data->GetRasterXSize() <= 0 || data->GetRasterYSize() <= 0)
        throw Error(msg("the mosaic of ", paths.size(), " inputs (", paths[0], " ...) is empty"));
    return std::make_unique<GdalGridReader>(
        msg("the mosaic of ", paths.size(), " inputs (", paths[0], " ...)"), std::move(data));
}

}  // namespace sierra::terrain::detail
#endif
