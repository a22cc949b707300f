#pragma once
// Geomorphing inside the error bound: the weight that blends a vertex from its
// morph base (the mean of the hypotenuse endpoints it bisects, where the
// coarser mesh has the surface) to its own height. The GPU side is the
// identical function in shaders/morph.glsl; change both together.
//
// The math. A vertex m has saturated error e, bounding radius r, and lies at
// distance d from the eye; lambda = viewport height / (2 tan(fovy / 2)).
// Without m the surface around m (inside its sphere) is off by at most e in
// height, seen from at least d - r away, so its screen-space error is bounded by
//
//     mu = lambda * e / (d - r)   pixels   (infinite when the eye is inside the sphere).
//
// Refinement without geomorphing activates m when mu > tau: just after, m
// jumps from its base to its height (a pop of up to tau pixels), and the old
// morph (blend from mu = tau to mu = 2 tau) kept m part-way at its base while
// the coarse error bound mu already exceeded tau: up to 1.25 tau on the
// surface, and a visibly softer mesh (2 dB PSNR on rough terrain).
//
// Here, as in CDLOD, the morph is done before the budget is reached:
// refinement activates m earlier, when mu > kMorphStart * tau (refine with
// refinementTau(tau)), and the weight grows linearly in mu,
//
//     w = clamp((mu / tau - kMorphStart) / (1 - kMorphStart), 0, 1),
//
// from 0 at activation (so nothing pops: the vertex starts where the coarse
// surface was) to 1 when mu reaches tau. While 0 < w < 1 the drawn surface
// around m is (1 - w) * coarse + w * fine, whose error is at most
// (1 - w) * mu + w * kMorphStart * tau <= tau (mu <= tau there, and m's
// inactive children are within kMorphStart * tau); the vertex itself is
// displaced by (1 - w) |h - base| <= (1 - w) e, i.e. less than
// lambda e / d < mu <= tau pixels. Once mu >= tau the vertex is exact.
//
// Cost: the mesh is the one of tau' = kMorphStart * tau. Triangles grow about
// as tau'^-2 on smooth terrain and faster on rough: on a rough 2049^2 fractal
// (Hurst 0.8) from the orbit path, 1.98x the triangles of tau (1 974 447 ->
// 3 919 269 over four cameras at tau = 1, 1920x1080).

namespace sierra::sbt {

// Activation threshold of the morph as a fraction of tau (0.75: the morph
// takes the last quarter of the error budget).
inline constexpr float kMorphStart = 0.75f;

// The tau to refine with when the renderer geomorphs with budget `tau`
// (pixels): vertices activate when their error bound reaches kMorphStart * tau.
// Without geomorphing refine with tau itself.
inline float refinementTau(float tau) {
    return kMorphStart * tau;
}

// Morph weight in [0, 1] (0: at the morph base, 1: at the true height) of a
// vertex with saturated error `error` and bounding radius `radius` (world
// units) at `distance` from the eye (world units, to its true position);
// lambdaOverTau = lambda / tau with tau the full budget (pixels).
inline float morphWeight(float error, float radius, float distance, float lambdaOverTau) {
    const float gap = distance - radius;              // eye to the vertex's sphere
    if (gap <= 0.0f) return 1.0f;                     // eye inside the sphere: always refined
    const float ratio = lambdaOverTau * error / gap;  // mu / tau
    const float w = (ratio - kMorphStart) / (1.0f - kMorphStart);
    return w < 0.0f ? 0.0f : (w > 1.0f ? 1.0f : w);
}

// The drawn height: base + w * (height - base), all world units.
inline float morphedHeight(float height, float base, float error, float radius, float distance,
                           float lambdaOverTau) {
    const float w = morphWeight(error, radius, distance, lambdaOverTau);
    return base + w * (height - base);
}

}  // namespace sierra::sbt
