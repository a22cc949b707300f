#pragma once
// The relief lighting of a tiled terrain (render/TiledTerrain.h): the sun's
// visibility (cast shadows) and the sky light of analysis/Relief.h, computed
// on the GPU (render/ReliefGpu.h) once on the file's overview
// (sbt::readOverview, every stride-th sample) and sampled bilinearly by world
// x, z, so both are continuous across tile borders at the overview's
// resolution. The overview is read on first use; the sky light is computed
// once per horizon radius, the sun's visibility again when the sun changes.

#include <sierra/gpu/Objects.h>
#include <sierra/render/ReliefGpu.h>
#include <sierra/sbt/TileFile.h>

#include <glm/glm.hpp>

#include <optional>
#include <vector>

namespace sierra::render {

struct TiledReliefRequest {
    bool shadows = false;                      // the visible share of the sun's disc (1 when off)
    bool skyLight = false;                     // the cosine-weighted sky light (1 when off)
    glm::vec3 sunDirection{0.0f, 1.0f, 0.0f};  // towards the sun
    float sunSize = 0.53f;                     // angular diameter, degrees, (0, 20]
    float radius = 0.0f;  // horizon search radius, world units; 0 = the whole terrain
    bool any() const { return shadows || skyLight; }
};

class TiledRelief {
  public:
    // The overview's sides are at most maxSide samples (and what ReliefGpu
    // takes); nothing is read before the first prepare().
    TiledRelief(const sbt::TileFile& file, int maxSide);
    TiledRelief(TiledRelief&&) noexcept;
    TiledRelief& operator=(TiledRelief&&) noexcept;
    ~TiledRelief();

    // Makes the fields `request` asks for resident, computing what is not
    // kept (each computation logged with its time); a field not asked for
    // reads 1. Returns the milliseconds spent. Throws sierra::Error for a
    // sun size or radius the relief computation refuses.
    double prepare(const TiledReliefRequest& request);
    // Sun visibility on unit sunUnit, sky light on skyUnit (R16F, linear,
    // one texel per overview sample).
    void bind(unsigned sunUnit, unsigned skyUnit) const;
    // World x, z to the fields' texture coordinates: uv = xz * xy + zw.
    glm::vec4 worldToUv() const;

    int stride() const { return stride_; }  // file samples per overview sample
    int width() const { return width_; }    // overview samples, 0 before the first prepare
    int height() const { return height_; }
    // The fields as sampled (overview samples, row-major, read back).
    std::vector<float> readSunVisibility() const;
    std::vector<float> readSkyLight() const;

  private:
    void readOverviewOnce();
    const sbt::TileFile* file_;
    int maxSide_;
    int stride_ = 1, width_ = 0, height_ = 0;
    glm::vec2 spacing_{1.0f};  // world units between overview samples
    std::optional<ReliefGpu> gpu_;
    gpu::Texture sun_, sky_, one_;
    std::optional<std::vector<float>> sunKey_;  // azimuth, altitude, size, radius of sun_
    std::optional<float> skyRadius_;            // radius of sky_
};

}  // namespace sierra::render
