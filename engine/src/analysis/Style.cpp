#include <sierra/analysis/Style.h>

#include <vector>

namespace sierra::analysis {

bool StyleLayers::enable(std::string_view name) {
    if (name == "shaded")
        shaded = true;
    else if (name == "lines")
        lines = true;
    else if (name == "hatch")
        hatch = true;
    else if (name == "contours")
        contours = true;
    else
        return false;
    return true;
}

LineOptions lineOptions(const StyleParams& style) {
    return {.threshold = style.lines.threshold,
            .minVertices = style.lines.minLength,
            .polarity = style.lines.polarity,
            .blended = style.lines.blended};
}

float autoCurvatureTarget(const StyleParams& style) {
    return style.layers.lines ? style.lines.threshold : 1.0f;
}

float autoCurvatureScale(const CurvatureField& field, const StyleParams& style) {
    std::vector<float> largest = largestMagnitudes(field);
    return scaleToReach(topFivePercent(largest), style.curvature.scale, autoCurvatureTarget(style));
}

}  // namespace sierra::analysis
