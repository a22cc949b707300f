#pragma once
// The camera metadata of dataset outputs as JSON: one file per frame
// (cameraJson) and, for a sequence, one transforms.json in the NeRF /
// instant-ngp convention (transformsJson). The numbers come as plain data
// (facade::cameraRecord fills them from a render::Camera), so this module writes JSON
// without knowing the renderer. The JSON forms are described in
// docs/dataset.md.

#include <sierra/zones/Palette.h>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace sierra::scene {

using Mat3 = std::array<std::array<double, 3>, 3>;  // rows
using Mat4 = std::array<std::array<double, 4>, 4>;  // rows

// Where the terrain's grid lies in its file's reference system
// (terrain::Heightfield::Georeference), and where the camera is in it.
struct CameraGeoreference {
    std::array<double, 6> geoTransform{};  // GDAL's: pixel corners to CRS X, Y
    std::string crsWkt;                    // OGC WKT; "" = unknown
    std::array<double, 3> position{};      // the camera in CRS X, Y and stored height
};

// One frame's camera. Camera axes follow OpenCV: x right, y down, z forward
// (the view direction); a world point p is at R p + t in camera axes.
struct CameraRecord {
    int width = 0, height = 0;  // image size in pixels
    bool orthographic = false;
    // Intrinsics in pixels; pixel (i, j) (column, row from the top-left)
    // covers [i, i + 1) x [j, j + 1) and its centre is at (i + 0.5, j + 0.5).
    // Perspective: (u, v) = (fx x / z + cx, fy y / z + cy). Orthographic: the
    // affine (u, v) = (fx x + cx, fy y + cy), fx = fy = 1 / pixelSize.
    double fx = 0.0, fy = 0.0, cx = 0.0, cy = 0.0;
    double pixelSize = 0.0;    // orthographic: world units per pixel; 0 for perspective
    double fovXDegrees = 0.0;  // perspective: full horizontal and vertical field of view
    double fovYDegrees = 0.0;
    Mat3 rotation{};                         // R, world to camera (OpenCV axes)
    std::array<double, 3> translation{};     // t, world units
    Mat4 view{};                             // the GL view matrix (camera looks down -z, y up)
    Mat4 projection{};                       // the GL projection matrix (clip = P V world)
    double nearPlane = 0.0, farPlane = 0.0;  // world units along the view direction
    std::array<double, 3> position{};        // the camera in world units
    // The terrain's world-to-grid map: sample (i, j) at world (i sx, h vs, j sz).
    double spacingX = 1.0, spacingZ = 1.0, verticalScale = 1.0;
    std::optional<CameraGeoreference> georeference;
};

// The camera JSON of one frame (see docs/dataset.md for its keys).
std::string cameraJson(const CameraRecord& camera);

// One frame of transforms.json: the image's path as the file names it
// (relative to the transforms file's folder) and its camera.
struct TransformsFrame {
    std::string filePath;
    CameraRecord camera;
};
// The instant-ngp transforms.json of a sequence: camera_angle_x, fl_x, fl_y,
// cx, cy, w, h from the first frame, and frames[] with file_path and
// transform_matrix, the 4x4 camera-to-world matrix in the OpenGL / NeRF axes
// (x right, y up, the camera looking down -z). Throws sierra::Error for no
// frames or frames of different sizes.
std::string transformsJson(const std::vector<TransformsFrame>& frames);

// The zone palette beside a zone-id image: zone id -> name and colour.
std::string zonePaletteJson(const zones::Palette& palette);

}  // namespace sierra::scene
