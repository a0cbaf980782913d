#version 450
// The colour pass over a periodic image's fold texels (compute_shaders/include/colour_transform.glsl).
#extension GL_GOOGLE_include_directive : require
#define CARBTF_COLOUR_FOLD
#include "colour_transform.glsl"
