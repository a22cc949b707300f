#include <sierra/render/SceneView.h>

#include <sierra/core/Error.h>
#include <sierra/scene/Terrain.h>

namespace sierra::render {

glm::vec3 toGlm(const scene::Vec3& v) { return {v.x, v.y, v.z}; }

std::vector<Camera> sceneCameras(const scene::Scene& s, const SceneBounds& bounds) {
    const scene::CameraDesc& c = s.camera;
    float aspect = float(s.output.width) / float(s.output.height);
    Projection projection =
        c.projection == scene::Projection::Orthographic ? Projection::Orthographic : Projection::Perspective;
    glm::vec3 target = c.target ? toGlm(*c.target) : defaultTarget(bounds);
    int frames = s.path.frames;
    std::vector<Camera> cameras;
    switch (s.path.type) {
    case scene::PathType::Orbit: {
        SIERRA_CHECK(!c.position, "an orbit path sets the camera position itself: leave out the camera position");
        cameras = orbitPath(bounds, frames, aspect, c.fov, c.elevation.value_or(30.0f));
        for (Camera& cam : cameras) {
            if (c.target) {
                cam.position += target - cam.target;
                cam.target = target;
            }
            if (c.distance) cam.position = cam.target + glm::normalize(cam.position - cam.target) * *c.distance;
            cam.projection = projection;
            if (projection == Projection::Orthographic) {
                Camera framed = framedCamera(bounds, {.target = cam.target, .fovYDegrees = c.fov,
                                                      .projection = projection, .aspect = aspect});
                cam.orthoHeight = framed.orthoHeight;
            }
            fitClipPlanes(cam, bounds);
        }
        break;
    }
    case scene::PathType::Flyover:
        cameras = flyoverPath(bounds, frames, c.fov);
        break;
    case scene::PathType::Keyframes: {
        std::vector<Keyframe> keys;
        for (const scene::Keyframe& k : s.path.keyframes)
            keys.push_back({.time = k.time, .position = toGlm(k.position), .target = toGlm(k.target)});
        cameras = keyframePath(bounds, keys, frames, c.fov);
        break;
    }
    case scene::PathType::None: {
        Camera cam;
        if (c.position) {
            cam.position = toGlm(*c.position);
            cam.target = target;
            cam.fovYDegrees = c.fov;
            cam.projection = projection;
            if (projection == Projection::Orthographic)
                cam.orthoHeight = framedCamera(bounds, {.target = target, .projection = projection, .aspect = aspect})
                                      .orthoHeight;
            fitClipPlanes(cam, bounds);
        } else {
            cam = framedCamera(bounds, {.target = target,
                                        .azimuthDeg = c.azimuth.value_or(225.0f),
                                        .elevationDeg = c.elevation.value_or(30.0f),
                                        .fovYDegrees = c.fov,
                                        .projection = projection,
                                        .aspect = aspect,
                                        .distance = c.distance.value_or(0.0f)});
        }
        cameras.assign(size_t(frames), cam);
        break;
    }
    }
    for (Camera& cam : cameras) cam.forward();  // throws for position == target
    return cameras;
}

Lighting sceneLighting(const scene::LightingDesc& l, bool transparent) {
    Lighting out;
    out.sunDirection = compassDirection(l.sunAzimuth, l.sunAltitude);
    out.ambient = l.ambient;
    out.fogDensity = l.fog ? *l.fog : -1.0f;
    out.sky = {l.sky.r, l.sky.g, l.sky.b};
    out.transparent = transparent;
    return out;
}

TerrainDesc sceneTerrainDesc(const scene::Scene& s, const terrain::Heightfield& field, float seaLevel) {
    return {.field = &field,
            .seaLevel = seaLevel,
            .threads = s.lod.threads,
            .metric = scene::metricHeights(s.terrain),
            .treeLine = s.style.treeLine,
            .snowLine = s.style.snowLine,
            .cpt = s.style.cpt};
}

DrawOptions sceneDrawOptions(const scene::Scene& s) {
    return {.lod = s.lod.mode == scene::LodMode::Full ? Lod::Full : Lod::Sbt,
            .tau = s.lod.tau,
            .geomorph = s.lod.geomorph,
            .cull = s.lod.cull,
            .wireframe = s.style.wireframe,
            .polygons = s.style.polygons,
            .points = s.style.points,
            .colourBy = s.style.colourBy == "level" ? 1 : s.style.colourBy == "error" ? 2 : 0,
            .threads = s.lod.threads,
            .lighting = sceneLighting(s.lighting, s.output.alpha)};
}

}  // namespace sierra::render
