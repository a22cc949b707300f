#version 450 core
// Dataset labels of the terrain, per pixel, into float and integer targets
// (engine: render/passes/LabelPass.h):
//   location 0 (RGBA32F): xyz the unit normal of the full-resolution heights
//     at the fragment's ground position (the normal the terrain pass shades
//     with; water flat), times uNormalRotation (identity: world axes; the
//     camera's R: its OpenCV axes), w 1 for terrain; the clear leaves NaN, 0
//   location 1 (R8UI): with SIERRA_ZONE_IDS the zone the zone surface shows
//     there (the texel's own zone of its field, as surfaceAlbedo takes it),
//     else 0; the clear leaves 255 (no terrain)
#include "frame.glsl"
#include "terrain_common.glsl"
#ifdef SIERRA_ZONE_IDS
#include "zone_field.glsl"
#endif

uniform mat3 uNormalRotation;

in vec3 vWorld;
layout(location = 0) out vec4 fragNormal;
layout(location = 1) out uint fragZone;

void main() {
    if (overPadding(vWorld)) discard;
    Ground g = groundAt(vWorld.xz);
    fragNormal = vec4(uNormalRotation * g.normal, 1.0);
#ifdef SIERRA_ZONE_IDS
    int zone;
    uvec2 pair;
    float distance;
    zoneField(zoneMapPosition(vWorld), zone, pair, distance);
    fragZone = uint(zone);
#else
    fragZone = 0u;
#endif
}
