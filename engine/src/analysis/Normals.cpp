#include <sierra/analysis/Normals.h>

#include "Internal.h"

#include <sierra/core/Error.h>

namespace sierra::analysis {

const char* normalMethodName(NormalMethod method) {
    switch (method) {
        case NormalMethod::Edge:
            return "edge";
        case NormalMethod::Triangle:
            return "triangle";
        case NormalMethod::Quad:
            return "quad";
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

void makeWorldGrid(const terrain::Heightfield& field, int threads, WorldGrid& g) {
    SIERRA_CHECK(!field.empty(), "curvature analysis needs a non-empty heightfield");
    g.width = field.width();
    g.height = field.height();
    g.spacingX = field.spacingX();
    g.spacingZ = field.spacingZ();
    g.hasNoData = field.hasMask();
    g.scale = field.verticalScale();
    auto samples = field.samples();
    if (!g.hasNoData) {
        g.raw = samples.data();
        return;
    }
    g.storage.resize(samples.size());
    auto mask = field.mask();
    forRows(g.width, g.height, threads, [&](int j0, int j1) {
        for (size_t k = size_t(j0) * size_t(g.width); k < size_t(j1) * size_t(g.width); ++k)
            g.storage[k] = mask[k] ? samples[k] : NAN;
    });
    g.raw = g.storage.data();
}

}  // namespace detail

NormalField computeNormals(const terrain::Heightfield& field, NormalMethod method, int threads) {
    detail::WorldGrid g;
    detail::makeWorldGrid(field, threads, g);
    NormalField out;
    out.width = g.width;
    out.height = g.height;
    out.normals.resize(size_t(field.sampleCount()));
    detail::dispatchNormalMethod(method, [&]<NormalMethod kMethod>() {
        detail::forRows(g.width, g.height, threads, [&](int j0, int j1) {
            detail::forNormalRows<kMethod>(
                g, j0, j1, [&](int j, const float* ox, const float* oy, const float* oz) {
                    Vec3* o = out.normals.data() + size_t(j) * size_t(g.width);
                    for (int i = 0; i < g.width; ++i) {
                        detail::V3 n = detail::normalized({ox[i], oy[i], oz[i]});
                        o[i] = {n.x, n.y, n.z};
                    }
                });
        });
    });
    return out;
}

}  // namespace sierra::analysis
