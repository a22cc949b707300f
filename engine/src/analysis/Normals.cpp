#include <sierra/analysis/Normals.h>

#include "Internal.h"

#include <sierra/core/Error.h>

namespace sierra::analysis {

const char* normalMethodName(NormalMethod method) {
    switch (method) {
        case NormalMethod::Edge: return "edge";
        case NormalMethod::Triangle: return "triangle";
        case NormalMethod::Quad: return "quad";
    }
    return "?";
}

NormalMethod parseNormalMethod(const std::string& name) {
    if (name == "edge") return NormalMethod::Edge;
    if (name == "triangle") return NormalMethod::Triangle;
    if (name == "quad") return NormalMethod::Quad;
    throw Error(msg("unknown normal method '", name, "' (expected edge, triangle or quad)"));
}

namespace detail {

WorldGrid makeWorldGrid(const terrain::Heightfield& field, int threads) {
    SIERRA_CHECK(!field.empty(), "curvature analysis needs a non-empty heightfield");
    WorldGrid g;
    g.width = field.width();
    g.height = field.height();
    g.spacingX = field.spacingX();
    g.spacingZ = field.spacingZ();
    g.hasNoData = field.hasMask();
    g.y.resize(size_t(field.sampleCount()));
    const float scale = field.verticalScale();
    auto samples = field.samples();
    auto mask = field.mask();
    forRows(g.width, g.height, threads, [&](int j0, int j1) {
        for (size_t k = size_t(j0) * size_t(g.width); k < size_t(j1) * size_t(g.width); ++k)
            g.y[k] = (mask.empty() || mask[k]) ? samples[k] * scale : NAN;
    });
    return g;
}

}  // namespace detail

NormalField computeNormals(const terrain::Heightfield& field, NormalMethod method, int threads) {
    detail::WorldGrid g = detail::makeWorldGrid(field, threads);
    NormalField out;
    out.width = g.width;
    out.height = g.height;
    out.normals.resize(g.y.size());
    detail::dispatchNormalMethod(method, [&]<NormalMethod kMethod>() {
        detail::forRows(g.width, g.height, threads, [&](int j0, int j1) {
            detail::forNormalSums<kMethod>(g, j0, j1, [&](int i, int j, detail::V3 s) {
                detail::V3 n = detail::normalized(s);
                out.normals[size_t(j) * size_t(g.width) + size_t(i)] = {n.x, n.y, n.z};
            });
        });
    });
    return out;
}

}  // namespace sierra::analysis
