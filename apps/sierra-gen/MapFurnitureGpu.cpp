// sierra-gen-gpu's part of `sierra-gen map` with labels or map furniture
// (--label, --title, --scale-bar, --north-arrow): the finished map is drawn
// into a headless EGL framebuffer and the 3D frames' overlay
// (render/Annotations.h: DejaVu Sans through Dear ImGui, halos, greedy label
// placement) goes over it, seen by an orthographic camera straight down
// whose pixels are the map's samples, so the scale bar is exact.

#include "Commands.h"

#include <sierra/core/Error.h>
#include <sierra/core/Log.h>
#include <sierra/core/Progress.h>
#include <sierra/facade/MapLayers.h>
#include <sierra/gpu/EglContext.h>
#include <sierra/gpu/Gl.h>
#include <sierra/render/Annotations.h>
#include <sierra/render/FrameTarget.h>
#include <sierra/scene/Terrain.h>

#include <vector>

namespace sierra::apps {

render::AnnotationDesc mapAnnotations(const scene::Scene& s, const terrain::Heightfield& field) {
    render::AnnotationDesc a = facade::furnitureAnnotations(s.layers.furniture);
    // Map space: x = i * spacingZ, z = j * spacingZ, so its pixels are square;
    // a pixel is then spacingX metres across, which the bar measures along x.
    const float sx = field.spacingX(), sz = field.spacingZ();
    a.unitsPerMetre = scene::metricHeights(s.terrain, field) ? sz / sx : 0.0f;
    const facade::TerrainPlacement place =
        facade::terrainPlacement(field, field.width(), field.height());
    for (const facade::LabelSample& l : facade::labelSamples(s, field, place))
        a.labels.push_back({l.text, {float(l.i) * sz, 0.0f, float(l.j) * sz}, 1.0f});
    return a;
}

void drawMapFurniture(terrain::RgbImage& image, const scene::Scene& s,
                      const terrain::Heightfield& field) {
    const render::AnnotationDesc desc = mapAnnotations(s, field);
    gpu::EglContext context = gpu::EglContext::create({.width = 16, .height = 16});
    log::info("map furniture: ", context.renderer());
    const int w = image.width, h = image.height;
    render::FrameTarget target =
        render::FrameTarget::create({.width = w, .height = h, .offscreen = true});
    gpu::Texture map = gpu::Texture::create({.format = GL_RGB8, .width = w, .height = h});
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    map.upload(GL_RGB, GL_UNSIGNED_BYTE, image.rgb.data());
    gpu::Framebuffer source = gpu::Framebuffer::create();
    source.attach(GL_COLOR_ATTACHMENT0, map);
    source.checkComplete("the map's framebuffer");

    target.begin({1.0f, 1.0f, 1.0f, 1.0f});
    GLint drawn = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawn);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, source.id());
    // The texture holds row 0 at its bottom: flipped, row 0 is the frame's top.
    glBlitFramebuffer(0, 0, w, h, 0, h, w, 0, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, GLuint(drawn));

    // Straight down on the map's centre, the frame spanning its rows edge to edge.
    const float sz = field.spacingZ();
    render::Camera camera;
    camera.projection = render::Projection::Orthographic;
    camera.target = {0.5f * float(w - 1) * sz, 0.0f, 0.5f * float(h - 1) * sz};
    camera.position = camera.target + glm::vec3(0.0f, 10.0f, 0.0f);
    camera.orthoHeight = float(h) * sz;
    camera.nearPlane = 1.0f;
    camera.farPlane = 20.0f;
    render::AnnotationOverlay overlay(desc.textPixels);
    const render::AnnotationLayout layout =
        render::layoutAnnotations(desc, camera, w, h, nullptr, overlay.measurer());
    if (layout.scaleBar)
        log::info("map furniture: scale bar ", layout.scaleBar->text, " = ",
                  fixed(layout.scaleBar->pixels, 1), " px");
    if (!desc.labels.empty())
        log::info("map furniture: ", layout.labels.size(), " of ", desc.labels.size(),
                  " labels placed");
    if (layout.crowdedOut)
        log::warn("map furniture: ", layout.crowdedOut, " of ", desc.labels.size(),
                  " labels found no free place");
    overlay.draw(desc, layout);

    const gpu::Image frame = target.read();
    for (size_t k = 0; k < size_t(w) * size_t(h); ++k)
        for (int c = 0; c < 3; ++c) image.rgb[3 * k + size_t(c)] = frame.rgba[4 * k + size_t(c)];
}

}  // namespace sierra::apps
