// sierra_png_stats FILE X0 Y0 X1 Y1: what the app tests need to know of a
// rendered PNG's rectangle [X0, X1) x [Y0, Y1) (pixels, row 0 at the top; a
// negative or oversized bound is clamped to the image). Prints one
// "key value" line each:
//   size W H        the whole image
//   corner R G B    the image's top-left pixel (the sky in a framed view)
//   not_corner S    share of the rectangle's pixels off the corner colour by
//                   more than 24 levels in some channel (the golden tests'
//                   threshold)
//   dark S          share whose every channel is below 64 (the debug panel's
//                   background)
//   bright S        share whose every channel is above 160 (the panel's text)
// Exits 2 for a bad command line, 1 for a file that cannot be read.

#include <sierra/core/Error.h>
#include <sierra/render/Capture.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>

int main(int argc, char** argv) {
    if (argc != 6) {
        std::fprintf(stderr, "usage: sierra_png_stats FILE X0 Y0 X1 Y1\n");
        return 2;
    }
    try {
        const sierra::gpu::Image image = sierra::render::readPng(argv[1]);
        if (image.width < 1 || image.height < 1)
            throw sierra::Error(std::string(argv[1]) + ": the image is empty");
        const int x0 = std::clamp(std::atoi(argv[2]), 0, image.width);
        const int y0 = std::clamp(std::atoi(argv[3]), 0, image.height);
        const int x1 = std::clamp(std::atoi(argv[4]), x0, image.width);
        const int y1 = std::clamp(std::atoi(argv[5]), y0, image.height);
        auto px = [&](int x, int y) { return &image.rgba[(size_t(y) * image.width + x) * 4]; };
        const uint8_t* corner = px(0, 0);
        long notCorner = 0, dark = 0, bright = 0;
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) {
                const uint8_t* p = px(x, y);
                int off = 0, lo = 255, hi = 0;
                for (int c = 0; c < 3; ++c) {
                    off = std::max(off, std::abs(int(p[c]) - int(corner[c])));
                    lo = std::min(lo, int(p[c]));
                    hi = std::max(hi, int(p[c]));
                }
                notCorner += off > 24;
                dark += hi < 64;
                bright += lo > 160;
            }
        const double n = std::max(1.0, double(x1 - x0) * double(y1 - y0));
        std::printf("size %d %d\ncorner %d %d %d\nnot_corner %.4f\ndark %.4f\nbright %.4f\n",
                    image.width, image.height, corner[0], corner[1], corner[2], notCorner / n,
                    dark / n, bright / n);
    } catch (const sierra::Error& e) {
        std::fprintf(stderr, "sierra_png_stats: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
