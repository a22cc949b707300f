// libFuzzer target: the OBJ reader behind sierra-render --mesh (tin::readObj)
// and the MTL reader beside it (tin::readMtlTextures), on arbitrary bytes.
// Both read a path, so each input is written to one in-memory file
// (memfd_create) and read back through /proc/self/fd: no disk traffic per run.
// A sierra::Error is the expected answer to bad input; anything else is a
// finding, and so is an ObjFile that breaks readObj's promises (every face
// index inside positions, every face UV -1 or inside uvs, one material per face).

#include "MemoryFile.h"

#include <sierra/core/Error.h>
#include <sierra/tin/Export.h>

#include <cstddef>
#include <cstdint>
#include <string>

namespace {

bool inside(int32_t index, size_t count) {
    return index >= 0 && size_t(index) < count;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static sierra::fuzz::MemoryFile file("fuzz.obj");
    file.fill(data, size);
    try {
        const sierra::tin::ObjFile obj = sierra::tin::readObj(file.path);
        if (obj.faceUvs.size() != obj.faces.size() || obj.faceMaterials.size() != obj.faces.size())
            __builtin_trap();
        for (size_t f = 0; f < obj.faces.size(); ++f)
            for (int k = 0; k < 3; ++k) {
                if (!inside(obj.faces[f][k], obj.positions.size())) __builtin_trap();
                const int32_t t = obj.faceUvs[f][k];
                if (t != -1 && !inside(t, obj.uvs.size())) __builtin_trap();
            }
    } catch (const sierra::Error&) {
    }
    try {
        sierra::tin::readMtlTextures(file.path);
    } catch (const sierra::Error&) {
    }
    return 0;
}
