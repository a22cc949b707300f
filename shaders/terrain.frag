#version 450 core
// Terrain shading: hypsometric colour ramp and Lambert light. Height, normal
// and colour come from the full-resolution data at the fragment's ground
// position, so a simplified mesh shades like the full grid and only its
// geometry differs.
#include "terrain_common.glsl"

layout(binding = 1) uniform sampler1D uRamp;  // colours over uRampRange
uniform vec2 uRampRange;    // world heights of the first and last ramp entries
uniform vec3 uSunDir;       // unit vector towards the light
uniform vec3 uEye;
uniform vec3 uSkyColour;
uniform float uFogDensity;  // per world unit; 0 = no haze
uniform float uAmbient;     // light that reaches faces turned away, 0..1

in vec3 vWorld;
out vec4 fragColour;

void main() {
    if (overPadding(vWorld)) discard;
    vec2 texel = 1.0 / vec2(uSide);
    vec2 uv = (vWorld.xz / uSpacing + 0.5) * texel;
    float h = texture(uHeights, uv).r;
    float dx = texture(uHeights, uv + vec2(texel.x, 0.0)).r - texture(uHeights, uv - vec2(texel.x, 0.0)).r;
    float dz = texture(uHeights, uv + vec2(0.0, texel.y)).r - texture(uHeights, uv - vec2(0.0, texel.y)).r;
    vec3 normal = normalize(vec3(-dx / (2.0 * uSpacing.x), 1.0, -dz / (2.0 * uSpacing.y)));
    if (h < uSeaLevel) normal = vec3(0.0, 1.0, 0.0);  // water lies flat

    float t = clamp((h - uRampRange.x) / (uRampRange.y - uRampRange.x), 0.0, 1.0);
    vec3 albedo = texture(uRamp, t).rgb;
    float light = uAmbient + (1.0 - uAmbient) * max(dot(normal, uSunDir), 0.0);
    vec3 colour = albedo * light;

    float fog = 1.0 - exp(-uFogDensity * distance(vWorld, uEye));
    fragColour = vec4(mix(colour, uSkyColour, clamp(fog, 0.0, 1.0)), 1.0);
}
