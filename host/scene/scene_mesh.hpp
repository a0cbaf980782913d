// The meshes the commands draw: a built-in shape by name, or a Wavefront OBJ file (through
// tinyobjloader): triangulated, texture coordinates required (the material is a texture), v flipped to
// carbtf's row-0-at-top convention, normals averaged from the faces where the file has none, tangents
// always generated (OBJ has none).
#pragma once

#include <filesystem>
#include <string>

#include "carbtf/engine/render/mesh.hpp"

namespace carbtf::cli {

// Throws CommandError naming the file and the problem: unreadable, no triangles, no texture
// coordinates, indices out of range, non-finite values, more than 16 M vertices.
Mesh load_obj_mesh(const std::filesystem::path& path);

// "plane", "sphere", "cylinder", "torus" or a path ending in .obj; else CommandError naming --mesh.
Mesh load_mesh(const std::string& spec);

}  // namespace carbtf::cli
