#include <sierra/facade/CameraRecord.h>

#include <sierra/core/Error.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace sierra::facade {

namespace {

scene::Mat4 rowsOf(const glm::mat4& m) {
    scene::Mat4 out{};
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c)
            out[size_t(r)][size_t(c)] = double(m[c][r]);  // glm: m[column][row]
    return out;
}

}  // namespace

glm::mat3 openCvRotation(const render::Camera& camera) {
    const glm::mat3 flip(glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, -1.0f, 0.0f),
                         glm::vec3(0.0f, 0.0f, -1.0f));
    return flip * glm::mat3(camera.view());
}

std::array<double, 3> worldToCrs(const glm::dvec3& world, const terrain::Heightfield& field) {
    SIERRA_CHECK(field.georeference().has_value(), "worldToCrs needs a georeferenced terrain");
    const auto& g = field.georeference()->geoTransform;
    // World x = i sx at sample i, whose centre is pixel column i + 0.5.
    const double col = world.x / double(field.spacingX()) + 0.5;
    const double row = world.z / double(field.spacingZ()) + 0.5;
    return {g[0] + col * g[1] + row * g[2], g[3] + col * g[4] + row * g[5],
            world.y / double(field.verticalScale())};
}

scene::CameraRecord cameraRecord(const render::Camera& camera, int width, int height,
                                 const terrain::Heightfield& field) {
    SIERRA_CHECK(width > 0 && height > 0, "a camera record needs a frame size, got ", width, "x",
                 height);
    scene::CameraRecord r;
    r.width = width;
    r.height = height;
    r.orthographic = camera.projection == render::Projection::Orthographic;
    const float aspect = float(width) / float(height);
    // Square pixels: the GL projection's horizontal extent is the vertical
    // one times the aspect ratio, so fx = fy.
    if (r.orthographic) {
        r.pixelSize = double(camera.orthoHeight) / double(height);
        r.fx = r.fy = 1.0 / r.pixelSize;
    } else {
        const double tanHalf = std::tan(glm::radians(double(camera.fovYDegrees)) * 0.5);
        r.fx = r.fy = 0.5 * double(height) / tanHalf;
        r.fovYDegrees = double(camera.fovYDegrees);
        r.fovXDegrees = glm::degrees(2.0 * std::atan(tanHalf * double(aspect)));
    }
    r.cx = 0.5 * double(width);
    r.cy = 0.5 * double(height);
    const glm::mat4 view = camera.view();
    r.view = rowsOf(view);
    r.projection = rowsOf(camera.projectionMatrix(aspect));
    // OpenCV's camera axes are GL's with y and z turned round (y down, z forward).
    const glm::mat3 rotation = openCvRotation(camera);
    for (int row = 0; row < 3; ++row) {
        const double flip = row == 0 ? 1.0 : -1.0;
        for (int c = 0; c < 3; ++c) r.rotation[size_t(row)][size_t(c)] = double(rotation[c][row]);
        r.translation[size_t(row)] = flip * r.view[size_t(row)][3];
    }
    r.nearPlane = camera.nearPlane;
    r.farPlane = camera.farPlane;
    r.position = {camera.position.x, camera.position.y, camera.position.z};
    r.spacingX = field.spacingX();
    r.spacingZ = field.spacingZ();
    r.verticalScale = field.verticalScale();
    if (const auto& geo = field.georeference()) {
        r.georeference =
            scene::CameraGeoreference{.geoTransform = geo->geoTransform,
                                      .crsWkt = geo->crsWkt,
                                      .position = worldToCrs(glm::dvec3(camera.position), field)};
    }
    return r;
}

}  // namespace sierra::facade
