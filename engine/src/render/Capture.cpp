#include <sierra/render/Capture.h>

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

namespace sierra::render {

void writePng(const std::string& path, const gpu::Image& image, bool alpha) {
    SIERRA_CHECK(image.width > 0 && image.height > 0 &&
                     image.rgba.size() == size_t(image.width) * image.height * 4,
                 "cannot write ", path, ": the image is empty or inconsistent");
    namespace fs = std::filesystem;
    fs::path target(path);
    std::error_code ec;
    if (target.has_parent_path()) fs::create_directories(target.parent_path(), ec);
    if (ec)
        throw Error(
            msg("cannot create directory ", target.parent_path().string(), ": ", ec.message()));
    const int channels = alpha ? 4 : 3;
    std::vector<uint8_t> rgb(size_t(image.width) * image.height * size_t(channels));
    for (size_t p = 0, n = size_t(image.width) * image.height; p < n; ++p)
        for (int c = 0; c < channels; ++c)
            rgb[p * size_t(channels) + size_t(c)] = image.rgba[p * 4 + size_t(c)];
    std::vector<uint8_t> png;
    auto append = [](void* context, void* data, int size) {
        auto* out = static_cast<std::vector<uint8_t>*>(context);
        const auto* bytes = static_cast<const uint8_t*>(data);
        out->insert(out->end(), bytes, bytes + size);
    };
    if (!stbi_write_png_to_func(append, &png, image.width, image.height, channels, rgb.data(),
                                image.width * channels))
        throw Error(msg("cannot write ", path, ": PNG encoding failed"));
    writeFileAtomic(path, png);
}

gpu::Image readPng(const std::string& path) {
    int w = 0, h = 0, n = 0;
    stbi_uc* data = stbi_load(path.c_str(), &w, &h, &n, 4);
    if (!data) throw Error(msg("cannot read image ", path, ": ", stbi_failure_reason()));
    gpu::Image image{w, h, std::vector<uint8_t>(data, data + size_t(w) * h * 4)};
    stbi_image_free(data);
    return image;
}

std::string sequencePath(const std::string& base, int index) {
    std::filesystem::path p(base);
    char number[16];
    std::snprintf(number, sizeof number, "_%04d", index);
    std::string ext = p.has_extension() ? p.extension().string() : ".png";
    return (p.parent_path() / (p.stem().string() + number + ext)).string();
}

ImageDifference compareImages(const gpu::Image& a, const gpu::Image& b, int threshold) {
    SIERRA_CHECK(a.width == b.width && a.height == b.height, "image sizes differ: ", a.width, "x",
                 a.height, " against ", b.width, "x", b.height);
    size_t pixels = size_t(a.width) * a.height;
    double squared = 0.0, absolute = 0.0;
    size_t differing = 0;
    for (size_t p = 0; p < pixels; ++p) {
        int worst = 0;
        for (int c = 0; c < 3; ++c) {
            int d = int(a.rgba[p * 4 + c]) - int(b.rgba[p * 4 + c]);
            squared += double(d) * d;
            absolute += std::abs(d);
            worst = std::max(worst, std::abs(d));
        }
        if (worst > threshold) ++differing;
    }
    ImageDifference result;
    double mse = squared / double(pixels * 3);
    result.psnr = mse == 0.0 ? std::numeric_limits<double>::infinity()
                             : 10.0 * std::log10(255.0 * 255.0 / mse);
    result.differingShare = double(differing) / double(pixels);
    result.meanAbsolute = absolute / double(pixels * 3);
    return result;
}

}  // namespace sierra::render
