// Line tracing on a sine ridge (one line per crest) and invariants on
// fractal terrain (no segment twice, no short line, steps between neighbours).
#include <sierra/analysis/Lines.h>
#include <sierra/core/Error.h>
#include <sierra/terrain/DiamondSquare.h>

#include "analysis_test_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>
#include <utility>

using namespace sierra;
using namespace sierra::analysis;
using sierra::analysis::test::sampleSurface;

namespace {

// A sin(k x) with period 16 samples: crests at x = 4 + 16 n, troughs at
// x = 12 + 16 n, running along z. 65 x 41 samples: crests at 4, 20, 36, 52.
terrain::Heightfield sineRidge() {
    const double A = 5.0, k = 2 * std::numbers::pi / 16.0;
    return sampleSurface(65, 41, 1.0, 1.0, [&](double x, double) { return A * std::sin(k * x); });
}

using Segment = std::pair<std::pair<float, float>, std::pair<float, float>>;

// Every segment of every polyline, undirected; fails the test on a repeat.
std::set<Segment> uniqueSegments(const LineSet& lines) {
    std::set<Segment> seen;
    for (size_t p = 0; p < lines.polylineCount(); ++p) {
        auto poly = lines.polyline(p);
        for (size_t k = 1; k < poly.size(); ++k) {
            std::pair a{poly[k - 1].x, poly[k - 1].z}, b{poly[k].x, poly[k].z};
            Segment s = a < b ? Segment{a, b} : Segment{b, a};
            EXPECT_TRUE(seen.insert(s).second) << "segment drawn twice in polyline " << p;
        }
    }
    return seen;
}

}  // namespace

TEST(AnalysisLines, SineRidgeGivesOneLinePerCrest) {
    auto field = sineRidge();
    for (CurvatureMethod m : {CurvatureMethod::TwoNormal, CurvatureMethod::ThreeNormal,
                              CurvatureMethod::ThreeVertex, CurvatureMethod::EdgeAngle}) {
        // Signed values and Ridges: only the crests count. The threshold sits
        // between the crest column and its neighbours (cos(2 pi/16) = 0.92 of it).
        auto c = computeCurvature(field, {.method = m, .signedValues = true});
        float crest = std::fabs(c.at(20, 20, 0));
        ASSERT_GT(crest, 0.0f);
        LineOptions o{
            .threshold = 0.96f * crest, .minVertices = 10, .polarity = LinePolarity::Ridges};
        auto lines = traceLines(c, o);
        ASSERT_EQ(lines.polylineCount(), 4u) << curvatureMethodName(m);
        std::set<int> columns;
        for (size_t p = 0; p < lines.polylineCount(); ++p) {
            auto poly = lines.polyline(p);
            EXPECT_GE(int(poly.size()), o.minVertices);
            EXPECT_EQ(poly.size(), 41u) << "a crest line runs the whole grid";
            for (auto& v : poly) {
                EXPECT_EQ(v.x, poly[0].x) << "the line stays on its crest";
                EXPECT_GT(v.alpha, 0.0f);
                EXPECT_LE(v.alpha, 1.0f);
            }
            for (size_t k = 1; k < poly.size(); ++k)
                EXPECT_EQ(std::fabs(poly[k].z - poly[k - 1].z), 1.0f);
            columns.insert(int(poly[0].x));
        }
        EXPECT_EQ(columns, (std::set<int>{4, 20, 36, 52})) << curvatureMethodName(m);
        uniqueSegments(lines);

        // Unsigned: crests and troughs; Valleys: the troughs only.
        auto unsignedField = computeCurvature(field, {.method = m});
        EXPECT_EQ(traceLines(unsignedField, {.threshold = o.threshold, .minVertices = 10})
                      .polylineCount(),
                  8u);
        EXPECT_EQ(
            traceLines(
                c, {.threshold = o.threshold, .minVertices = 10, .polarity = LinePolarity::Valleys})
                .polylineCount(),
            4u);
        // A minimum longer than the grid keeps nothing.
        EXPECT_EQ(
            traceLines(
                c, {.threshold = o.threshold, .minVertices = 42, .polarity = LinePolarity::Ridges})
                .polylineCount(),
            0u);
    }
}

TEST(AnalysisLines, BlendedSineRidgeFollowsTheCrests) {
    auto field = sineRidge();
    auto c =
        computeCurvature(field, {.method = CurvatureMethod::ThreeVertex, .signedValues = true});
    float crest = std::fabs(c.at(20, 20, 0));
    for (float step : {1.0f, 0.5f}) {
        LineOptions o{.threshold = 0.96f * crest,
                      .minVertices = 10,
                      .polarity = LinePolarity::Ridges,
                      .blended = true,
                      .step = step};
        auto lines = traceLines(c, o);
        ASSERT_EQ(lines.polylineCount(), 4u) << "step " << step;
        for (size_t p = 0; p < lines.polylineCount(); ++p) {
            auto poly = lines.polyline(p);
            EXPECT_GE(poly.size(), size_t(40 / step));
            for (auto& v : poly) EXPECT_NEAR(v.x, poly[0].x, 1e-4f);
        }
        uniqueSegments(lines);
    }
}

