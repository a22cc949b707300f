// render::Capture's encoders: PNG (RGB, RGBA, 16-bit grey) decodes to the
// very samples encoded at every compression, JPEG stays close at its
// quality, writes are all-or-nothing and bad requests say what is wrong.
#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/render/Capture.h>

#include <gtest/gtest.h>
#include <spng.h>
#include <stb/stb_image.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

using namespace sierra;
namespace fs = std::filesystem;

namespace {

// A frame-like test image: a sky gradient over shaded, noisy ground, with a
// varying alpha.
gpu::Image testImage(int width, int height) {
    gpu::Image image{width, height, std::vector<uint8_t>(size_t(width) * height * 4)};
    uint32_t noise = 12345;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            noise = noise * 1664525u + 1013904223u;
            uint8_t* p = &image.rgba[(size_t(y) * width + x) * 4];
            const bool sky = y < height / 3;
            p[0] = uint8_t(sky ? 150 + y % 40 : 60 + (x * 7 + y * 3) % 90 + (noise >> 28));
            p[1] = uint8_t(sky ? 180 + y % 30 : 90 + (x + y) % 70 + (noise >> 27 & 7));
            p[2] = uint8_t(sky ? 220 : 40 + (x * y) % 50);
            p[3] = uint8_t(sky ? 0 : 255 - x % 64);
        }
    return image;
}

gpu::Image decode(const std::vector<uint8_t>& bytes, int* channels = nullptr) {
    int w = 0, h = 0, n = 0;
    stbi_uc* data = stbi_load_from_memory(bytes.data(), int(bytes.size()), &w, &h, &n, 4);
    EXPECT_NE(data, nullptr) << stbi_failure_reason();
    if (!data) return {};
    gpu::Image image{w, h, std::vector<uint8_t>(data, data + size_t(w) * h * 4)};
    stbi_image_free(data);
    if (channels) *channels = n;
    return image;
}

class CaptureFiles : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("sierra_capture_" + std::to_string(::getpid()) + "_" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    size_t fileCount() const {
        return size_t(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()));
    }
    fs::path dir_;
};

}  // namespace

TEST(Capture, PngRoundTripsExactlyAtEveryCompression) {
    const gpu::Image image = testImage(97, 61);
    size_t fastBytes = 0, bestBytes = 0;
    for (auto level : {render::PngCompression::Fast, render::PngCompression::Default,
                       render::PngCompression::Best}) {
        for (bool alpha : {false, true}) {
            const std::vector<uint8_t> png = render::encodePng(image, alpha, level);
            int channels = 0;
            const gpu::Image back = decode(png, &channels);
            ASSERT_EQ(back.width, image.width);
            ASSERT_EQ(back.height, image.height);
            EXPECT_EQ(channels, alpha ? 4 : 3);
            for (size_t i = 0; i < image.rgba.size(); ++i) {
                const uint8_t expected = i % 4 == 3 && !alpha ? 255 : image.rgba[i];
                ASSERT_EQ(back.rgba[i], expected) << "byte " << i << ", "
                                                  << "level " << int(level) << ", alpha " << alpha;
            }
            if (!alpha && level == render::PngCompression::Fast) fastBytes = png.size();
            if (!alpha && level == render::PngCompression::Best) bestBytes = png.size();
        }
    }
    EXPECT_LT(bestBytes, fastBytes) << "best compression is no smaller than fast";
}

TEST(Capture, Grey16PngKeepsEverySample) {
    const int w = 37, h = 23;
    std::vector<uint16_t> samples(size_t(w) * h);
    for (size_t i = 0; i < samples.size(); ++i) samples[i] = uint16_t(i * 2654435761u >> 16);
    const std::vector<uint8_t> png =
        render::encodePngGrey16(w, h, samples, render::PngCompression::Default);
    spng_ctx* ctx = spng_ctx_new(0);
    ASSERT_EQ(spng_set_png_buffer(ctx, png.data(), png.size()), 0);
    spng_ihdr ihdr{};
    ASSERT_EQ(spng_get_ihdr(ctx, &ihdr), 0);
    EXPECT_EQ(ihdr.bit_depth, 16);
    EXPECT_EQ(ihdr.color_type, SPNG_COLOR_TYPE_GRAYSCALE);
    std::vector<uint16_t> back(samples.size());
    // SPNG_FMT_PNG decodes 16-bit samples to host order.
    ASSERT_EQ(spng_decode_image(ctx, back.data(), back.size() * 2, SPNG_FMT_PNG, 0), 0);
    spng_ctx_free(ctx);
    EXPECT_EQ(back, samples);
    EXPECT_THROW(render::encodePngGrey16(w, h + 1, samples, render::PngCompression::Fast), Error);
}

