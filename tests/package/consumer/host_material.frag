#version 450
// A host engine's own fragment shader drawing carbtf's material from descriptor set 1.
#extension GL_GOOGLE_include_directive : require
#define CARBTF_MATERIAL_SET 1
#include "carbtf_material.glsl"

layout(location = 0) in vec2 uv;
layout(location = 1) in vec3 light;  // tangent frame
layout(location = 2) in vec3 view;
layout(location = 0) out vec4 colour;

void main() {
  vec2 shifted = carbtf_parallax_uv(uv, normalize(view));
  colour = vec4(carbtf_material_shade(shifted, normalize(light), normalize(view)), 1.0);
}
