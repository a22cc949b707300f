// Renders one frame of a DEM with Sierra and writes it as a PNG:
//   hello_terrain DEM.tif frame.png
// Any heightmap sierra-render reads will do; with no arguments a generated
// fractal terrain goes to hello.png.
#include <sierra/core/Error.h>
#include <sierra/facade/SceneRenderer.h>
#include <sierra/render/Capture.h>

#include <cstdio>

int main(int argc, char** argv) {
    sierra::scene::Scene scene;
    if (argc > 1) scene.terrain.heightmap = argv[1];
    scene.output.width = 960;
    scene.output.height = 540;
    scene.camera.azimuth = 200.0f;  // looking from the south-south-west
    scene.camera.elevation = 30.0f;
    const char* out = argc > 2 ? argv[2] : "hello.png";
    try {
        auto renderer = sierra::facade::SceneRenderer::create(scene);
        sierra::render::writePng(out, renderer.frame());
        std::printf("%s\n%d triangles -> %s\n", renderer.description().c_str(),
                    renderer.lastStats().triangles, out);
    } catch (const sierra::Error& e) {
        std::fprintf(stderr, "hello_terrain: %s\n", e.what());
        return 1;
    }
    return 0;
}
