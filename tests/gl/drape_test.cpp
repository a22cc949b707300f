// Imagery drapes on the terrain (render/DrapeSurface.h): seen straight down
// in an orthographic frame, a drape's texels land on their pixels; where it
// does not reach, the surface beneath shows; multiply and opacity blend as
// their formulas say; the drape is lit like any albedo.

#include "GlTest.h"
#include "GoldenCompare.h"

#include <sierra/render/Capture.h>
#include <sierra/render/DrapeSurface.h>
#include <sierra/render/FrameTarget.h>
#include <sierra/render/TerrainRenderer.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace sierra::test {
namespace {

constexpr int kSide = 257;  // samples and frame pixels: one pixel a sample

terrain::DrapeImage image(int width, int height,
                          const std::function<std::array<uint8_t, 4>(int, int)>& colour) {
    terrain::DrapeImage d;
    d.width = width;
    d.height = height;
    d.rgba.resize(size_t(width) * height * 4);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const auto c = colour(x, y);
            std::copy(c.begin(), c.end(), d.rgba.begin() + (ptrdiff_t(y) * width + x) * 4);
        }
    d.coverage = 1.0;
    return d;
}

std::array<uint8_t, 4> checker(int x, int y) {
    const bool dark = (x / 8 + y / 8) % 2 == 0;
    return dark ? std::array<uint8_t, 4>{40, 60, 160, 255}
                : std::array<uint8_t, 4>{230, 200, 90, 255};
}

// The frame inside its outer ring of pixels, whose centres lie on the grid's
// edge (half of them sky, by the rasteriser's rule): pixels 1 .. kSide - 2.
gpu::Image inner(const gpu::Image& i) {
    gpu::Image out{kSide - 2, kSide - 2, {}};
    for (int y = 1; y < kSide - 1; ++y)
        out.rgba.insert(out.rgba.end(), i.rgba.begin() + (ptrdiff_t(y) * kSide + 1) * 4,
                        i.rgba.begin() + (ptrdiff_t(y) * kSide + kSide - 1) * 4);
    return out;
}

class Drape : public GlTest {
  protected:
    void SetUp() override {
        createContext(kSide, kSide);
        field_ = terrain::Heightfield(kSide, kSide, 10.0f);  // flat: lit by the zenith sun at 1
        terrain_.emplace(render::TerrainRenderer::create({.field = &field_}));
        target_.emplace(render::FrameTarget::create({.width = kSide, .height = kSide}));
    }

    // Straight down over the grid's pixel corners, the sun at the zenith, no fog:
    // every fragment's light is exactly 1, so the frame shows the albedo.
    gpu::Image frame(float sunAltitude = 90.0f) {
        render::Camera camera;
        camera.projection = render::Projection::Orthographic;
        camera.position = {128.0f, 200.0f, 128.0f};
        camera.target = {128.0f, 0.0f, 128.0f};
        camera.orthoHeight = float(kSide);
        camera.nearPlane = 1.0f;
        camera.farPlane = 400.0f;
        render::DrawOptions options{.lod = render::Lod::Full};
        options.lighting.fogDensity = 0.0f;
        options.lighting.sunDirection = render::compassDirection(180.0f, sunAltitude);
        target_->begin(render::TerrainRenderer::clearColour({}));
        terrain_->draw(camera, kSide, kSide, options);
        return target_->read();
    }

    void drape(std::vector<render::DrapeLayer> layers) {
        terrain_->setSurface(
            render::makeDrapeSurface(render::makeRampSurface(terrain_->terrain()), layers));
    }

    terrain::Heightfield field_;
    std::optional<render::TerrainRenderer> terrain_;
    std::optional<render::FrameTarget> target_;
};

TEST_F(Drape, StraightDownItsTexelsLandOnTheirPixels) {
    const auto checkerboard = image(kSide, kSide, checker);
    drape({{&checkerboard}});
    const gpu::Image shot = frame();
    render::writePng(testOutputPath("drape_checker.png"), shot);
    gpu::Image expected{kSide, kSide, {}};
    expected.rgba = checkerboard.rgba;
    const auto result = compareWithGolden(inner(shot), inner(expected));
    std::printf("checkerboard drape against the image: %.1f dB\n", result.psnr);
    EXPECT_GE(result.psnr, 35.0);
    // At about half the resolution (129 texels over 257 pixels), the frame is
    // the image resampled bilinearly between texel centres.
    const auto coarse = image(129, 129, [](int x, int y) { return checker(2 * x, 2 * y); });
    drape({{&coarse}});
    gpu::Image resampled{kSide, kSide, std::vector<uint8_t>(size_t(kSide) * kSide * 4, 255)};
    for (int y = 0; y < kSide; ++y)
        for (int x = 0; x < kSide; ++x) {
            const float u = std::clamp((x + 0.5f) * 129.0f / kSide - 0.5f, 0.0f, 128.0f);
            const float v = std::clamp((y + 0.5f) * 129.0f / kSide - 0.5f, 0.0f, 128.0f);
            const int x0 = int(u), y0 = int(v), x1 = std::min(x0 + 1, 128),
                      y1 = std::min(y0 + 1, 128);
            const float fu = u - x0, fv = v - y0;
            for (int c = 0; c < 3; ++c) {
                auto t = [&](int tx, int ty) {
                    return float(coarse.rgba[(size_t(ty) * 129 + tx) * 4 + c]);
                };
                const float value = (1 - fu) * (1 - fv) * t(x0, y0) + fu * (1 - fv) * t(x1, y0) +
                                    (1 - fu) * fv * t(x0, y1) + fu * fv * t(x1, y1);
                resampled.rgba[(size_t(y) * kSide + x) * 4 + c] = uint8_t(std::lround(value));
            }
        }
    const auto half = compareWithGolden(inner(frame()), inner(resampled));
    std::printf("129x129 drape against the image resampled: %.1f dB\n", half.psnr);
    EXPECT_GE(half.psnr, 35.0);
}

