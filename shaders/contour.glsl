// Contour edges (render/passes/ContourPass.h), shared by the in-memory and
// the tiled terrain's fragment stages: the view-dependent silhouettes, where
// s = dot(normal, towards the eye) changes sign. s comes from the vertices
// (full-resolution normals) interpolated across each triangle, so its zero
// crossings are clean lines at the mesh's scale (the same s per fragment,
// from this fragment's normal, breaks them into sub-pixel specks where the
// grid is finer than the pixels); |s| / fwidth(s) is the distance to the
// crossing in pixels, and the line covers what lies within half the width,
// antialiased over one pixel.
uniform float uContourWidth;  // pixels, > 0
uniform vec4 uContourColour;  // RGBA 0..1

// `colour` under the contour edge through the zero crossing of s.
vec3 withContour(vec3 colour, float s) {
    float pixels = abs(s) / max(fwidth(s), 1e-6);
    float coverage = clamp(0.5 * uContourWidth + 0.5 - pixels, 0.0, 1.0);
    return mix(colour, uContourColour.rgb, uContourColour.a * coverage);
}
