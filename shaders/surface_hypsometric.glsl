// Surface function: the hypsometric colour ramp (deep and shallow water, a
// thin sand band at the coast, grass, rock, snow) over the terrain's height
// range, read from a 1D ramp texture the terrain pass builds.
layout(binding = 1) uniform sampler1D uRamp;  // colours from the lowest to the highest world height

vec3 surfaceAlbedo(vec3 world, Ground g) {
    float t = clamp((g.height - uHeightInfo.z) / max(uHeightInfo.w - uHeightInfo.z, 1e-6), 0.0, 1.0);
    return texture(uRamp, t).rgb;
}
