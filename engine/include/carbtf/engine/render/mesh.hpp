// Triangle meshes for carbtf's own render pass: the built-in shapes and tangent generation. A host
// engine draws its own meshes; it needs only the tangent-frame convention below.
//
// Tangent frame: tangent.xyz points along +u (texture right); the texture's "up" (towards row 0, i.e.
// along -v) is tangent.w * cross(normal, tangent.xyz). Texture coordinates cover [0, 1]^2 once. A
// closed shape meets itself where u wraps (the built-in ones put that at the back, facing -y): its
// `periodic_uv` asks for periodic textures (SynthesisBlock::periodic_overlap), which show no seam there.
// Thread safety: all functions are pure.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "carbtf/engine/status.hpp"

namespace carbtf {

struct MeshVertex {
  float position[3];
  float normal[3];
  float tangent[4];
  float uv[2];
};
static_assert(sizeof(MeshVertex) == 48, "MeshVertex is the vertex buffer layout");

struct Mesh {
  std::vector<MeshVertex> vertices;
  std::vector<std::uint32_t> indices;  // triangles, counter-clockwise seen from outside
  // The texture coordinates wrap (a closed shape, or coordinates beyond [0, 1]): the textures must tile.
  bool periodic_uv = false;
};

// The 2 x 2 square z = 0, x and y in [-1, 1], normal +z; u along +x, row 0 at y = +1.
Mesh make_plane(std::uint32_t subdivisions = 1);
// Radius 1 about the origin; u around +z from -y, v from the top (z = 1) to the bottom.
Mesh make_sphere(std::uint32_t segments = 64, std::uint32_t rings = 32);
// Radius 1, z in [-1, 1], without caps; u around +z from -y, v from z = 1 down.
Mesh make_cylinder(std::uint32_t segments = 64);
// Ring radius 1, tube radius 0.4, about +z; u around the ring from -y, v around the tube.
Mesh make_torus(std::uint32_t segments = 96, std::uint32_t tube_segments = 32);

// Recomputes every vertex's tangent (xyz and handedness w) from positions, normals and texture
// coordinates: per-triangle uv derivatives summed per vertex, made orthogonal to the normal.
// Vertices whose triangles have no uv extent get any tangent orthogonal to their normal.
void generate_tangents(Mesh& mesh);

// Whether a mesh's texture coordinates wrap, for meshes from files: coordinates beyond [0, 1], or a seam
// (vertices at one place, to 1e-5 of the mesh's size, whose coordinates differ by at least a half).
bool texture_coordinates_wrap(const Mesh& mesh);
// Checks a mesh a host or a file gave: indices in range, a whole number of triangles, finite values.
Status validate_mesh(const Mesh& mesh);

}  // namespace carbtf
