// Surface function: plain paper, for the line and hatch styles without the
// shaded terrain (the document's figures draw lines on white). The albedo
// undoes terrain.frag's Lambert term, so the terrain comes out one flat tone
// (kPaper) whatever the light; fog still fades it into the sky.
const vec3 kPaper = vec3(0.96, 0.955, 0.94);

vec3 surfaceAlbedo(vec3 world, Ground g) {
    float ambient = uSun.w;
    float light = ambient + (1.0 - ambient) * max(dot(g.normal, uSun.xyz), 0.0);
    return kPaper / max(light, 1e-3);
}
