// Micro-benchmarks of frame encoding on a 1080p frame: stb's PNG writer (the
// reference), libspng at each --png-compression level and libjpeg-turbo at
// the default quality, one thread each. Counters: ms per encode and the
// file's bytes. Target (issue 40): libspng fast in at most a quarter of stb's
// time, with a file no larger.
//
// The frame is synthetic and looks rendered: a smooth sky gradient over the
// top third, below it the hill-shaded, height-tinted 2049^2 diamond-square
// terrain (seed 1), each pixel the mean of 2x2 samples (as multisampling
// smooths a render).
#include <sierra/render/Capture.h>
#include <sierra/terrain/DiamondSquare.h>

#include <benchmark/benchmark.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace {

using sierra::gpu::Image;

const Image& frame() {
    static const Image image = [] {
        constexpr int kWidth = 1920, kHeight = 1080, kSky = kHeight / 3;
        auto field = sierra::terrain::generateDiamondSquare({.size = 2049, .seed = 1});
        auto [lo, hi] = field.range();
        const float relief = 300.0f / std::max(hi - lo, 1e-6f);  // heights over 2048 samples
        Image out{kWidth, kHeight, std::vector<uint8_t>(size_t(kWidth) * kHeight * 4, 255)};
        auto shade = [&](int i, int j, float rgb[3]) {
            const float dx = (field.at(i + 1, j) - field.at(i - 1, j)) * relief;
            const float dz = (field.at(i, j + 1) - field.at(i, j - 1)) * relief;
            const float lambert =
                std::clamp((-0.45f * dx + 0.75f * 2.0f - 0.35f * dz) /
                                   (2.0f * std::sqrt(dx * dx + 4.0f + dz * dz)) * 1.1f +
                               0.25f,
                           0.0f, 1.0f);
            const float t = (field.at(i, j) - lo) / std::max(hi - lo, 1e-6f);
            const float low[3] = {70, 140, 60}, high[3] = {140, 120, 100};
            for (int c = 0; c < 3; ++c) rgb[c] = (low[c] + t * (high[c] - low[c])) * lambert;
        };
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                uint8_t* p = &out.rgba[(size_t(y) * kWidth + size_t(x)) * 4];
                if (y < kSky) {
                    const float t = float(y) / float(kSky);
                    p[0] = uint8_t(150 + 20 * t);
                    p[1] = uint8_t(180 + 14 * t);
                    p[2] = uint8_t(220 + 10 * t);
                    continue;
                }
                float sum[3] = {0, 0, 0};
                for (int s = 0; s < 4; ++s) {
                    float rgb[3];
                    shade(1 + x + (s & 1), 1 + (y - kSky) + (s >> 1), rgb);
                    for (int c = 0; c < 3; ++c) sum[c] += rgb[c];
                }
                for (int c = 0; c < 3; ++c) p[c] = uint8_t(std::clamp(sum[c] / 4.0f, 0.0f, 255.0f));
            }
        return out;
    }();
    return image;
}

// ms per encode and the bytes of the last file, as counters.
template <typename Encode>
void measure(benchmark::State& state, const Encode& encode) {
    size_t bytes = 0;
    double ms = 0.0;
    for (auto _ : state) {
        const auto start = std::chrono::steady_clock::now();
        bytes = encode();
        ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                  .count();
    }
    state.counters["ms"] = benchmark::Counter(ms, benchmark::Counter::kAvgIterations);
    state.counters["bytes"] = double(bytes);
}

// The writer the frames went through before libspng: stb's, RGB rows.
void BM_EncodePngStb(benchmark::State& state) {
    const Image& image = frame();
    measure(state, [&] {
        std::vector<uint8_t> rgb(size_t(image.width) * image.height * 3);
        for (size_t p = 0, n = size_t(image.width) * image.height; p < n; ++p)
            for (int c = 0; c < 3; ++c) rgb[p * 3 + size_t(c)] = image.rgba[p * 4 + size_t(c)];
        std::vector<uint8_t> png;
        auto append = [](void* context, void* data, int size) {
            auto* out = static_cast<std::vector<uint8_t>*>(context);
            out->insert(out->end(), static_cast<uint8_t*>(data),
                        static_cast<uint8_t*>(data) + size);
        };
        stbi_write_png_to_func(append, &png, image.width, image.height, 3, rgb.data(),
                               image.width * 3);
        return png.size();
    });
}
BENCHMARK(BM_EncodePngStb)->Unit(benchmark::kMillisecond)->UseRealTime();

// Arg: 0 fast, 1 default, 2 best (render::PngCompression).
void BM_EncodePng(benchmark::State& state) {
    const auto level = sierra::render::PngCompression(state.range(0));
    measure(state, [&] { return sierra::render::encodePng(frame(), false, level).size(); });
    state.SetLabel(state.range(0) == 0 ? "fast" : state.range(0) == 1 ? "default" : "best");
}
BENCHMARK(BM_EncodePng)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// Arg: the quality.
void BM_EncodeJpeg(benchmark::State& state) {
    measure(state, [&] { return sierra::render::encodeJpeg(frame(), int(state.range(0))).size(); });
}
BENCHMARK(BM_EncodeJpeg)->Arg(90)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
