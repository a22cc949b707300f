#version 450 core
// The shaded terrain: albedo from the surface function chosen when the program
// is built (surface.glsl stands for one of the surface_*.glsl files), Lambert
// light from the sun, and fog towards the sky colour. Height and normal come
// from the full-resolution data at the fragment's ground position, so a
// simplified mesh shades like the full grid and only its geometry differs.
#include "frame.glsl"
#include "terrain_common.glsl"
#include "surface.glsl"

in vec3 vWorld;
out vec4 fragColour;

void main() {
    if (overPadding(vWorld)) discard;
    Ground g = groundAt(vWorld.xz);
    vec3 albedo = surfaceAlbedo(vWorld, g);
    float ambient = uSun.w;
    float light = ambient + (1.0 - ambient) * max(dot(g.normal, uSun.xyz), 0.0);
    vec3 colour = albedo * light;
    float fog = 1.0 - exp(-uFog.x * distance(vWorld, uEye.xyz));
    fragColour = vec4(mix(colour, uSky.rgb, clamp(fog, 0.0, 1.0)), 1.0);
}
