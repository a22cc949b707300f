// The per-frame uniform block every pass reads (engine: render/FrameUniforms.h,
// written once per frame, binding 0).
layout(std140, binding = 0) uniform Frame {
    mat4 uViewProj;
    vec4 uEye;        // xyz: camera position (world units)
    vec4 uLodEye;     // xyz: eye the SBT measures distance from; w: lambda / tau for geomorphing, 0 = off
    vec4 uSun;        // xyz: unit vector towards the sun, 0 below the horizon; w: ambient light 0..1
    vec4 uSky;        // rgb: sky colour; a: background alpha
    vec4 uFrameSize;  // xy: frame size in pixels; z: lambda; w: tau in pixels
    vec4 uFog;        // x: fog density per world unit (0 = off); y: 1 for orthographic; z: eye distance where it begins
    vec4 uViewDir;    // xyz: camera forward, unit
};

// Unit vector from a world point towards the camera (the view direction
// reversed for an orthographic camera).
vec3 towardsEye(vec3 world) {
    return uFog.y > 0.5 ? -uViewDir.xyz : normalize(uEye.xyz - world);
}
