// libFuzzer target: vector layers (terrain::readVectorLayer, behind
// --vector) on arbitrary bytes, through GDAL's OGR drivers onto a
// georeferenced grid. Each input is written to one in-memory file
// (memfd_create) read back through /proc/self/fd. A sierra::Error is the
// expected answer to bad input; anything else is a finding, and so is a layer
// that breaks readVectorLayer's promises (parts non-empty, lines of two points
// or more, polygon rings closed, coordinates finite, every kept feature
// touching the grid, counts consistent).

#include "MemoryFile.h"

#include <sierra/core/Error.h>
#include <sierra/terrain/Vector.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static sierra::fuzz::MemoryFile file("fuzz.vector");
    file.fill(data, size);
    using sierra::terrain::VectorFeature;
    try {
        const auto layer = sierra::terrain::readVectorLayer(
            file.path, {.placement = sierra::terrain::GridPlacement{
                            {10.0, 0.01, 0.0, 47.0, 0.0, -0.01}, sierra::fuzz::kWgs84, 101, 51}});
        if (layer.outside > layer.read ||
            int64_t(layer.features.size()) < layer.read - layer.outside)
            __builtin_trap();
        int64_t vertices = 0;
        for (const VectorFeature& f : layer.features) {
            if (f.parts.empty()) __builtin_trap();
            for (const auto& part : f.parts) {
                if (part.empty()) __builtin_trap();
                if (f.kind == VectorFeature::Kind::Line && part.size() < 2) __builtin_trap();
                for (const auto& p : part)
                    if (!std::isfinite(p.i) || !std::isfinite(p.j)) __builtin_trap();
                vertices += int64_t(part.size());
            }
        }
        if (vertices != layer.vertices) __builtin_trap();
    } catch (const sierra::Error&) {
    }
    return 0;
}
