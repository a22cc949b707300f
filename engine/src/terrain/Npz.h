#pragma once
// NumPy .npz archives (numpy.savez and savez_compressed): a zip file of .npy
// members, stored or deflated. Only what heightmaps need: find the member,
// inflate it into a buffer of its declared size, check its CRC.

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

// The .npy bytes of the archive's members of at most maxBytes, by name
// without ".npy": small arrays beside the heights, such as the
// georeferencing some DEM archives carry (scalars dx, dy, xmin, xmax, ymin,
// ymax, or the latitude and longitude of every row and column). A corrupt
// archive throws as npzMember does.
std::map<std::string, std::vector<uint8_t>> npzSmallMembers(const std::string& path,
                                                            const std::vector<uint8_t>& bytes,
                                                            uint64_t maxBytes);

}  // namespace sierra::terrain
