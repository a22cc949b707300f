#pragma once
// Reading and writing heightfields. The format is chosen by file extension
// (case-insensitive):
//   .png  8- or 16-bit grey or grey+alpha (alpha ignored); heights are the
//         stored integers, 0..255 or 0..65535 (1/2/4-bit grey scaled to 0..255).
//         Decoded by libspng with every CRC checked. Colour (RGB, RGBA,
//         palette) is refused unless LoadOptions::channel picks one.
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
//   .tif / .tiff  GeoTIFF band 1, when built with SIERRA_WITH_GDAL (the default
//         when GDAL is installed); no data from the band's mask (its no-data
//         value, NaN included, or an internal mask), filled like .hgt; spacing
//         in metres: a projected system's pixel size, or for a geographic one
//         (degrees) the pixel size at the latitude of the tile's centre on its
//         ellipsoid (east-west shrinks with the cosine of the latitude)
// File row 0 is row j = 0. Float input must be finite (NaN/Inf rejected).
// Every loader throws sierra::Error with one line naming the file, what is
// wrong and what would be right; none crashes on bad input.
//
// Limits, all checked before anything is allocated for the samples:
//   - only regular files are read (a FIFO or a link to /dev/zero is refused),
//     and no more bytes than the format can hold for the largest allowed grid;
//   - each side 2..65537 samples (kMinSide, kMaxSide): a 1x1 or 1xN image is
//     not a surface;
//   - the grid the renderer pads the field to, paddedSide(max(width, height))
//     squared, at most LoadOptions::maxPaddedSide squared samples (default
//     16385^2 = 268 M samples, 1 GiB of float32: also the largest texture side
//     most GL drivers allow). A 16386x2 file would pad to 32769^2 samples
//     (4 GiB) and is refused in milliseconds with a message naming the limit.

#include <sierra/terrain/Heightfield.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace sierra::terrain {

// Sides a loader accepts, in samples: 2 (a surface needs two samples each
// way) to 65537 = 2^16 + 1 (the largest grid the SBT addresses).
constexpr int kMinSide = 2;
constexpr int kMaxSide = 65537;
// Default LoadOptions::maxPaddedSide: 16385 = 2^14 + 1, the largest side most
// GL drivers allow for a texture (GL_MAX_TEXTURE_SIZE 16384, plus the SBT's +1).
constexpr int kDefaultMaxPaddedSide = 16385;

struct LoadOptions {
    // Size of a raw .r16/.r32 file in samples (required for raw files; 0 = guess a
    // square from the file size). Give both or neither.
    int rawWidth = 0;
    int rawHeight = 0;
    // Which value of a colour PNG is the height: "" (default) refuses colour, the
    // heightmap must be grey; "luminance" = 0.2126 R + 0.7152 G + 0.0722 B
    // (Rec. 709 weights on the stored values, no gamma); "r", "g" or "b" one
    // channel. Grey PNGs ignore it.
    std::string channel;
    // Largest side of the (2^n+1)^2 grid a field is padded to, in samples
    // (default 16385: at most 16385^2 samples, 1 GiB as float32). Must be 3..65537.
    int maxPaddedSide = kDefaultMaxPaddedSide;
};

// Throws sierra::Error "WHAT: SIZE ..." naming the limit hit when a width x
// height field is outside kMinSide..kMaxSide per side, or when its padded grid
// would exceed maxPaddedSide^2 samples. Every loader calls it before allocating.
void checkFieldSize(const std::string& what, int64_t width, int64_t height,
                    int maxPaddedSide = kDefaultMaxPaddedSide);

Heightfield loadHeightfield(const std::string& path, const LoadOptions& options = {});

// The same decoders on bytes already in memory; `name` picks the format by its
// extension and names the data in messages. Every format but GeoTIFF; the same
// limits (a raw size, when given, must match bytes.size() exactly).
Heightfield decodeHeightfield(const std::string& name, const std::vector<uint8_t>& bytes,
                              const LoadOptions& options = {});

// Writes .png (16-bit grey, heights mapped linearly from range() to 0..65535;
// a flat field writes 0 everywhere; nothing else is recorded: spacing,
// vertical scale and mask are lost) or .npy (float32, exact; masked samples
// keep their stored fill value). Writes to a temporary name, then renames: a
// failed write never leaves a half file.
void saveHeightfield(const std::string& path, const Heightfield& field);

}  // namespace sierra::terrain
