#include "carbtf/engine/render/mesh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>

#include <glm/glm.hpp>

namespace carbtf {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

MeshVertex vertex(glm::vec3 p, glm::vec3 n, glm::vec3 t, float w, glm::vec2 uv) {
  return {{p.x, p.y, p.z}, {n.x, n.y, n.z}, {t.x, t.y, t.z, w}, {uv.x, uv.y}};
}

// Triangles of a (columns + 1) x (rows + 1) vertex grid, row-major; `flip` reverses the winding.
void grid_indices(Mesh& mesh, std::uint32_t columns, std::uint32_t rows, bool flip) {
  for (std::uint32_t r = 0; r < rows; ++r) {
    for (std::uint32_t c = 0; c < columns; ++c) {
      const std::uint32_t a = r * (columns + 1) + c, b = a + 1, d = a + columns + 1, e = d + 1;
      if (flip) {
        mesh.indices.insert(mesh.indices.end(), {a, b, d, b, e, d});
      } else {
        mesh.indices.insert(mesh.indices.end(), {a, d, b, b, d, e});
      }
    }
  }
}

// A parametric surface over (u, v) in [0, 1]^2 with analytic position and normal; tangents follow.
template <typename Surface>
Mesh parametric(std::uint32_t columns, std::uint32_t rows, Surface surface) {
  Mesh mesh;
  for (std::uint32_t r = 0; r <= rows; ++r) {
    for (std::uint32_t c = 0; c <= columns; ++c) {
      const glm::vec2 uv(static_cast<float>(c) / columns, static_cast<float>(r) / rows);
      glm::vec3 p, n;
      surface(uv, p, n);
      mesh.vertices.push_back(vertex(p, n, glm::vec3(1, 0, 0), 1.0f, uv));
    }
  }
  grid_indices(mesh, columns, rows, false);
  generate_tangents(mesh);
  return mesh;
}

// A shape whose texture coordinates meet themselves.
Mesh closed(Mesh mesh) {
  mesh.periodic_uv = true;
  return mesh;
}

}  // namespace

Mesh make_plane(std::uint32_t subdivisions) {
  const std::uint32_t n = std::max(subdivisions, 1u);
  Mesh mesh;
  for (std::uint32_t r = 0; r <= n; ++r) {
    for (std::uint32_t c = 0; c <= n; ++c) {
      const glm::vec2 uv(static_cast<float>(c) / n, static_cast<float>(r) / n);
      mesh.vertices.push_back(
          vertex(glm::vec3(2 * uv.x - 1, 1 - 2 * uv.y, 0), glm::vec3(0, 0, 1), glm::vec3(1, 0, 0), 1.0f, uv));
    }
  }
  // Row r + 1 lies below row r (y decreases), so this winding is counter-clockwise seen from +z.
  grid_indices(mesh, n, n, false);
  return mesh;
}

// Azimuth a = 2 pi u - pi / 2 starts at -y, so u = 0 (the seam) faces away from a camera on +y... and
// a camera on -y sees it; the CLI's default camera looks from +x +y.
Mesh make_sphere(std::uint32_t segments, std::uint32_t rings) {
  return closed(
      parametric(std::max(segments, 3u), std::max(rings, 2u), [](glm::vec2 uv, glm::vec3& p, glm::vec3& n) {
        const float a = 2 * kPi * uv.x - kPi / 2, polar = kPi * uv.y;
        n = glm::vec3(std::sin(polar) * std::cos(a), std::sin(polar) * std::sin(a), std::cos(polar));
        p = n;
      }));
}

Mesh make_cylinder(std::uint32_t segments) {
  return closed(parametric(std::max(segments, 3u), 1, [](glm::vec2 uv, glm::vec3& p, glm::vec3& n) {
    const float a = 2 * kPi * uv.x - kPi / 2;
    n = glm::vec3(std::cos(a), std::sin(a), 0);
    p = glm::vec3(n.x, n.y, 1 - 2 * uv.y);
  }));
}

Mesh make_torus(std::uint32_t segments, std::uint32_t tube_segments) {
  return closed(parametric(std::max(segments, 3u), std::max(tube_segments, 3u),
                           [](glm::vec2 uv, glm::vec3& p, glm::vec3& n) {
                             const float a = 2 * kPi * uv.x - kPi / 2, b = 2 * kPi * uv.y;
                             const glm::vec3 radial(std::cos(a), std::sin(a), 0);
                             n = std::cos(b) * radial + glm::vec3(0, 0, std::sin(b));
                             p = radial + 0.4f * n;
                           }));
}