TEST(Capture, JpegIsCloseAtItsQualityAndSmallerAtALowerOne) {
    gpu::Image image = testImage(160, 90);
    const std::vector<uint8_t> jpeg = render::encodeJpeg(image, 90);
    ASSERT_GE(jpeg.size(), 4u);
    EXPECT_EQ(jpeg[0], 0xFF);
    EXPECT_EQ(jpeg[1], 0xD8);  // SOI
    int channels = 0;
    const gpu::Image back = decode(jpeg, &channels);
    ASSERT_EQ(back.width, 160);
    ASSERT_EQ(back.height, 90);
    EXPECT_EQ(channels, 3);
    EXPECT_GT(render::compareImages(image, back).psnr, 25.0);
    const std::vector<uint8_t> rough = render::encodeJpeg(image, 20);
    EXPECT_LT(rough.size(), jpeg.size());
    EXPECT_LT(render::compareImages(image, decode(rough)).psnr,
              render::compareImages(image, back).psnr);
    EXPECT_THROW(render::encodeJpeg(image, 0), Error);
    EXPECT_THROW(render::encodeJpeg(image, 101), Error);
}

TEST_F(CaptureFiles, FormatFollowsTheName) {
    const gpu::Image image = testImage(64, 48);
    render::writeImage(path("a.png"), image, {});
    render::writeImage(path("b.JPG"), image, {});
    render::writeImage(path("c.jpeg"), image, {.jpegQuality = 50});
    const std::vector<uint8_t> png = readFileBytes(path("a.png"));
    EXPECT_EQ(png[1], 'P');
    EXPECT_EQ(png, render::encodePng(image));
    for (const char* name : {"b.JPG", "c.jpeg"}) {
        const std::vector<uint8_t> jpeg = readFileBytes(path(name));
        EXPECT_EQ(jpeg[0], 0xFF) << name;
        EXPECT_EQ(jpeg[1], 0xD8) << name;
    }
    EXPECT_LT(readFileBytes(path("c.jpeg")).size(), readFileBytes(path("b.JPG")).size());
    EXPECT_EQ(fileCount(), 3u) << "a temporary file was left";
}

TEST_F(CaptureFiles, JpegWithAlphaIsRefusedAndWritesNothing) {
    try {
        render::writeImage(path("f.jpg"), testImage(8, 8), {.alpha = true});
        FAIL() << "a JPEG with alpha was written";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("JPEG has no alpha channel"), std::string::npos)
            << e.what();
    }
    EXPECT_EQ(fileCount(), 0u);
}

TEST_F(CaptureFiles, AFailedWriteLeavesNoFileBehind) {
    // The target is a directory: the rename fails after the bytes were written.
    fs::create_directories(path("frame.png"));
    EXPECT_THROW(render::writeImage(path("frame.png"), testImage(8, 8), {}), Error);
    EXPECT_EQ(fileCount(), 1u) << "only the directory that was in the way";
    // An inconsistent image is refused before anything is written.
    gpu::Image broken = testImage(8, 8);
    broken.rgba.resize(10);
    EXPECT_THROW(render::writeImage(path("broken.png"), broken, {}), Error);
    EXPECT_FALSE(fs::exists(path("broken.png")));
    EXPECT_EQ(fileCount(), 1u);
}

TEST(Capture, SequenceNamesGrowPastFourDigits) {
    EXPECT_EQ(render::sequencePath("out/f.png", 7), "out/f_0007.png");
    EXPECT_EQ(render::sequencePath("out/f.jpg", 123456789), "out/f_123456789.jpg");
}
