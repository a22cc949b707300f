// Shared by the terrain stages: the terrain data texture and grid layout.
//
// uData holds one texel per grid sample (i, j) of the drawn surface (water
// flattened to sea level):
//   r: world height, g: geomorph base (the mean of the world heights of the
//   hypotenuse endpoints the vertex bisects), b: saturated object-space error
//   (world units), a: nested bounding radius (world units).
layout(binding = 0) uniform sampler2D uData;
// The true world heights (the ground below the water too), linearly filtered.
layout(binding = 2) uniform sampler2D uHeights;
uniform int uSide;       // samples per side, 2^n + 1
uniform vec2 uSpacing;   // world distance between samples along x and z
uniform float uSeaLevel; // world height of the water surface
uniform vec2 uValidMax;  // world x, z of the last real sample; beyond it lies padding

// True for fragments over the padding added to reach (2^n+1)^2 samples.
bool overPadding(vec3 world) {
    return any(greaterThan(world.xz, uValidMax + 1e-3 * uSpacing));
}

vec3 gridToWorld(ivec2 ij, float height) {
    return vec3(float(ij.x) * uSpacing.x, height, float(ij.y) * uSpacing.y);
}
