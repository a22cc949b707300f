#include <sierra/scene/CameraJson.h>

#include <sierra/core/Error.h>

#include <nlohmann/json.hpp>

#include <numbers>

namespace sierra::scene {

namespace {

using Json = nlohmann::ordered_json;

template <size_t N>
Json rows(const std::array<std::array<double, N>, N>& m) {
    Json out = Json::array();
    for (const auto& row : m) out.push_back(Json(row));
    return out;
}

// The inverse of a rigid GL view matrix [Q | s; 0 1]: [Q^T | -Q^T s; 0 1],
// the camera-to-world matrix in GL's camera axes (x right, y up, looking down -z).
Mat4 cameraToWorld(const Mat4& view) {
    Mat4 out{};
    for (int r = 0; r < 3; ++r) {
        double shift = 0.0;
        for (int c = 0; c < 3; ++c) {
            out[size_t(r)][size_t(c)] = view[size_t(c)][size_t(r)];
            shift -= view[size_t(c)][size_t(r)] * view[size_t(c)][3];
        }
        out[size_t(r)][3] = shift;
    }
    out[3] = {0.0, 0.0, 0.0, 1.0};
    return out;
}

}  // namespace

std::string cameraJson(const CameraRecord& c) {
    Json j;
    j["width"] = c.width;
    j["height"] = c.height;
    j["model"] = c.orthographic ? "orthographic" : "perspective";
    j["K"] = rows(Mat3{{{c.fx, 0.0, c.cx}, {0.0, c.fy, c.cy}, {0.0, 0.0, 1.0}}});
    j["fx"] = c.fx;
    j["fy"] = c.fy;
    j["cx"] = c.cx;
    j["cy"] = c.cy;
    j["pixel_centre"] = 0.5;  // pixel (i, j) is centred at (i + 0.5, j + 0.5)
    if (c.orthographic) {
        j["pixel_size"] = c.pixelSize;
    } else {
        j["fov_x_degrees"] = c.fovXDegrees;
        j["fov_y_degrees"] = c.fovYDegrees;
    }
    j["R"] = rows(c.rotation);
    j["t"] = c.translation;
    j["near"] = c.nearPlane;
    j["far"] = c.farPlane;
    j["gl_view"] = rows(c.view);
    j["gl_projection"] = rows(c.projection);
    j["position"] = c.position;
    Json terrain;
    terrain["spacing"] = {c.spacingX, c.spacingZ};
    terrain["vertical_scale"] = c.verticalScale;
    if (c.georeference) {
        terrain["geotransform"] = c.georeference->geoTransform;
        terrain["crs_wkt"] = c.georeference->crsWkt;
        j["position_crs"] = c.georeference->position;
    }
    j["terrain"] = terrain;
    return j.dump(2) + "\n";
}

std::string transformsJson(const std::vector<TransformsFrame>& frames) {
    SIERRA_CHECK(!frames.empty(), "transforms.json needs at least one frame");
    const CameraRecord& first = frames.front().camera;
    Json j;
    if (first.orthographic) {
        j["orthographic"] = true;
        j["pixel_size"] = first.pixelSize;
    } else {
        j["camera_angle_x"] = first.fovXDegrees * std::numbers::pi / 180.0;
        j["camera_angle_y"] = first.fovYDegrees * std::numbers::pi / 180.0;
    }
    j["fl_x"] = first.fx;
    j["fl_y"] = first.fy;
    j["cx"] = first.cx;
    j["cy"] = first.cy;
    j["w"] = first.width;
    j["h"] = first.height;
    Json list = Json::array();
    for (const TransformsFrame& f : frames) {
        const CameraRecord& c = f.camera;
        SIERRA_CHECK(c.width == first.width && c.height == first.height &&
                         c.orthographic == first.orthographic && c.fx == first.fx &&
                         c.fy == first.fy,
                     "transforms.json holds one camera model; frame ", f.filePath, " is ", c.width,
                     "x", c.height, " with fx ", c.fx, ", the first ", first.width, "x",
                     first.height, " with fx ", first.fx);
        list.push_back(
            {{"file_path", f.filePath}, {"transform_matrix", rows(cameraToWorld(c.view))}});
    }
    j["frames"] = list;
    return j.dump(2) + "\n";
}

std::string zonePaletteJson(const zones::Palette& palette) {
    Json zones = Json::array();
    for (size_t id = 0; id < palette.surfaces.size(); ++id) {
        const zones::SurfaceType& s = palette.surfaces[id];
        zones.push_back(
            {{"id", id},
             {"name", s.name},
             {"colour", zones::colourHex(s.colour)},
             {"rgb", {(s.colour >> 16) & 255u, (s.colour >> 8) & 255u, s.colour & 255u}}});
    }
    Json j;
    j["zones"] = zones;
    return j.dump(2) + "\n";
}

}  // namespace sierra::scene
