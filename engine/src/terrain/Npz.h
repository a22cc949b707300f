#pragma once
// NumPy .npz archives (numpy.savez and savez_compressed): a zip file of .npy
// members, stored or deflated. Only what heightmaps need: find the member,
// inflate it into a buffer of its declared size, check its CRC.

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace sierra::terrain {

// The .npy bytes of the first member of `bytes` (an .npz read from `path`)
// that holds a 2-D array, or of the member named `member` (".npy" optional)
// when given. Throws sierra::Error naming the file for anything else: not a
// zip, zip64, encrypted or otherwise compressed members, a CRC mismatch, a
// member larger than `maxBytes`, or no 2-D array (the members are listed).
std::vector<uint8_t> npzMember(const std::string& path, const std::vector<uint8_t>& bytes,
                               const std::string& member = {},
                               uint64_t maxBytes = uint64_t(1) << 32);

// The archive's numbers and lists of numbers (0-d and 1-d arrays of a
// little-endian float or integer type, at most maxValues values), by member
// name without ".npy": the georeferencing some DEM archives carry beside
// their array (scalars dx, dy, xmin, xmax, ymin, ymax, or the latitude and
// longitude of every row and column). Members of any other shape or type
// are skipped; a corrupt archive throws as npzMember does.
std::map<std::string, std::vector<double>> npzNumbers(const std::string& path,
                                                      const std::vector<uint8_t>& bytes,
                                                      size_t maxValues);

}  // namespace sierra::terrain
