// libFuzzer target: imagery drapes (terrain::readDrape, behind --drape) on
// arbitrary bytes, through GDAL's raster drivers onto a georeferenced grid,
// as one in-memory file (memfd_create) read back through /proc/self/fd. A
// sierra::Error is the expected answer to bad input; anything else is a
// finding, and so is a drape that breaks readDrape's promises (a size within
// the texture limit, width * height * 4 bytes, coverage in (0, 1]).

#include "MemoryFile.h"

#include <sierra/core/Error.h>
#include <sierra/terrain/Drape.h>

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static sierra::fuzz::MemoryFile file("fuzz.drape");
    file.fill(data, size);
    try {
        // A small texture limit keeps a huge declared image cheap to place.
        const auto drape = sierra::terrain::readDrape(
            file.path, {.placement =
                            sierra::terrain::GridPlacement{
                                {10.0, 0.01, 0.0, 47.0, 0.0, -0.01}, sierra::fuzz::kWgs84, 64, 32},
                        .maxTexels = 256});
        if (drape.width < 1 || drape.height < 1 || drape.width > 256 || drape.height > 256 ||
            drape.rgba.size() != size_t(drape.width) * size_t(drape.height) * 4 ||
            !(drape.coverage > 0.0 && drape.coverage <= 1.0))
            __builtin_trap();
    } catch (const sierra::Error&) {
    }
    return 0;
}
