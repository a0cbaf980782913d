#version 450
// The colour pass over every texel beyond the fold (compute_shaders/include/colour_transform.glsl).
#extension GL_GOOGLE_include_directive : require
#include "colour_transform.glsl"
