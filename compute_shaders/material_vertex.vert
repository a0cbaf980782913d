#version 450
// carbtf's own mesh pipeline, vertex stage: world position, normal and tangent frame for the fragment
// stage. Vertex layout: engine/include/carbtf/engine/render/mesh.hpp (MeshVertex).
#extension GL_GOOGLE_include_directive : require
#include "carbtf_gpu_shared.h"

layout(std140, set = 1, binding = 0) uniform Frame { RenderFrameUniforms frame; };

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec4 in_tangent;
layout(location = 3) in vec2 in_uv;

layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec4 out_tangent;
layout(location = 3) out vec2 out_uv;

void main() {
  vec4 world = frame.model * vec4(in_position, 1.0);
  out_world = world.xyz;
  // The model matrix has a uniform scale only, so its upper 3x3 maps normals too.
  out_normal = mat3(frame.model) * in_normal;
  out_tangent = vec4(mat3(frame.model) * in_tangent.xyz, in_tangent.w);
  out_uv = in_uv;
  gl_Position = frame.view_projection * world;
}
