#pragma once
// Reading and writing heightfields. The format is chosen by file extension
// (case-insensitive):
//   .png  8- or 16-bit grey (or the first channel of grey+alpha/RGB/RGBA);
//         heights are the stored integers, 0..255 or 0..65535
//   .pgm  P2 (ASCII) or P5 (binary), 8 or 16 bit (16-bit P5 is big-endian);
//         heights are the stored integers, each at most the header's maxval
//   .r16 / .r32  raw little-endian uint16 / float32, size from LoadOptions
//   .hgt  SRTM: big-endian int16 metres, 1201 or 3601 wide, -32768 = no data
//         (mask 0, stored height filled from the nearest valid samples);
//         spacing set to the nominal 90 m (1201) or 30 m (3601)
//   .npy  NumPy <f4, <f8, <i2, <u2 or |u1, 2-D (rows = height, columns =
//         width), C order, format version 1.0 or 2.0
//   .npz  NumPy archive (numpy.savez, stored or deflated): the first member
//         holding a 2-D array, read as .npy
//   .tif / .tiff  GeoTIFF band 1, only when built with SIERRA_WITH_GDAL
// File row 0 is row j = 0. Float input must be finite (NaN/Inf rejected).
// Every loader throws sierra::Error with one line naming the file, what is
// wrong and what would be right; none crashes on bad input.

#include <sierra/terrain/Heightfield.h>

#include <string>

namespace sierra::terrain {

struct LoadOptions {
    // Size of a raw .r16/.r32 file in samples (required for raw files; 0 = guess a
    // square from the file size). Give both or neither.
    int rawWidth = 0;
    int rawHeight = 0;
};

Heightfield loadHeightfield(const std::string& path, const LoadOptions& options = {});

// Writes .png (16-bit grey, heights mapped linearly from range() to 0..65535;
// a flat field writes 0 everywhere; nothing else is recorded: spacing,
// vertical scale and mask are lost) or .npy (float32, exact; masked samples
// keep their stored fill value). Writes to a temporary name, then renames: a
// failed write never leaves a half file.
void saveHeightfield(const std::string& path, const Heightfield& field);

}  // namespace sierra::terrain
