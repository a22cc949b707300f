// sierra_image_compare A.png B.png: how far two images of one size are apart,
// by render::compareImages. Prints "psnr DB" (inf for identical images),
// "differing SHARE" (pixels off by more than 8 levels in some channel) and
// "mean_absolute M" (0..255), one a line. Exits 2 for a bad command line, 1
// for a file that cannot be read or images of different sizes.

#include <sierra/core/Error.h>
#include <sierra/render/Capture.h>

#include <cstdio>

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: sierra_image_compare A.png B.png\n");
        return 2;
    }
    try {
        const sierra::gpu::Image a = sierra::render::readPng(argv[1]);
        const sierra::gpu::Image b = sierra::render::readPng(argv[2]);
        const sierra::render::ImageDifference d = sierra::render::compareImages(a, b);
        std::printf("psnr %.3f\ndiffering %.6f\nmean_absolute %.4f\n", d.psnr, d.differingShare,
                    d.meanAbsolute);
        return 0;
    } catch (const sierra::Error& e) {
        std::fprintf(stderr, "sierra_image_compare: error: %s\n", e.what());
        return 1;
    }
}
