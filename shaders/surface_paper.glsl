// Surface function: plain paper, for the line and hatch styles without the
// shaded terrain (the document's figures draw lines on white). The terrain
// pass draws this surface unlit (SIERRA_UNLIT, render/Surface.h), so the
// terrain comes out one flat tone (kPaper) whatever the light; fog still
// fades it into the sky.
const vec3 kPaper = vec3(0.96, 0.955, 0.94);

vec3 surfaceAlbedo(vec3 world, Ground g) {
    return kPaper;
}