bool texture_coordinates_wrap(const Mesh& mesh) {
  float extent = 0.0f;
  for (const MeshVertex& v : mesh.vertices) {
    if (v.uv[0] < 0.0f || v.uv[0] > 1.0f || v.uv[1] < 0.0f || v.uv[1] > 1.0f) return true;
    for (float x : v.position) extent = std::max(extent, std::abs(x));
  }
  if (!(extent > 0.0f)) return false;
  // Seam vertices land in one cell of a grid 1e-5 of the size fine (one on either side of a cell
  // border is missed; a seam has many vertices, so it is still found).
  const double cell = 1e-5 * extent;
  std::map<std::array<long long, 3>, std::array<float, 2>> first_uv;
  for (const MeshVertex& v : mesh.vertices) {
    std::array<long long, 3> key;
    for (int i = 0; i < 3; ++i) key[static_cast<std::size_t>(i)] = std::llround(v.position[i] / cell);
    const auto [at, inserted] = first_uv.try_emplace(key, std::array<float, 2>{v.uv[0], v.uv[1]});
    if (!inserted && (std::abs(at->second[0] - v.uv[0]) >= 0.5f || std::abs(at->second[1] - v.uv[1]) >= 0.5f))
      return true;
  }
  return false;
}

void generate_tangents(Mesh& mesh) {
  std::vector<glm::vec3> along_u(mesh.vertices.size(), glm::vec3(0)),
      along_v(mesh.vertices.size(), glm::vec3(0));
  for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
    const std::uint32_t k[3] = {mesh.indices[i], mesh.indices[i + 1], mesh.indices[i + 2]};
    const auto& a = mesh.vertices[k[0]];
    const auto& b = mesh.vertices[k[1]];
    const auto& c = mesh.vertices[k[2]];
    const glm::vec3 e1 = glm::vec3(b.position[0], b.position[1], b.position[2]) -
                         glm::vec3(a.position[0], a.position[1], a.position[2]);
    const glm::vec3 e2 = glm::vec3(c.position[0], c.position[1], c.position[2]) -
                         glm::vec3(a.position[0], a.position[1], a.position[2]);
    const glm::vec2 d1(b.uv[0] - a.uv[0], b.uv[1] - a.uv[1]), d2(c.uv[0] - a.uv[0], c.uv[1] - a.uv[1]);
    const float det = d1.x * d2.y - d2.x * d1.y;
    if (std::abs(det) < 1e-20f) continue;
    // Solve e = dP/du * du + dP/dv * dv for the two edges; summing unnormalised weights by area.
    const glm::vec3 dpdu = (e1 * d2.y - e2 * d1.y) / det, dpdv = (e2 * d1.x - e1 * d2.x) / det;
    const float area = glm::length(glm::cross(e1, e2));
    for (std::uint32_t v : k) {
      along_u[v] += area * dpdu;
      along_v[v] += area * dpdv;
    }
  }
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    MeshVertex& vx = mesh.vertices[i];
    glm::vec3 n(vx.normal[0], vx.normal[1], vx.normal[2]);
    n = glm::length(n) > 0 ? glm::normalize(n) : glm::vec3(0, 0, 1);
    glm::vec3 t = along_u[i] - n * glm::dot(n, along_u[i]);
    if (glm::length(t) < 1e-12f) {
      // No uv extent: any direction orthogonal to the normal.
      t = std::abs(n.x) < 0.9f ? glm::cross(n, glm::vec3(1, 0, 0)) : glm::cross(n, glm::vec3(0, 1, 0));
    }
    t = glm::normalize(t);
    // Texture up is -dP/dv; w makes w * cross(n, t) point that way.
    const float w = glm::dot(glm::cross(n, t), -along_v[i]) < 0.0f ? -1.0f : 1.0f;
    vx.tangent[0] = t.x;
    vx.tangent[1] = t.y;
    vx.tangent[2] = t.z;
    vx.tangent[3] = w;
  }
}

Status validate_mesh(const Mesh& mesh) {
  if (mesh.vertices.empty() || mesh.indices.empty())
    return {ErrorCode::invalid_argument, "the mesh has no triangles"};
  if (mesh.indices.size() % 3 != 0) {
    return {ErrorCode::invalid_argument, "the mesh's index count " + std::to_string(mesh.indices.size()) +
                                             " is not a whole number of triangles"};
  }
  for (std::uint32_t index : mesh.indices) {
    if (index >= mesh.vertices.size()) {
      return {ErrorCode::invalid_argument, "the mesh's index " + std::to_string(index) + " is past its " +
                                               std::to_string(mesh.vertices.size()) + " vertices"};
    }
  }
  for (const MeshVertex& v : mesh.vertices) {
    for (float x : v.position) {
      if (!std::isfinite(x))
        return {ErrorCode::invalid_argument, "the mesh has a non-finite vertex position"};
    }
    for (float x : v.uv) {
      if (!std::isfinite(x))
        return {ErrorCode::invalid_argument, "the mesh has a non-finite texture coordinate"};
    }
    // The vertex stage normalizes the normal: a zero or non-finite one would light the pixel with NaN.
    const float length2 = v.normal[0] * v.normal[0] + v.normal[1] * v.normal[1] + v.normal[2] * v.normal[2];
    if (!std::isfinite(length2) || !(length2 > 1e-24f)) {
      return {ErrorCode::invalid_argument, "the mesh has a zero or non-finite normal at vertex " +
                                               std::to_string(&v - mesh.vertices.data())};
    }
  }
  return {};
}

}  // namespace carbtf
