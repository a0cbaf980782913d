#include "scene/scene_mesh.hpp"

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <tuple>

#include <tiny_obj_loader.h>
#include <glm/glm.hpp>

#include "cli/command_error.hpp"

namespace carbtf::cli {

namespace {

constexpr std::size_t kMaxVertices = std::size_t{1} << 24;

// tinyobjloader reads "nan" as 0 and wraps an index of 99999999999999999999, so every number of the
// v, vt, vn and f records is checked first, in one linear pass: coordinates must be finite floats and
// indices must fit 32 bits.
void check_obj_numbers(const std::filesystem::path& path) {
  std::ifstream file(path);
  if (!file) throw CommandError(path.string() + ": cannot open the mesh file");
  std::string line;
  for (std::size_t number = 1; std::getline(file, line); ++number) {
    std::istringstream words(line);
    std::string record, token;
    words >> record;
    const bool coordinates = record == "v" || record == "vt" || record == "vn";
    if (!coordinates && record != "f") continue;
    while (words >> token) {
      const std::string where = path.string() + ":" + std::to_string(number) + ": ";
      if (coordinates) {
        char* end = nullptr;
        const double value = std::strtod(token.c_str(), &end);
        if (end != token.c_str() + token.size() || !std::isfinite(value) || std::fabs(value) > 1e30) {
          throw CommandError(where + "'" + token + "' is a non-finite or malformed coordinate");
        }
        continue;
      }
      for (std::size_t start = 0; start <= token.size();) {
        const std::size_t slash = std::min(token.find('/', start), token.size());
        const std::string part = token.substr(start, slash - start);
        if (!part.empty()) {
          char* end = nullptr;
          errno = 0;
          const long long index = std::strtoll(part.c_str(), &end, 10);
          if (end != part.c_str() + part.size() || errno == ERANGE || index == 0 || index > INT32_MAX ||
              index < -INT32_MAX) {
            throw CommandError(where + "face index '" + part + "' is not a non-zero 32-bit integer");
          }
        }
        start = slash + 1;
      }
    }
  }
}

bool usable_normal(const float* n) {
  const float length2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
  return std::isfinite(length2) && length2 > 1e-24f;
}

}  // namespace

Mesh load_obj_mesh(const std::filesystem::path& path) {
  const std::string name = path.string();
  if (!std::filesystem::is_regular_file(path)) throw CommandError(name + ": no such mesh file");
  check_obj_numbers(path);
  tinyobj::ObjReaderConfig config;
  // Faces are fanned below, in linear time; tinyobjloader's own triangulation is quadratic per face.
  config.triangulate = false;
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
  bool zero_normals = false;  // zero, NaN or infinite normals in the file
  std::map<std::tuple<int, int, int>, std::uint32_t> unique;
  const auto add_corner = [&](const tinyobj::index_t& index) {
    const auto key = std::make_tuple(index.vertex_index, index.normal_index, index.texcoord_index);
    if (auto found = unique.find(key); found != unique.end()) {
      mesh.indices.push_back(found->second);
      return;
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
      if (!usable_normal(v.normal)) zero_normals = true;
    } else {
      has_normals = false;
    }
    if (mesh.vertices.size() >= kMaxVertices) throw CommandError(name + ": more than 16 M vertices");
    unique.emplace(key, static_cast<std::uint32_t>(mesh.vertices.size()));
    mesh.indices.push_back(static_cast<std::uint32_t>(mesh.vertices.size()));
    mesh.vertices.push_back(v);
  };
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    std::size_t first = 0;
    for (const unsigned int corners : shape.mesh.num_face_vertices) {
      if (first + corners > shape.mesh.indices.size())
        throw CommandError(name + ": a face lists more corners than the file holds");
      // A fan from the first corner: exact for the convex polygons OBJ exporters write.
      for (std::size_t k = 1; k + 1 < corners; ++k) {
        for (std::size_t corner : {first, first + k, first + k + 1}) add_corner(shape.mesh.indices[corner]);
      }
      first += corners;
    }
  }
  if (mesh.indices.empty()) throw CommandError(name + ": the OBJ file has no faces");
  if (zero_normals && has_normals) {
    std::fprintf(stderr,
                 "carbtf: warning: %s: some normals (vn) are zero, NaN or infinite; all normals are "
                 "recomputed from the faces\n",
                 name.c_str());
  }
  if (!has_normals || zero_normals) {
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
  if (!has_normals || zero_normals) {
    // A vertex whose triangles all have zero area is never lit; any unit normal will do.
    for (MeshVertex& v : mesh.vertices) {
      if (!usable_normal(v.normal)) v.normal[0] = 0.0f, v.normal[1] = 0.0f, v.normal[2] = 1.0f;
    }
  }
  const Status valid = validate_mesh(mesh);
  if (!valid.ok()) throw CommandError(name + ": " + valid.message());
  generate_tangents(mesh);
  mesh.periodic_uv = texture_coordinates_wrap(mesh);
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
