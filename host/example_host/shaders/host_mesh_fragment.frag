#version 450
// The example host engine's own fragment shader: carbtf's material from descriptor set 1, under the
// host's one directional light, in the host's own tangent frame code.
#extension GL_GOOGLE_include_directive : require
#define CARBTF_MATERIAL_SET 1
#include "carbtf_material.glsl"

layout(std140, set = 0, binding = 0) uniform HostFrame {
  mat4 view_projection;
  vec4 camera;
  vec4 light;
} host;

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec4 in_tangent;
layout(location = 3) in vec2 in_uv;
layout(location = 0) out vec4 out_colour;

void main() {
  float lod = carbtf_material_lod(in_uv);  // before any branch: it takes derivatives
  vec3 n = normalize(in_normal);
  vec3 t = normalize(in_tangent.xyz - n * dot(n, in_tangent.xyz));
  mat3 to_tangent = transpose(mat3(t, in_tangent.w * cross(n, t), n));
  vec3 view = normalize(to_tangent * (host.camera.xyz - in_world));
  vec3 light = normalize(to_tangent * host.light.xyz);
  vec2 uv = carbtf_parallax_uv(in_uv, view, lod);
  out_colour = vec4(carbtf_material_shade(uv, light, view, lod), 1.0);
}
