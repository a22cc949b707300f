#pragma once
// What the heightfield loaders share across their files: HeightfieldIO.cpp
// (the format dispatch, PNG, PGM, raw, SRTM and the writers) holds the common
// checks and byte readers; HeightfieldNpy.cpp the NumPy formats;
// HeightfieldGdal.cpp GeoTIFF through GDAL.

#include <sierra/terrain/Heightfield.h>
#include <sierra/terrain/HeightfieldIO.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

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

// .npy bytes as a grid (any numeric dtype, C or Fortran order).
Heightfield loadNpy(const std::string& path, const std::vector<uint8_t>& bytes,
                    const LoadOptions& options);
// An .npz DEM's spacing and orientation from its georeferencing members.
void applyNpzGeoreference(const std::string& path, const std::vector<uint8_t>& bytes,
                          Heightfield& field);
#ifdef SIERRA_WITH_GDAL
Heightfield loadGdal(const std::string& path, const LoadOptions& options);
#endif

}  // namespace sierra::terrain::detail
