#version 450 core
// The tiled terrain's colour (render/TiledTerrain.h): a hypsometric ramp over
// the height range, lit by the sun with an ambient term, hazed towards the
// sky with distance. Normals from the finest heights on the GPU; cast shadows
// and sky light from the overview's relief fields (render/TiledRelief.h).
#include "tiled_common.glsl"

uniform vec3 uEye;
uniform vec3 uSun;       // towards the sun, unit
uniform vec3 uSky;       // the frame's clear colour, 0..1
uniform float uFog;      // haze per world unit
uniform float uAmbient;  // 0..1
uniform vec4 uReliefUv;  // world x, z to the relief fields' uv: xz * xy + zw
layout(binding = 14) uniform sampler2D uSunVisibility;  // the visible share of the sun's disc
layout(binding = 15) uniform sampler2D uSkyLight;       // the cosine-weighted sky light

in vec3 vWorld;
out vec4 fragColour;

// Lowland green to rock to snow, linear.
vec3 ramp(float t) {
    const vec3 stops[5] = vec3[5](vec3(0.10, 0.24, 0.08), vec3(0.32, 0.40, 0.14),
                                  vec3(0.45, 0.36, 0.24), vec3(0.50, 0.47, 0.44),
                                  vec3(0.92, 0.93, 0.95));
    float x = clamp(t, 0.0, 1.0) * 4.0;
    int i = min(int(x), 3);
    return mix(stops[i], stops[i + 1], x - float(i));
}

void main() {
    if (any(greaterThan(vWorld.xz, uTileSpacing.zw + 1e-3 * uTileSpacing.xy))) discard;
    TiledGround g = tiledGroundAt(vWorld.xz);
    if (isnan(g.height)) discard;  // no data here
    float t = (g.height - uTileRange.x) / max(uTileRange.y - uTileRange.x, 1e-6);
    // As the in-memory renderer's terrainLight: the ambient term scaled by
    // the sky light, the sun's Lambert term by the share of its disc seen
    // (both 1 when off; uSun is 0 for a sun below the horizon).
    vec2 uv = vWorld.xz * uReliefUv.xy + uReliefUv.zw;
    float sun = textureLod(uSunVisibility, uv, 0.0).r, sky = textureLod(uSkyLight, uv, 0.0).r;
    float light = uAmbient * sky + (1.0 - uAmbient) * max(dot(g.normal, uSun), 0.0) * sun;
    // Display colour, then the haze towards the sky as the frame is cleared to it.
    vec3 colour = pow(ramp(t) * light, vec3(1.0 / 2.2));
    float haze = 1.0 - exp(-uFog * distance(uEye, vWorld));
    fragColour = vec4(mix(colour, uSky, clamp(haze, 0.0, 1.0)), 1.0);
}