TEST(AnalysisLines, FractalTerrainInvariants) {
    // On rough terrain lines meet and join: no segment twice, none shorter
    // than the minimum, discrete steps between 8-neighbours, every vertex but
    // the joins passing the threshold, each vertex on at most one line except
    // as a join.
    auto g = terrain::generateDiamondSquare({.size = 129, .seed = 11});
    auto c =
        computeCurvature(g, {.method = CurvatureMethod::ThreeNormal, .distance = 2, .scale = 4.0f});
    std::vector<float> strengths;
    for (int j = 0; j < c.height; ++j)
        for (int i = 0; i < c.width; ++i) strengths.push_back(c.maxMagnitude(i, j));
    std::sort(strengths.begin(), strengths.end());
    float threshold = strengths[strengths.size() * 8 / 10];  // the top 20% of vertices
    for (int minVertices : {2, 6}) {
        LineOptions o{.threshold = threshold, .minVertices = minVertices};
        auto lines = traceLines(c, o);
        ASSERT_GT(lines.polylineCount(), 10u);
        uniqueSegments(lines);
        std::vector<int> interiorUse(size_t(c.width * c.height), 0);
        for (size_t p = 0; p < lines.polylineCount(); ++p) {
            auto poly = lines.polyline(p);
            ASSERT_GE(int(poly.size()), minVertices);
            for (size_t k = 0; k < poly.size(); ++k) {
                int i = int(poly[k].x), j = int(poly[k].z);
                if (k > 0) {
                    int di = std::abs(i - int(poly[k - 1].x)),
                        dj = std::abs(j - int(poly[k - 1].z));
                    ASSERT_LE(std::max(di, dj), 1);
                    ASSERT_GT(di + dj, 0);
                }
                bool end = k == 0 || k + 1 == poly.size();
                if (c.maxMagnitude(i, j) < threshold) {
                    ASSERT_TRUE(end) << "only a join may sit below the threshold";
                }
                if (!end) ++interiorUse[size_t(j * c.width + i)];
            }
        }
        for (int n : interiorUse) ASSERT_LE(n, 1) << "a vertex runs through two lines";
        // A larger minimum keeps fewer lines.
        if (minVertices == 6) {
            EXPECT_LT(lines.polylineCount(),
                      traceLines(c, {.threshold = threshold, .minVertices = 2}).polylineCount());
        }
    }
    // Blended tracing terminates and keeps its minimum too.
    auto blended = traceLines(c, {.threshold = threshold, .minVertices = 6, .blended = true});
    ASSERT_GT(blended.polylineCount(), 0u);
    for (size_t p = 0; p < blended.polylineCount(); ++p) ASSERT_GE(blended.polyline(p).size(), 6u);
}

TEST(AnalysisLines, NoDataStopsLines) {
    auto field = sineRidge();
    std::vector<uint8_t> mask;
    for (int j = 0; j < 41; ++j)
        for (int i = 0; i < 65; ++i) mask.push_back(j == 20 ? 0 : 1);  // row 20 has no data
    field.setMask(mask);
    auto c =
        computeCurvature(field, {.method = CurvatureMethod::ThreeVertex, .signedValues = true});
    float crest = std::fabs(c.at(20, 5, 0));
    auto lines = traceLines(
        c, {.threshold = 0.96f * crest, .minVertices = 10, .polarity = LinePolarity::Ridges});
    // Each crest is cut in two by the hole: rows 0..19 and 21..40.
    ASSERT_EQ(lines.polylineCount(), 8u);
    for (size_t p = 0; p < lines.polylineCount(); ++p)
        for (auto& v : lines.polyline(p)) EXPECT_NE(v.z, 20.0f);
}

TEST(AnalysisLines, BadOptionsGiveClearErrors) {
    auto c = computeCurvature(sineRidge(), {});
    auto expectError = [&](LineOptions o, const std::string& words) {
        try {
            traceLines(c, o);
            ADD_FAILURE() << "no error for " << words;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
        }
    };
    expectError({.minVertices = 1}, "minimum length must be at least 2");
    expectError({.threshold = -0.5f}, "threshold must be finite and >= 0");
    expectError({.blended = true, .step = 0.0f}, "blended step");
    EXPECT_THROW(traceLines(CurvatureField{}, {}), Error);
    EXPECT_THROW(parseLinePolarity("crests"), Error);
}
