#version 450
// The example host engine's own vertex shader: its own uniform block (set 0), carbtf's vertex layout.
layout(std140, set = 0, binding = 0) uniform HostFrame {
  mat4 view_projection;
  vec4 camera;     // world position
  vec4 light;      // direction towards the light, world
} host;

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec4 in_tangent;
layout(location = 3) in vec2 in_uv;

layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec4 out_tangent;
layout(location = 3) out vec2 out_uv;

void main() {
  out_world = in_position;
  out_normal = in_normal;
  out_tangent = in_tangent;
  out_uv = in_uv;
  gl_Position = host.view_projection * vec4(in_position, 1.0);
}
