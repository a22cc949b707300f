#version 450 core
// The curvature field as a compute shader, one sample (or gradient texel)
// per invocation, into the same layers as the fragment runs; the code and
// its description: curvature_field.glsl.
#define CURVATURE_COMPUTE 1
#include "curvature_field.glsl"
