#pragma once
// Imagery drapes over a surface: layers of terrain::DrapeImage (placed over
// the grid by terrain::readDrape) blended in order over a base surface's
// albedo, replacing it or multiplying it (the relief look), each with its
// alpha times an opacity. The result is an albedo like any other, so the
// terrain pass lights, shadows, sky-lights and fogs it, overlays draw over it,
// and a TIN mesh shades the same (shaders/surface_drape.glsl).

#include <sierra/render/Surface.h>
#include <sierra/terrain/Drape.h>

#include <memory>
#include <span>
#include <vector>

namespace sierra::render {

enum class DrapeBlend { Replace, Multiply };

struct DrapeLayer {
    const terrain::DrapeImage* image = nullptr;
    float opacity = 1.0f;  // 0..1, times the image's alpha
    DrapeBlend blend = DrapeBlend::Replace;
};

// The layers composed into one map per channel, albedo = base * multiplier +
// added, at the finest layer's size (coarser layers resampled bilinearly):
// RGBA8 images, alpha unused (255).
struct DrapeMaps {
    int width = 0, height = 0;
    std::vector<uint8_t> multiplier;
    std::vector<uint8_t> added;
};
DrapeMaps composeDrapes(std::span<const DrapeLayer> layers);

// `base` with `layers` over it (at least one). Throws sierra::Error for an
// opacity outside 0..1, a missing image, or maps larger than the driver's
// texture limit (readDrape's maxTexels should be that limit).
std::unique_ptr<Surface> makeDrapeSurface(std::unique_ptr<Surface> base,
                                          std::span<const DrapeLayer> layers);

// The driver's largest texture side (GL_MAX_TEXTURE_SIZE).
int maxTextureSide();

}  // namespace sierra::render
