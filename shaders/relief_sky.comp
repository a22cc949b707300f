#version 450 core
// The sky-view factor and the terrain pass's sky light from the horizons of
// horizon.comp, one sample per invocation: analysis::skyViewFactor and
// analysis::skyLight (docs/relief.md has the closed form).
layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0) uniform sampler2DArray uHorizons;  // radians, layer d = azimuth d
layout(binding = 1) uniform sampler2D uHeights;        // stored heights (R32F)
layout(binding = 2) uniform usampler2D uMask;          // R8UI, 0 = no data
uniform float uScale;
uniform bool uHasMask;
uniform vec2 uSpacing;  // world units between samples in x and z
uniform int uDirections;
layout(std430, binding = 0) readonly buffer Azimuths { vec2 azimuths[]; };  // (ux, uz) per d

layout(r32f, binding = 0) uniform writeonly image2D uSkyView;
layout(r32f, binding = 1) uniform writeonly image2D uSkyLight;

const float kPi = 3.14159265358979;

bool inside(ivec2 ij, ivec2 size) {
    return all(greaterThanEqual(ij, ivec2(0))) && all(lessThan(ij, size));
}

// World height at ij, NaN outside the grid or without data.
float heightAt(ivec2 ij, ivec2 size) {
    if (!inside(ij, size)) return uintBitsToFloat(0x7fc00000u);
    if (uHasMask && texelFetch(uMask, ij, 0).r == 0u) return uintBitsToFloat(0x7fc00000u);
    return texelFetch(uHeights, ij, 0).r * uScale;
}

// The mean slope of the edges to the two neighbours along one axis that
// exist (NormalMethod::Edge), 0 with neither.
float axisSlope(float centre, float plus, float minus, float step) {
    float sum = 0.0;
    int n = 0;
    if (!isnan(plus)) {
        sum += (plus - centre) / step;
        ++n;
    }
    if (!isnan(minus)) {
        sum -= (minus - centre) / step;
        ++n;
    }
    return n > 0 ? sum / float(n) : 0.0;
}

void main() {
    const ivec2 size = textureSize(uHeights, 0).xy;
    const ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    if (!inside(ij, size)) return;
    const float nan = uintBitsToFloat(0x7fc00000u);
    const float centre = heightAt(ij, size);
    vec3 normal = vec3(nan);
    if (!isnan(centre)) {
        const float sx = axisSlope(centre, heightAt(ij + ivec2(1, 0), size),
                                   heightAt(ij - ivec2(1, 0), size), uSpacing.x);
        const float sz = axisSlope(centre, heightAt(ij + ivec2(0, 1), size),
                                   heightAt(ij - ivec2(0, 1), size), uSpacing.y);
        normal = normalize(vec3(-sx, 1.0, -sz));
    }
    float sines = 0.0, light = 0.0;
    bool missing = false;
    for (int d = 0; d < uDirections; ++d) {
        const float g = texelFetch(uHorizons, ivec3(ij, d), 0).r;
        if (isnan(g)) {
            missing = true;
            break;
        }
        sines += sin(max(g, 0.0));
        // n . w = a cos e + b sin e for w at elevation e in this azimuth; the
        // sky from max(horizon, the tangent plane) to the zenith counts.
        const float a = normal.x * azimuths[d].x + normal.z * azimuths[d].y, b = normal.y;
        const float e0 = max(g, atan(-a, b));
        const float c = cos(e0);
        light += a * (kPi / 4.0 - e0 / 2.0 - sin(2.0 * e0) / 4.0) + b / 2.0 * c * c;
    }
    const bool none = missing || isnan(centre);
    imageStore(uSkyView, ij, vec4(none ? nan : 1.0 - sines / float(uDirections)));
    imageStore(uSkyLight, ij, vec4(none ? nan : min(1.0, 2.0 * light / float(uDirections))));
}
