// The compiled half of the Python module `sierra` (python/sierra/__init__.py is
// the other): a renderer over one shared EGL context, the scene's JSON form,
// and the GL-free maps and relief fields, on numpy arrays. Keyword arguments become a scene's
// JSON in Python and are read here by the scene's own strict reader, so a
// Python call and a scene file accept exactly the same keys and values.
//
// Threads: every GL call runs with the GIL released, under the renderer's
// mutex, with the context made current on the calling thread and released
// again afterwards, so any Python thread may use a renderer, one call at a
// time.
#include <sierra/analysis/Relief.h>
#include <sierra/core/Error.h>
#include <sierra/facade/SceneRenderer.h>
#include <sierra/gpu/EglContext.h>
#include <sierra/render/Capture.h>
#include <sierra/scene/SceneJson.h>
#include <sierra/terrain/DemMaps.h>
#include <sierra/terrain/Heightfield.h>
#include <sierra/terrain/HeightfieldIO.h>
#include <sierra/terrain/Padding.h>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

namespace py = pybind11;
using namespace sierra;

namespace {

using FloatGrid = py::array_t<float, py::array::c_style>;

// A float32 C-order (rows, columns) array as a heightfield: rows run along +z,
// columns along +x; NaN samples are no-data. The Python side has already cast
// the dtype and turned masked values into NaN.
terrain::Heightfield toHeightfield(const FloatGrid& heights, double spacingX, double spacingZ) {
    if (heights.ndim() != 2)
        throw Error(msg("heights must be a 2-D array (rows, columns), got ", heights.ndim(),
                        " dimension(s)"));
    const auto rows = heights.shape(0), columns = heights.shape(1);
    if (rows < 2 || columns < 2)
        throw Error(
            msg("heights of ", rows, "x", columns, " samples have no cell: give at least 2x2"));
    if (!(spacingX > 0.0 && spacingZ > 0.0 && std::isfinite(spacingX) && std::isfinite(spacingZ)))
        throw Error(
            msg("spacing must be two positive numbers, got (", spacingX, ", ", spacingZ, ")"));
    terrain::checkFieldSize("heights", columns, rows);
    terrain::Heightfield field{int(columns), int(rows)};
    const float* src = heights.data();
    std::vector<uint8_t> mask;
    const size_t n = size_t(rows) * size_t(columns);
    auto samples = field.samples();
    for (size_t k = 0; k < n; ++k) {
        const float v = src[k];
        if (std::isfinite(v)) {
            samples[k] = v;
        } else {
            if (mask.empty()) mask.assign(n, 1);
            mask[k] = 0;
            samples[k] = 0.0f;
        }
    }
    if (!mask.empty()) {
        if (std::find(mask.begin(), mask.end(), 1) == mask.end())
            throw Error("heights hold no finite sample");
        field.setMask(std::move(mask));
        // As the loaders do: voids take heights grown from their valid
        // neighbours, so the surface has no cliff into a fill value.
        terrain::fillNoData(field);
    }
    field.setSpacing(float(spacingX), float(spacingZ));
    return field;
}

py::array_t<uint8_t> toArray(const gpu::Image& image) {
    py::array_t<uint8_t> out({image.height, image.width, 4});
    std::copy(image.rgba.begin(), image.rgba.end(), out.mutable_data());
    return out;
}

py::array_t<float> toArray(const std::vector<float>& values, int rows, int columns) {
    py::array_t<float> out({rows, columns});
    std::copy(values.begin(), values.end(), out.mutable_data());
    return out;
}

// One EGL context for the frames of this renderer. Its pbuffer takes the
// frame's size, so frames are drawn as sierra-render draws them (into the
// pbuffer; an offscreen target differs from it by a level in the odd pixel on
// llvmpipe); a frame of another size gets a new context.
class Renderer {
  public:
    Renderer() { context(640, 360); }

    ~Renderer() {
        py::gil_scoped_release unlocked;
        std::lock_guard lock(mutex_);
        dropScene();
    }

    // Renders frame `frame` of the scene (JSON text) for `heights` (or the
    // scene's own terrain when None): "rgba" gives (height, width, 4) uint8,
    // "depth" (height, width) float32 (NaN where no terrain).
    py::object render(const std::string& sceneText, std::optional<FloatGrid> heights,
                      double spacingX, double spacingZ, const std::string& output, int frame) {
        if (output != "rgba" && output != "depth")
            throw Error(msg("output must be \"rgba\" or \"depth\", got \"", output, "\""));
        scene::Scene s =
            scene::sceneFromJson(scene::parseJson(sceneText, "the scene"), "the scene");
        scene::validateScene(s);
        std::optional<terrain::Heightfield> grid;
        if (heights) {
            grid = toHeightfield(*heights, spacingX, spacingZ);
            if (s.terrain.heightmap.empty()) s.terrain.heightmap = "the array";
        }
        gpu::Image image;
        render::DepthImage depth;
        {
            py::gil_scoped_release unlocked;
            std::lock_guard lock(mutex_);
            dropScene();
            context(s.output.width, s.output.height);
            context_->makeCurrent();
            try {
                last_ = std::make_unique<facade::SceneRenderer>(
                    facade::SceneRenderer::create(s, context_, grid ? &*grid : nullptr));
                if (output == "rgba")
                    image = last_->frame(frame);
                else
                    depth = last_->depth(frame);
            } catch (...) {
                last_.reset();
                context_->release();
                throw;
            }
            context_->release();
        }
        if (output == "rgba") return toArray(image);
        return toArray(depth.depth, depth.height, depth.width);
    }