TEST_F(Drape, WhereItDoesNotReachTheSurfaceBeneathShows) {
    const gpu::Image plain = frame();
    const auto west = image(kSide, kSide, [](int x, int) {
        return std::array<uint8_t, 4>{200, 30, 30, uint8_t(x < kSide / 2 ? 255 : 0)};
    });
    drape({{&west}});
    const gpu::Image draped = frame();
    render::writePng(testOutputPath("drape_half.png"), draped);
    auto at = [](const gpu::Image& i, int x, int y) {
        return &i.rgba[(size_t(y) * i.width + x) * 4];
    };
    int eastSame = 0, westRed = 0;
    for (int y = 1; y < kSide - 1; ++y) {
        for (int x = kSide / 2 + 2; x < kSide - 1; ++x)
            eastSame += std::equal(at(draped, x, y), at(draped, x, y) + 3, at(plain, x, y));
        for (int x = 1; x < kSide / 2 - 2; ++x) {
            const uint8_t* p = at(draped, x, y);
            westRed +=
                std::abs(p[0] - 200) <= 1 && std::abs(p[1] - 30) <= 1 && std::abs(p[2] - 30) <= 1;
        }
    }
    EXPECT_EQ(eastSame, (kSide - 2) * (kSide - 1 - kSide / 2 - 2))
        << "the base surface in the east";
    EXPECT_EQ(westRed, (kSide - 2) * (kSide / 2 - 3)) << "the drape in the west";
}

TEST_F(Drape, MultiplyAndOpacityBlendAsTheirFormulasSay) {
    const gpu::Image plain = frame();
    const auto grey = image(kSide, kSide, [](int, int) {
        return std::array<uint8_t, 4>{128, 128, 128, 255};
    });
    const auto red = image(kSide, kSide, [](int, int) {
        return std::array<uint8_t, 4>{255, 0, 0, 255};
    });
    auto centre = [](const gpu::Image& i) {
        const uint8_t* p = &i.rgba[(size_t(kSide / 2) * kSide + kSide / 2) * 4];
        return glm::vec3(p[0], p[1], p[2]);
    };
    const glm::vec3 base = centre(plain);
    drape({{&grey, 1.0f, render::DrapeBlend::Multiply}});
    const glm::vec3 multiplied = centre(frame());
    drape({{&red, 0.5f}});
    const glm::vec3 halfRed = centre(frame());
    // Replace at half opacity, then multiply: (c / 2 + red / 2) * grey.
    drape({{&red, 0.5f}, {&grey, 1.0f, render::DrapeBlend::Multiply}});
    const glm::vec3 both = centre(frame());
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(multiplied[c], base[c] * 128.0f / 255.0f, 1.5f) << c;
        const float r = c == 0 ? 255.0f : 0.0f;
        EXPECT_NEAR(halfRed[c], 0.5f * base[c] + 0.5f * r, 1.5f) << c;
        EXPECT_NEAR(both[c], (0.5f * base[c] + 0.5f * r) * 128.0f / 255.0f, 2.0f) << c;
    }
    EXPECT_THROW(drape({{&red, 1.5f}}), Error);
}

TEST_F(Drape, AStreamedDrapeDrawsAsTheComposedOne) {
    // Half transparent in places, at half opacity: premultiplied either way.
    const auto art = image(300, 200, [](int x, int y) {
        return std::array<uint8_t, 4>{uint8_t(x), uint8_t(y), uint8_t((x + y) / 2),
                                      uint8_t(x < 150 ? 255 : 100)};
    });
    gpu::Image png{art.width, art.height, art.rgba};
    const std::string file = testOutputPath("drape_streamed_source.png");
    render::writePng(file, png, true);
    drape({{&art, 0.5f}});
    const gpu::Image composed = frame();
    terrain::DrapeImage header;
    terrain_->setSurface(
        render::makeStreamedDrapeSurface(render::makeRampSurface(terrain_->terrain()), file,
                                         {.width = kSide, .height = kSide}, 0.5f, &header));
    const gpu::Image streamed = frame();
    render::writePng(testOutputPath("drape_streamed.png"), streamed);
    EXPECT_TRUE(header.stretched);
    // Stretched over the square grid at the image's finer density: 300 x 300.
    EXPECT_EQ(header.width, 300);
    EXPECT_EQ(header.height, 300);
    const auto result = compareWithGolden(inner(streamed), inner(composed));
    std::printf("streamed against composed: %.1f dB, max difference within the tolerance: %d\n",
                result.psnr, int(result.matches));
    EXPECT_GE(result.psnr, 50.0);
}

TEST_F(Drape, ADrapeIsLitLikeTheSurface) {
    const auto white = image(kSide, kSide, [](int, int) {
        return std::array<uint8_t, 4>{255, 255, 255, 255};
    });
    drape({{&white}});
    const size_t centre = (size_t(kSide / 2) * kSide + kSide / 2) * 4;
    const glm::vec3 noon = glm::vec3(frame(90.0f).rgba[centre]);
    const glm::vec3 low = glm::vec3(frame(30.0f).rgba[centre]);
    // ambient + (1 - ambient) sin(altitude) for a flat ground.
    const float ambient = render::Lighting{}.ambient;
    EXPECT_NEAR(noon.x, 255.0f, 1.0f);
    EXPECT_NEAR(low.x, 255.0f * (ambient + (1.0f - ambient) * 0.5f), 1.5f);
}

}  // namespace
}  // namespace sierra::test
