// Shared by the overlay passes (lines, hatches): where an overlay point sits
// so it neither sinks into nor floats over the SBT mesh, and how a world
// segment becomes an antialiased screen-space quad (wide GL lines are not core
// profile). Needs frame.glsl and terrain_common.glsl.

// The drawn surface's world height at a ground position in grid units: the
// true height (bilinear between samples; exact at a vertex), raised to sea
// level where there is water (TerrainGpu::surface), so nothing is drawn on
// the ground under the water, which the flat water hides from above but not
// from beside the terrain's edge.
float surfaceHeight(vec2 grid) {
    vec2 texel = 1.0 / vec2(uGrid.x);
    float h = texture(uHeights, (grid + 0.5) * texel).r;
    return uHeightInfo.y > 0.5 && h < uHeightInfo.x ? uHeightInfo.x : h;  // NaN (no data) stays
}

// The point at grid position `grid` on the drawn surface, moved towards the
// camera along its view ray (so it stays on the same pixel) by as much as the
// SBT mesh can be off the true surface there, plus 0.2% of its distance for
// depth precision: the depth test then never hides it under the mesh, and it
// can only win against surfaces within that small distance in front of it.
// The mesh's bound: an inactive vertex projects to at most tau pixels, i.e.
// its error is at most tau * distance / lambda (the refinement's test,
// distance from the LOD eye); with the nearest vertex's own saturated error
// as a floor (a vertex blending in by geomorph).
vec3 overlayPoint(vec2 grid) {
    vec3 world = vec3(grid.x * uSpacingValid.x, surfaceHeight(grid), grid.y * uSpacingValid.y);
    ivec2 ij = clamp(ivec2(round(grid)), ivec2(0), ivec2(uGrid.x - 1));
    float error = texelFetch(uData, ij, 0).b;
    float screenBound = uFrameSize.z > 0.0 ? uFrameSize.w * distance(world, uLodEye.xyz) / uFrameSize.z : 0.0;
    float lift = max(error, screenBound) + 0.002 * distance(world, uEye.xyz);
    return world + towardsEye(world) * lift;
}

// One corner of the screen-space quad around the segment a-b (world), for
// corner 0..3 of a triangle strip: half-width `halfPx` pixels plus one pixel
// of antialiasing ramp, extended past each end by the same amount. `across`
// receives the signed distance from the centre line in pixels. Returns a
// point outside the clip volume when an end is behind the camera.
vec4 segmentCorner(vec3 a, vec3 b, int corner, float halfPx, out float across) {
    vec4 ca = uViewProj * vec4(a, 1.0), cb = uViewProj * vec4(b, 1.0);
    across = 0.0;
    if (ca.w <= 1e-6 || cb.w <= 1e-6) return vec4(2.0, 2.0, 2.0, 1.0);
    vec2 halfSize = 0.5 * uFrameSize.xy;
    vec2 sa = ca.xy / ca.w * halfSize, sb = cb.xy / cb.w * halfSize;
    vec2 d = sb - sa;
    float len = length(d);
    vec2 dir = len > 1e-6 ? d / len : vec2(1.0, 0.0);
    vec2 normal = vec2(-dir.y, dir.x);
    bool atB = (corner & 1) != 0;
    float side = (corner & 2) != 0 ? 1.0 : -1.0;
    float extent = halfPx + 1.0;
    vec4 c = atB ? cb : ca;
    vec2 offset = normal * side * extent + dir * (atB ? extent : -extent);
    across = side * extent;
    c.xy += offset / halfSize * c.w;
    return c;
}

// The screen size in pixels of one grid cell at a world point whose clip
// position is `clip`: a step of one spacing across the view direction,
// projected; 0 behind the camera. The overlays thin out where it is small.
float cellPixels(vec3 world, vec4 clip) {
    vec3 across = normalize(cross(uViewDir.xyz, abs(uViewDir.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0)));
    vec4 clip2 = uViewProj * vec4(world + across * uSpacingValid.x, 1.0);
    return clip.w > 1e-6 && clip2.w > 1e-6
               ? length((clip2.xy / clip2.w - clip.xy / clip.w) * 0.5 * uFrameSize.xy) : 0.0;
}

// Coverage of a fragment `across` pixels from the centre of a line halfPx wide.
float lineCoverage(float across, float halfPx) {
    return clamp(halfPx + 0.5 - abs(across), 0.0, 1.0);
}
