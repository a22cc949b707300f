#include <sierra/render/Capture.h>

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>

#include <jpeglib.h>
#include <spng.h>
#include <stb/stb_image.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>

namespace sierra::render {

namespace {

void checkImage(const gpu::Image& image, const char* what) {
    SIERRA_CHECK(image.width > 0 && image.height > 0 &&
                     image.rgba.size() == size_t(image.width) * image.height * 4,
                 "cannot encode ", what, ": the image is empty or inconsistent (", image.width, "x",
                 image.height, ", ", image.rgba.size(), " bytes)");
}

struct SpngFree {
    void operator()(spng_ctx* ctx) const { spng_ctx_free(ctx); }
};

// zlib level, strategy and the filters libspng may pick from for each row.
// Fast: the Sub filter alone (the pixel to the left subtracted: one
// subtraction per byte instead of five trial filters and their sums) and
// zlib's run-length matches at level 1: on a 1080p frame of the default
// orbit about 7x quicker than stb's writer with files a third smaller, and
// faster and smaller than level 1's string matching with the Up, Paeth or
// per-row filter (apps/sierra-microbench/capture_bench.cpp). Default and
// best: zlib's levels 6 and 9 with the filter chosen per row.
void setCompression(spng_ctx* ctx, PngCompression compression) {
    int level = 1, filters = SPNG_FILTER_CHOICE_SUB, strategy = Z_RLE;
    if (compression != PngCompression::Fast) {
        level = compression == PngCompression::Best ? 9 : 6;
        filters = SPNG_FILTER_CHOICE_ALL;
        strategy = Z_FILTERED;
    }
    spng_set_option(ctx, SPNG_IMG_COMPRESSION_LEVEL, level);
    spng_set_option(ctx, SPNG_IMG_COMPRESSION_STRATEGY, strategy);
    spng_set_option(ctx, SPNG_FILTER_CHOICE, filters);
}

// Encodes `height` rows of `rowBytes` each; row(y, buffer) fills row y (top
// first) in the PNG's own layout (16-bit samples in host order: libspng
// swaps them).
template <typename Row>
std::vector<uint8_t> encodeSpng(int width, int height, uint8_t colourType, uint8_t bitDepth,
                                size_t rowBytes, PngCompression compression, const Row& row) {
    std::unique_ptr<spng_ctx, SpngFree> ctx(spng_ctx_new(SPNG_CTX_ENCODER));
    if (!ctx) throw Error("cannot encode PNG: out of memory");
    auto check = [](int err, const char* step) {
        if (err != 0 && err != SPNG_EOI)
            throw Error(msg("cannot encode PNG: ", step, " (libspng: ", spng_strerror(err), ")"));
    };
    check(spng_set_option(ctx.get(), SPNG_ENCODE_TO_BUFFER, 1), "no memory output");
    spng_ihdr ihdr{};
    ihdr.width = uint32_t(width);
    ihdr.height = uint32_t(height);
    ihdr.bit_depth = bitDepth;
    ihdr.color_type = colourType;
    check(spng_set_ihdr(ctx.get(), &ihdr), "bad header");
    setCompression(ctx.get(), compression);
    check(spng_encode_image(ctx.get(), nullptr, 0, SPNG_FMT_PNG,
                            SPNG_ENCODE_PROGRESSIVE | SPNG_ENCODE_FINALIZE),
          "cannot start");
    std::vector<uint8_t> buffer(rowBytes);
    for (int y = 0; y < height; ++y) {
        row(y, buffer.data());
        check(spng_encode_row(ctx.get(), buffer.data(), rowBytes), "row");
    }
    size_t size = 0;
    int err = 0;
    void* png = spng_get_png_buffer(ctx.get(), &size, &err);
    check(err, "no output");
    if (!png) throw Error("cannot encode PNG: no output");
    std::vector<uint8_t> bytes(static_cast<uint8_t*>(png), static_cast<uint8_t*>(png) + size);
    std::free(png);
    return bytes;
}

// libjpeg reports errors through error_exit, which must not return: it jumps
// back to the encoding function with the message kept (the library is C, so
// no exception may cross it).
struct JpegError {
    jpeg_error_mgr manager;
    std::jmp_buf jump;
    char message[JMSG_LENGTH_MAX];
};

void jpegErrorExit(j_common_ptr info) {
    auto* error = reinterpret_cast<JpegError*>(info->err);
    (*info->err->format_message)(info, error->message);
    std::longjmp(error->jump, 1);
}

// The JPEG of `image` into *out (malloc'd by libjpeg, *outSize bytes); false
// with error->message set on failure. No C++ object lives in this frame, so
// the longjmp skips no destructor.
bool jpegEncode(const gpu::Image& image, int quality, JpegError* error, unsigned char** out,
                unsigned long* outSize) {
    jpeg_compress_struct info{};
    info.err = jpeg_std_error(&error->manager);
    error->manager.error_exit = jpegErrorExit;
    if (setjmp(error->jump)) {
        jpeg_destroy_compress(&info);
        return false;
    }
    jpeg_create_compress(&info);
    jpeg_mem_dest(&info, out, outSize);
    info.image_width = JDIMENSION(image.width);
    info.image_height = JDIMENSION(image.height);
    info.input_components = 4;
    info.in_color_space = JCS_EXT_RGBX;  // libjpeg-turbo: RGBA rows as they are, alpha skipped
    jpeg_set_defaults(&info);
    jpeg_set_quality(&info, quality, TRUE);
    jpeg_start_compress(&info, TRUE);
    const size_t stride = size_t(image.width) * 4;
    while (info.next_scanline < info.image_height) {
        JSAMPROW row = const_cast<JSAMPROW>(image.rgba.data() + info.next_scanline * stride);
        jpeg_write_scanlines(&info, &row, 1);
    }
    jpeg_finish_compress(&info);
    jpeg_destroy_compress(&info);
    return true;
}

bool isJpegName(const std::string& path) {
    const std::string ext = lowerExtension(path);
    return ext == ".jpg" || ext == ".jpeg";
}

}  // namespace

std::vector<uint8_t> encodePng(const gpu::Image& image, bool alpha, PngCompression compression) {
    checkImage(image, "PNG");
    const size_t pixels = size_t(image.width);
    const uint8_t* rgba = image.rgba.data();
    if (alpha)
        return encodeSpng(image.width, image.height, SPNG_COLOR_TYPE_TRUECOLOR_ALPHA, 8, pixels * 4,
                          compression, [&](int y, uint8_t* row) {
                              std::memcpy(row, rgba + size_t(y) * pixels * 4, pixels * 4);
                          });
    return encodeSpng(image.width, image.height, SPNG_COLOR_TYPE_TRUECOLOR, 8, pixels * 3,
                      compression, [&](int y, uint8_t* row) {
                          const uint8_t* from = rgba + size_t(y) * pixels * 4;
                          for (size_t x = 0; x < pixels; ++x) {
                              row[3 * x] = from[4 * x];
                              row[3 * x + 1] = from[4 * x + 1];
                              row[3 * x + 2] = from[4 * x + 2];
                          }
                      });
}

std::vector<uint8_t> encodePngGrey16(int width, int height, std::span<const uint16_t> samples,
                                     PngCompression compression) {
    SIERRA_CHECK(width > 0 && height > 0 && samples.size() == size_t(width) * size_t(height),
                 "cannot encode a 16-bit PNG: ", width, "x", height, " needs ",
                 size_t(std::max(width, 0)) * size_t(std::max(height, 0)), " samples, got ",
                 samples.size());
    const size_t rowBytes = size_t(width) * 2;
    return encodeSpng(width, height, SPNG_COLOR_TYPE_GRAYSCALE, 16, rowBytes, compression,
                      [&](int y, uint8_t* row) {
                          std::memcpy(row, samples.data() + size_t(y) * size_t(width), rowBytes);
                      });
}

std::vector<uint8_t> encodePngGrey8(int width, int height, std::span<const uint8_t> samples,
                                    PngCompression compression) {
    SIERRA_CHECK(width > 0 && height > 0 && samples.size() == size_t(width) * size_t(height),
                 "cannot encode an 8-bit PNG: ", width, "x", height, " needs ",
                 size_t(std::max(width, 0)) * size_t(std::max(height, 0)), " samples, got ",
                 samples.size());
    return encodeSpng(width, height, SPNG_COLOR_TYPE_GRAYSCALE, 8, size_t(width), compression,
                      [&](int y, uint8_t* row) {
                          std::memcpy(row, samples.data() + size_t(y) * size_t(width),
                                      size_t(width));
                      });
}

std::vector<uint8_t> encodeJpeg(const gpu::Image& image, int quality) {
    checkImage(image, "JPEG");
    SIERRA_CHECK(quality >= 1 && quality <= 100, "JPEG quality must be 1..100, got ", quality);
    JpegError error{};
    unsigned char* out = nullptr;
    unsigned long size = 0;
    const bool ok = jpegEncode(image, quality, &error, &out, &size);
    std::vector<uint8_t> bytes;
    if (ok && out) bytes.assign(out, out + size);
    std::free(out);
    if (!ok) throw Error(msg("cannot encode JPEG: ", error.message));
    return bytes;
}

std::vector<uint8_t> encodeImage(const std::string& path, const gpu::Image& image,
                                 const ImageEncoding& encoding) {
    if (!isJpegName(path)) return encodePng(image, encoding.alpha, encoding.png);
    if (encoding.alpha)
        throw Error(msg("cannot write ", path,
                        ": JPEG has no alpha channel (write a .png for a transparent sky)"));
    return encodeJpeg(image, encoding.jpegQuality);
}

void writeImage(const std::string& path, const gpu::Image& image, const ImageEncoding& encoding) {
    namespace fs = std::filesystem;
    fs::path target(path);
    std::error_code ec;
    if (target.has_parent_path()) fs::create_directories(target.parent_path(), ec);
    if (ec)
        throw Error(
            msg("cannot create directory ", target.parent_path().string(), ": ", ec.message()));
    std::vector<uint8_t> bytes;
    try {
        bytes = encodeImage(path, image, encoding);
    } catch (const Error& e) {
        throw Error(msg("cannot write ", path, ": ", e.what()));
    }
    writeFileAtomic(path, bytes);
}

void writePng(const std::string& path, const gpu::Image& image, bool alpha) {
    writeImage(path, image, {.alpha = alpha});
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
    char number[24];
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
