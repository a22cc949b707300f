#pragma once
// Analytic surfaces sampled onto heightfields for the analysis tests.

#include <sierra/terrain/Heightfield.h>

#include <functional>

namespace sierra::analysis::test {

// A w x h grid with spacing `spacing` on both axes and vertical scale `vscale`
// whose world height at world (x, z) is f(x, z); x = i * spacing + x0,
// z = j * spacing + z0 (so the origin can sit anywhere in the grid).
inline terrain::Heightfield sampleSurface(int w, int h, double spacing, double vscale,
                                          const std::function<double(double, double)>& f,
                                          double x0 = 0.0, double z0 = 0.0) {
    terrain::Heightfield field(w, h);
    field.setSpacing(float(spacing), float(spacing));
    field.setVerticalScale(float(vscale));
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i)
            field.at(i, j) = float(f(i * spacing + x0, j * spacing + z0) / vscale);
    return field;
}

}  // namespace sierra::analysis::test
