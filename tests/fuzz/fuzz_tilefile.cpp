// libFuzzer target: the tiled SBT file reader (sbt::TileFile, what
// sierra-render and sierra-tile info open) on arbitrary bytes: the header,
// index and coarse section at open, then every stored tile read whole and in
// part, and the records FileTiles hands the refiner. A sierra::Error is the
// expected answer to bad input; anything else is a finding, and so is a
// record that is not finite or a negative error or radius.

#include "MemoryFile.h"

#include <sierra/core/Error.h>
#include <sierra/sbt/TileFile.h>

#include <cmath>
#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static sierra::fuzz::MemoryFile file("fuzz.sierra");
    file.fill(data, size);
    try {
        const sierra::sbt::TileFile tiles(file.path);
        const int P = tiles.info().tilesPerSide();
        if (P > 64) return 0;  // a valid header of a huge grid: reading it all is no finding
        sierra::sbt::FileTiles vertices(tiles);
        for (int ty = 0; ty < P; ++ty)
            for (int tx = 0; tx < P; ++tx) {
                if (!tiles.stored(tx, ty)) continue;
                sierra::sbt::TileData part;
                tiles.readTile(tx, ty, 1, part);
                vertices.load(tx, ty, 2 * tiles.info().k);
            }
        const int64_t side = tiles.info().gridSide();
        for (int64_t j = 0; j < side; j += 3)
            for (int64_t i = 0; i < side; i += 3) {
                const sierra::sbt::VertexRecord r = vertices.vertex(uint32_t(i), uint32_t(j));
                if (!std::isfinite(r.height) || !(r.error >= 0.0f) || !(r.radius >= 0.0f))
                    __builtin_trap();
            }
    } catch (const sierra::Error&) {
    }
    return 0;
}
