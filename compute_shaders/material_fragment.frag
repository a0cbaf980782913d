#version 450
// carbtf's own mesh pipeline, fragment stage: the material (carbtf_material.glsl) under up to
// CARBTF_RENDER_MAX_LIGHTS directional or point lights, in linear RGB; an sRGB target encodes it.
#extension GL_GOOGLE_include_directive : require
#include "carbtf_material.glsl"

layout(std140, set = 1, binding = 0) uniform Frame { RenderFrameUniforms frame; };

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec4 in_tangent;
layout(location = 3) in vec2 in_uv;

layout(location = 0) out vec4 out_colour;

void main() {
  float lod = carbtf_material_lod(in_uv);
  vec3 n = normalize(in_normal);
  vec3 t = normalize(in_tangent.xyz - n * dot(n, in_tangent.xyz));
  vec3 up = in_tangent.w * cross(n, t);  // texture up (towards row 0)
  mat3 to_tangent = transpose(mat3(t, up, n));

  vec3 to_eye = frame.camera.w > 0.5 ? frame.camera.xyz - in_world : frame.camera.xyz;
  vec3 view = normalize(to_tangent * to_eye);
  vec2 uv = carbtf_parallax_uv(in_uv, view, lod);

  // The relief and the view's lookup once for every light.
  CarbtfSurface surface = carbtf_material_surface(uv, view, lod);
  vec3 colour = vec3(0.0);
  for (uint i = 0u; i < min(frame.counts.x, CARBTF_RENDER_MAX_LIGHTS); ++i) {
    vec4 light = frame.light_position[i];
    vec3 to_light = light.w > 0.5 ? light.xyz - in_world : light.xyz;
    float falloff = light.w > 0.5 ? 1.0 / max(dot(to_light, to_light), 1.0e-12) : 1.0;
    vec3 l = normalize(to_tangent * to_light);
    colour += falloff * frame.light_colour[i].rgb * carbtf_material_shade(surface, l);
  }
  out_colour = vec4(colour, 1.0);
}
