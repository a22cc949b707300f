// Geomorphing inside the error bound: the GPU copy of sierra::sbt::morphWeight
// and morphedHeight (engine/include/sierra/sbt/Morph.h, where the math is
// explained). Change both together.
//
// The vertex is blended from its morph base (the mean of the hypotenuse
// endpoints it bisects) to its true height while the screen-space error bound
// of the coarser surface around it, mu = lambda e / (d - r), grows from
// kMorphStart * tau (where refinement, run with tau' = kMorphStart * tau,
// activates it) to tau; past tau it is exact. The drawn surface thus stays
// within tau pixels, and nothing pops at activation (w = 0 there).

// Fraction of tau at which refinement activates a vertex (sbt::kMorphStart).
const float kMorphStart = 0.75;

// Weight in [0, 1]: 0 at the morph base, 1 at the true height. error and
// radius in world units (the vertex's saturated error and bounding radius),
// dist: world distance from the eye to the vertex at its true height,
// lambdaOverTau: lambda / tau with tau the full budget in pixels.
float morphWeight(float error, float radius, float dist, float lambdaOverTau) {
    float gap = dist - radius;  // eye to the vertex's sphere
    if (gap <= 0.0) return 1.0;  // eye inside the sphere: always refined
    float ratio = lambdaOverTau * error / gap;  // mu / tau
    return clamp((ratio - kMorphStart) / (1.0 - kMorphStart), 0.0, 1.0);
}

// The drawn world height of a vertex from its texel (r: height, g: morph base,
// b: error, a: radius), its world position at its true height and the eye.
float morphedHeight(vec4 texel, vec3 trueWorld, vec3 eye, float lambdaOverTau) {
    float w = morphWeight(texel.b, texel.a, distance(trueWorld, eye), lambdaOverTau);
    return texel.g + w * (texel.r - texel.g);
}
