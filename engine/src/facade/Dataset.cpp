#include <sierra/facade/Dataset.h>

#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/core/Npy.h>
#include <sierra/facade/CameraRecord.h>
#include <sierra/facade/SceneView.h>
#include <sierra/render/Capture.h>
#include <sierra/render/Exr.h>
#include <sierra/scene/Assets.h>
#include <sierra/scene/PaletteJson.h>
#include <sierra/zones/Palette.h>

#include <filesystem>

namespace sierra::facade {

namespace {

void writeNormals(const std::string& path, const render::LabelImage& labels, bool half) {
    if (lowerExtension(path) == ".exr") {
        writeFileAtomic(path, render::encodeExr({.width = labels.width,
                                                 .height = labels.height,
                                                 .channels = {"R", "G", "B"},
                                                 .values = labels.normals,
                                                 .precision = half ? render::ExrPrecision::Half
                                                                   : render::ExrPrecision::Float}));
        return;
    }
    const int shape[] = {labels.height, labels.width, 3};
    writeFileAtomic(path, half ? encodeNpyFloat16(shape, labels.normals)
                               : encodeNpyFloat32(shape, labels.normals));
}

}  // namespace

DatasetWriter::DatasetWriter(const scene::Scene& scene, bool sequence)
    : output_(scene.output), sequence_(sequence) {
    if (!scene.zones.map.empty())
        palette_ = scene.zones.palette.empty() ? scene::assetPath("palettes/default.json")
                                               : scene.zones.palette;
}

bool DatasetWriter::any() const {
    const scene::OutputDesc& o = output_;
    return !o.depth.empty() || !o.normals.empty() || !o.zoneIds.empty() || !o.mask.empty() ||
           !o.camera.empty() || !o.transforms.empty();
}

void DatasetWriter::checkLocations() const {
    const scene::OutputDesc& o = output_;
    for (const std::string* path :
         {&o.depth, &o.normals, &o.zoneIds, &o.mask, &o.camera, &o.transforms})
        if (!path->empty()) ensureWritableLocation(*path);
    if (!o.zoneIds.empty()) ensureWritableLocation(palettePath(o.zoneIds));
}

std::string DatasetWriter::framePath(const std::string& base, int k) const {
    return sequence_ ? render::sequencePath(base, k) : base;
}

std::string DatasetWriter::palettePath(const std::string& zoneIds) {
    return std::filesystem::path(zoneIds).replace_extension(".json").string();
}

void DatasetWriter::write(render::TerrainRenderer& renderer, const terrain::Heightfield& field,
                          int k, const render::Camera& camera, int width, int height,
                          const render::DrawOptions& options) {
    const scene::OutputDesc& o = output_;
    if (!o.depth.empty()) {
        render::DepthImage depth = renderer.renderDepth(camera, width, height, options);
        writeFileAtomic(framePath(o.depth, k),
                        encodeNpyFloat32(depth.height, depth.width, depth.depth));
    }
    const scene::CameraRecord record = cameraRecord(camera, width, height, field);
    if (!o.normals.empty() || !o.zoneIds.empty() || !o.mask.empty()) {
        SIERRA_CHECK(o.zoneIds.empty() || renderer.hasZoneIds(), "--zones-out ", o.zoneIds,
                     " needs the zone surface, and the renderer has none");
        render::LabelImage labels = renderer.renderLabels(
            camera, width, height, options,
            o.normalsSpace == "camera" ? openCvRotation(camera) : glm::mat3(1.0f));
        if (!o.normals.empty())
            writeNormals(framePath(o.normals, k), labels, o.normalsPrecision == "float16");
        if (!o.mask.empty())
            writeFileAtomic(framePath(o.mask, k),
                            render::encodePngGrey8(width, height, labels.mask,
                                                   pngCompression(o.pngCompression)));
        if (!o.zoneIds.empty()) {
            writeFileAtomic(framePath(o.zoneIds, k),
                            render::encodePngGrey8(width, height, labels.zones,
                                                   pngCompression(o.pngCompression)));
            if (!paletteWritten_) {
                writeFileAtomic(palettePath(o.zoneIds),
                                scene::zonePaletteJson(scene::loadPalette(palette_, false)));
                paletteWritten_ = true;
            }
        }
    }
    if (!o.camera.empty()) writeFileAtomic(framePath(o.camera, k), scene::cameraJson(record));
    if (!o.transforms.empty()) {
        // file_path relative to the transforms file's folder, as instant-ngp reads it.
        const std::filesystem::path dir = std::filesystem::absolute(o.transforms).parent_path();
        const std::filesystem::path image = std::filesystem::absolute(framePath(o.frame, k));
        frames_.push_back({image.lexically_relative(dir).generic_string(), record});
    }
}

void DatasetWriter::finish() {
    if (output_.transforms.empty() || frames_.empty()) return;
    writeFileAtomic(output_.transforms, scene::transformsJson(frames_));
}

}  // namespace sierra::facade
