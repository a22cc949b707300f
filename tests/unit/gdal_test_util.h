#pragma once
// GDAL helpers the unit tests of georeferenced inputs share (built with
// SIERRA_WITH_GDAL).
#include <ogr_spatialref.h>

#include <gtest/gtest.h>

#include <string>

namespace sierra::test {

// The WKT of an EPSG reference system (4326: WGS 84; 32633: UTM zone 33 N).
inline std::string wktOf(int epsg) {
    OGRSpatialReference srs;
    EXPECT_EQ(srs.importFromEPSG(epsg), OGRERR_NONE);
    char* text = nullptr;
    srs.exportToWkt(&text);
    std::string wkt = text;
    CPLFree(text);
    return wkt;
}

}  // namespace sierra::test
