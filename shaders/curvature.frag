#version 450 core
// The curvature field as fragment runs; the code and its description:
// curvature_field.glsl.
#include "curvature_field.glsl"
