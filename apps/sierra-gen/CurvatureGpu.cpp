// sierra-gen-gpu's part of `curvature --device gpu`: the field from the
// compute shader the overlays use, in a headless EGL context.

#include "Commands.h"

#include <sierra/core/Log.h>
#include <sierra/core/Timer.h>
#include <sierra/gpu/EglContext.h>
#include <sierra/render/CurvatureGpu.h>

namespace sierra::apps {

analysis::CurvatureField computeCurvatureOnGpu(const terrain::Heightfield& field,
                                               const analysis::CurvatureOptions& options) {
    gpu::EglContext context = gpu::EglContext::create({.width = 16, .height = 16});
    log::info("gpu: ", context.renderer(), " (", context.platform(), ")");
    render::CurvatureGpu curvature = render::CurvatureGpu::create(field);
    Stopwatch clock;
    curvature.compute(options, /*tangentPlanes=*/false);
    analysis::CurvatureField result = curvature.read();  // waits for the dispatches
    log::info("curvature on the gpu: ", clock.ms(), " ms with the read-back");
    result.spacingX = field.spacingX();
    result.spacingZ = field.spacingZ();
    return result;
}

}  // namespace sierra::apps
