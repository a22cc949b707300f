#pragma once
// What every reader through GDAL (GeoTIFF heightmaps, drapes, vector layers)
// does around its calls: GDAL's drivers registered, its own error printing
// silenced so the user gets one message (its last error goes into the
// sierra::Error), and datasets closed however the reader leaves. Built with
// SIERRA_WITH_GDAL only.
#ifdef SIERRA_WITH_GDAL
#include <gdal_priv.h>

#include <memory>

namespace sierra::terrain::detail {

// For the scope of one read: drivers registered, errors quiet, the last one cleared.
class GdalSession {
  public:
    GdalSession() {
        GDALAllRegister();
        CPLPushErrorHandler(CPLQuietErrorHandler);
        CPLErrorReset();
    }
    ~GdalSession() { CPLPopErrorHandler(); }
    GdalSession(const GdalSession&) = delete;
    GdalSession& operator=(const GdalSession&) = delete;
};

struct GdalCloser {
    void operator()(GDALDataset* d) const { GDALClose(GDALDataset::ToHandle(d)); }
};
using GdalDataset = std::unique_ptr<GDALDataset, GdalCloser>;

}  // namespace sierra::terrain::detail
#endif
