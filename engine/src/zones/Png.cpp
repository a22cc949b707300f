#include "Png.h"

#include <sierra/core/Error.h>

#include <stb/stb_image_write.h>

namespace sierra::zones::detail {

std::vector<uint8_t> encodePng8(int width, int height, int channels, const uint8_t* pixels) {
    std::vector<uint8_t> out;
    auto append = [](void* context, void* data, int size) {
        auto* bytes = static_cast<std::vector<uint8_t>*>(context);
        const auto* p = static_cast<const uint8_t*>(data);
        bytes->insert(bytes->end(), p, p + size);
    };
    int ok =
        stbi_write_png_to_func(append, &out, width, height, channels, pixels, width * channels);
    if (!ok) throw Error(msg("PNG encoding of a ", width, "x", height, " image failed"));
    return out;
}

}  // namespace sierra::zones::detail
