#pragma once
// How mipmapped colour textures (zone tiles, drapes) are filtered on this
// driver. llvmpipe (Mesa 22.3) filters in software: with anisotropy 8 one
// 1080p frame took minutes, and bilinear lookups of the nearest mip level
// cost fewer instructions than trilinear ones (docs/zones.md, "Frame cost").
// Other drivers: trilinear, anisotropy 8 (or the driver's limit).

#include <sierra/gpu/Objects.h>

namespace sierra::render {

// Sets the min filter and anisotropy of `texture` (`levels` mip levels,
// already filled) for the current context's driver.
void applyMipmapFiltering(const gpu::Texture& texture, int levels);

}  // namespace sierra::render
