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
#include <string>
#include <vector>

namespace sierra::render {

enum class DrapeBlend { Replace, Multiply };

struct LinePyramid;  // render/VectorOverlay.h

struct DrapeLayer {
    const terrain::DrapeImage* image = nullptr;
    float opacity = 1.0f;  // 0..1, times the image's alpha
    DrapeBlend blend = DrapeBlend::Replace;
};

// The layers composed into one map per channel, albedo = base * multiplier +
// added, at the finest layer's size (coarser layers resampled bilinearly):
// RGBA8 images. Replace layers alone multiply by a grey: `added` then holds
// 1 - that grey as its alpha and the shader reads it alone; otherwise alpha
// is 255 in both.
struct DrapeMaps {
    int width = 0, height = 0;
    bool replaceOnly = true;
    std::vector<uint8_t> multiplier;
    std::vector<uint8_t> added;
};
DrapeMaps composeDrapes(std::span<const DrapeLayer> layers);

// `base` with `layers` over it, and over them the far vector lines of
// `lines` when given (render/VectorOverlay.h; faded out where its finest
// level is magnified, since LinePass draws the near lines as quads). At
// least one layer or the lines. Throws sierra::Error for an opacity outside
// 0..1, a missing image, or maps larger than the driver's texture limit
// (readDrape's maxTexels should be that limit).
std::unique_ptr<Surface> makeDrapeSurface(std::unique_ptr<Surface> base,
                                          std::span<const DrapeLayer> layers,
                                          const LinePyramid* lines = nullptr);

// One replace layer read from `path` strip by strip (terrain::readDrapeStrips)
// straight into its texture, premultiplied by its alpha times `opacity`: the
// image is never held whole, for drapes near the texture limit; `lines` as in
// makeDrapeSurface. maxTexels is
// lowered to the driver's limit. `header`, when given, receives the drape's
// size, flags and coverage.
std::unique_ptr<Surface> makeStreamedDrapeSurface(std::unique_ptr<Surface> base,
                                                  const std::string& path,
                                                  const terrain::DrapeOptions& options,
                                                  float opacity = 1.0f,
                                                  terrain::DrapeImage* header = nullptr,
                                                  const LinePyramid* lines = nullptr);

// The driver's largest texture side (GL_MAX_TEXTURE_SIZE).
int maxTextureSide();

}  // namespace sierra::render
