#pragma once
// The numbers of a frame's camera for dataset outputs (scene::CameraRecord,
// written as JSON by scene/CameraJson.h): intrinsics K and world-to-camera
// R|t in OpenCV's convention, the GL view and projection matrices, and the
// camera's position in the terrain's reference system when it has one.

#include <sierra/render/Camera.h>
#include <sierra/scene/CameraJson.h>
#include <sierra/terrain/Heightfield.h>

namespace sierra::facade {

// The record of `camera` drawing a width x height frame over `field` (the
// terrain as loaded: its spacing, vertical scale and georeference map world
// units to the grid and to the file's reference system). The camera's depth
// at pixel (u, v) (DepthImage: distance along the view direction) is the z of
// the camera-axes point K^-1 (u, v, 1) z for perspective, (K^-1 (u, v, 1))
// with z = depth for orthographic; the world point is then R^T (p - t).
scene::CameraRecord cameraRecord(const render::Camera& camera, int width, int height,
                                 const terrain::Heightfield& field);

// R of the record: the world-to-camera rotation into OpenCV's axes (x right,
// y down, z forward), GL's view rotation with y and z turned round.
glm::mat3 openCvRotation(const render::Camera& camera);

// The CRS position (X, Y, stored height) of world point `world` over `field`
// (which must have a georeference): grid position (x / sx, z / sz) in
// samples, through the geotransform at the samples' pixel centres.
std::array<double, 3> worldToCrs(const glm::dvec3& world, const terrain::Heightfield& field);

}  // namespace sierra::facade
