#pragma once
// What the heightfield loaders share across their files: HeightfieldIO.cpp
// (the format dispatch, PNG, PGM, raw, SRTM and the writers) holds the common
// checks and byte readers; HeightfieldNpy.cpp the NumPy formats;
// HeightfieldGdal.cpp GeoTIFF through GDAL.

#include <sierra/terrain/GridReader.h>
#include <sierra/terrain/Heightfield.h>
#include <sierra/terrain/HeightfieldIO.h>

#include <cstdint>
#include <initializer_list>
#include <span>
#include <string>
#include <utility>
#include <vector>

#ifdef SIERRA_WITH_GDAL
class GDALDataset;
#endif

namespace sierra::terrain::detail {

// Rejects a width x height field of `what` in `path` before anything is
// allocated for it (checkFieldSize with the options' limit).
void checkSize(const std::string& path, int64_t width, int64_t height, const char* what,
               const LoadOptions& options);
// Float input must be finite; a no-data value belongs in .hgt or a mask, not NaN.
void checkFinite(const std::string& path, const Heightfield& field);
// Little-endian integers at p.
uint16_t le16(const uint8_t* p);
uint32_t le32(const uint8_t* p);
uint64_t le64(const uint8_t* p);
// Metres east and north of a step of `east` x `north` radians at `latitude`
// radians on an ellipsoid of semi-major axis `a` metres and flattening `f`.
std::pair<double, double> ellipsoidSpacing(double east, double north, double latitude, double a,
                                           double f);
// Metres east and north of a step of `east` x `north` degrees at `latitude` on WGS 84.
std::pair<double, double> degreesToMetres(double east, double north, double latitude);

// A .npy header, checked: its dtype, its shape and where its data starts.
struct NpyHeader {
    std::string descr;            // '<f4' ...
    int valueBytes = 0;           // bytes per value of descr
    std::vector<uint64_t> shape;  // each extent at most 2^40
    std::string dims;             // the shape tuple's text, for messages
    uint64_t dataStart = 0;
};
// Parses and checks a .npy header (magic, version, C order, a shape tuple)
// at the start of `bytes` (the whole file or a map of it). `supported` lists
// the dtypes taken, as the message names them. Throws sierra::Error naming
// `path` for anything else.
NpyHeader parseNpyHeader(const std::string& path, std::span<const uint8_t> bytes,
                         std::initializer_list<const char*> supported);
// Value k of data in a numeric little-endian dtype `descr` ('<f4', '<i2', '|u1' ...).
double npyNumber(const std::string& descr, const uint8_t* data, size_t k);

// .npy bytes as a grid (any numeric dtype, C or Fortran order).
Heightfield loadNpy(const std::string& path, const std::vector<uint8_t>& bytes,
                    const LoadOptions& options);
// An .npz DEM's spacing and orientation from its georeferencing members.
void applyNpzGeoreference(const std::string& path, const std::vector<uint8_t>& bytes,
                          Heightfield& field);
#ifdef SIERRA_WITH_GDAL
// A GDAL raster's spacing (metres for a projected or geographic system, on
// the ellipsoid at the central latitude), its centre and georeference.
GridInfo gdalGridInfo(const std::string& path, GDALDataset& data);
Heightfield loadGdal(const std::string& path, const LoadOptions& options);
#endif

}  // namespace sierra::terrain::detail
