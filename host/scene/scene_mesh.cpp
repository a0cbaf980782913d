#include "scene/scene_mesh.hpp"

#include <cmath>
#include <map>
#include <tuple>

#include <tiny_obj_loader.h>
#include <glm/glm.hpp>

#include "cli/cli_support.hpp"

namespace carbtf::cli {

namespace {

constexpr std::size_t kMaxVertices = std::size_t{1} << 24;

}  // namespace

Mesh load_obj_mesh(const std::filesystem::path& path) {
  const std::string name = path.string();
  if (!std::filesystem::is_regular_file(path)) throw CommandError(name + ": no such mesh file");
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  config.mtl_search_path = "";  // materials are carbtf's; never read .mtl files beside the mesh
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(name, config)) {
    throw CommandError(
        name + ": not a readable OBJ mesh: " + (reader.Error().empty() ? "parse error" : reader.Error()));
  }
  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  Mesh mesh;
  bool has_normals = true;
  std::map<std::tuple<int, int, int>, std::uint32_t> unique;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    for (const tinyobj::index_t& index : shape.mesh.indices) {
      const auto key = std::make_tuple(index.vertex_index, index.normal_index, index.texcoord_index);
      if (auto found = unique.find(key); found != unique.end()) {
        mesh.indices.push_back(found->second);
        continue;
      }
      if (index.vertex_index < 0 ||
          3 * static_cast<std::size_t>(index.vertex_index) + 2 >= attrib.vertices.size()) {
        throw CommandError(name + ": a face refers to a vertex position that does not exist");
      }
      if (index.texcoord_index < 0 ||
          2 * static_cast<std::size_t>(index.texcoord_index) + 1 >= attrib.texcoords.size()) {
        throw CommandError(name + ": a face has no texture coordinates (vt); the material needs them");
      }
      MeshVertex v{};
      for (int k = 0; k < 3; ++k)
        v.position[k] = attrib.vertices[3 * static_cast<std::size_t>(index.vertex_index) + k];
      v.uv[0] = attrib.texcoords[2 * static_cast<std::size_t>(index.texcoord_index)];
      v.uv[1] = 1.0f - attrib.texcoords[2 * static_cast<std::size_t>(index.texcoord_index) + 1];
      if (index.normal_index >= 0 &&
          3 * static_cast<std::size_t>(index.normal_index) + 2 < attrib.normals.size()) {
        for (int k = 0; k < 3; ++k)
          v.normal[k] = attrib.normals[3 * static_cast<std::size_t>(index.normal_index) + k];
      } else {
        has_normals = false;
      }
      if (mesh.vertices.size() >= kMaxVertices) throw CommandError(name + ": more than 16 M vertices");
      unique.emplace(key, static_cast<std::uint32_t>(mesh.vertices.size()));
      mesh.indices.push_back(static_cast<std::uint32_t>(mesh.vertices.size()));
      mesh.vertices.push_back(v);
    }
  }
  if (mesh.indices.empty()) throw CommandError(name + ": the OBJ file has no faces");
  if (!has_normals) {
    // Area-weighted face normals summed per vertex.
    for (MeshVertex& v : mesh.vertices) v.normal[0] = v.normal[1] = v.normal[2] = 0.0f;
    for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
      MeshVertex* t[3] = {&mesh.vertices[mesh.indices[i]], &mesh.vertices[mesh.indices[i + 1]],
                          &mesh.vertices[mesh.indices[i + 2]]};
      const glm::vec3 a(t[0]->position[0], t[0]->position[1], t[0]->position[2]);
      const glm::vec3 b(t[1]->position[0], t[1]->position[1], t[1]->position[2]);
      const glm::vec3 c(t[2]->position[0], t[2]->position[1], t[2]->position[2]);
      const glm::vec3 n = glm::cross(b - a, c - a);
      for (MeshVertex* v : t) {
        for (int k = 0; k < 3; ++k) v->normal[k] += n[k];
      }
    }
  }
  const Status valid = validate_mesh(mesh);
  if (!valid.ok()) throw CommandError(name + ": " + valid.message());
  generate_tangents(mesh);
  return mesh;
}

Mesh load_mesh(const std::string& spec) {
  if (spec == "plane") return make_plane(8);
  if (spec == "sphere") return make_sphere();
  if (spec == "cylinder") return make_cylinder();
  if (spec == "torus") return make_torus();
  if (std::filesystem::path(spec).extension() == ".obj") return load_obj_mesh(spec);
  throw CommandError("--mesh " + spec + ": expected plane, sphere, cylinder, torus or a .obj file");
}

}  // namespace carbtf::cli