    std::string renderer() const { return context_->renderer(); }
    std::string platform() const { return context_->platform(); }

  private:
    // The GL objects of the last scene go with their context current.
    void dropScene() {
        if (!last_) return;
        context_->makeCurrent();
        last_.reset();
        context_->release();
    }

    // Makes sure the context's pbuffer is width x height (no scene held).
    void context(int width, int height) {
        if (context_ && context_->width() == width && context_->height() == height) return;
        context_.reset();
        context_ = std::make_shared<gpu::EglContext>(
            gpu::EglContext::create({.width = width, .height = height}));
        context_->release();
    }

    std::shared_ptr<gpu::EglContext> context_;
    std::unique_ptr<facade::SceneRenderer> last_;
    std::mutex mutex_;
};

}  // namespace

PYBIND11_MODULE(_sierra, m) {
    m.doc() = "Sierra's compiled core; use the `sierra` package.";
    static py::exception<Error> error(m, "Error");
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const Error& e) {
            error(e.what());
        }
    });

    py::class_<Renderer>(m, "_Renderer")
        .def(py::init<>())
        .def("render", &Renderer::render, py::arg("scene"), py::arg("heights"),
             py::arg("spacing_x"), py::arg("spacing_z"), py::arg("output"), py::arg("frame"))
        .def_property_readonly("gl_renderer", &Renderer::renderer)
        .def_property_readonly("platform", &Renderer::platform);

    // The scene text for JSON text: every key checked, absent keys at their
    // defaults, written as scene files are.
    m.def("scene_text", [](const std::string& text) {
        scene::Scene s = scene::sceneFromJson(scene::parseJson(text, "the scene"), "the scene");
        scene::validateScene(s);
        return scene::sceneToText(s);
    });

    // One scalar field of a DEM (terrain/DemMaps.h) by the map command's name.
    m.def(
        "dem_field",
        [](const FloatGrid& heights, double spacingX, double spacingZ, const std::string& name,
           bool computeEdges, float azimuth, float altitude, float zFactor) {
            terrain::Heightfield field = toHeightfield(heights, spacingX, spacingZ);
            terrain::DemFieldDesc desc{.computeEdges = computeEdges,
                                       .azimuth = azimuth,
                                       .altitude = altitude,
                                       .zFactor = zFactor};
            if (!terrain::parseDemField(name, &desc.field))
                throw Error(msg("unknown map \"", name, "\""));
            if (name.rfind("curvature", 0) == 0) desc.stencil = terrain::Stencil::EvansYoung;
            std::vector<float> values;
            {
                py::gil_scoped_release unlocked;
                values = terrain::demField(field, desc);
            }
            return toArray(values, field.height(), field.width());
        },
        py::arg("heights"), py::arg("spacing_x"), py::arg("spacing_z"), py::arg("name"),
        py::arg("compute_edges"), py::arg("azimuth"), py::arg("altitude"), py::arg("z_factor"));

    // The relief lighting fields (analysis/Relief.h) over the whole grid.
    m.def(
        "relief_field",
        [](const FloatGrid& heights, double spacingX, double spacingZ, const std::string& name,
           int directions, float radius, float azimuth, float altitude, float sunSize) {
            terrain::Heightfield field = toHeightfield(heights, spacingX, spacingZ);
            analysis::HorizonOptions options{.directions = directions, .radius = radius};
            std::vector<float> values;
            {
                py::gil_scoped_release unlocked;
                if (name == "shadow")
                    values = analysis::sunVisibility(
                        field, {.azimuth = azimuth, .altitude = altitude, .diameter = sunSize},
                        options);
                else if (name == "sky-view")
                    values = analysis::skyViewFactor(field, options);
                else if (name == "sky-light")
                    values = analysis::skyLight(field, options);
                else if (name == "openness-positive")
                    values = analysis::opennessPositive(field, options);
                else if (name == "openness-negative")
                    values = analysis::opennessNegative(field, options);
                else
                    throw Error(msg("unknown relief field \"", name, "\""));
            }
            return toArray(values, field.height(), field.width());
        },
        py::arg("heights"), py::arg("spacing_x"), py::arg("spacing_z"), py::arg("name"),
        py::arg("directions"), py::arg("radius"), py::arg("azimuth"), py::arg("altitude"),
        py::arg("sun_size"));

    m.def("read_png", [](const std::string& path) { return toArray(render::readPng(path)); });
}
