#include "carbtf/engine/internal/direction_lookup.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <carbtf_gpu_shared.h>

namespace carbtf {

static_assert(gpu::CARBTF_LOOKUP_MIN_WEIGHT == 1.0e-5f,
              "lookup_direction_weights() defaults to the shader's threshold");

namespace {

using Point = std::array<double, 2>;

// Whether triangle t meets the box [x0, x1] x [y0, y1], given that their bounding boxes do: no edge
// of the triangle has the whole box strictly on its outer side (the separating-axis test's remaining
// axes). The fragment stage scans every triangle a cell lists, so a cell that lists only the
// triangles that meet it (not every one whose bounding box does) makes the scan shorter.
bool triangle_meets_box(const DirectionTriangulation& tri, std::uint32_t triangle, double x0, double y0,
                        double x1, double y1) {
  const auto& t = tri.triangles[triangle];
  for (int k = 0; k < 3; ++k) {
    const Point &a = tri.points[t[k]], &b = tri.points[t[(k + 1) % 3]], &c = tri.points[t[(k + 2) % 3]];
    const auto side = [&](double x, double y) {
      return (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]);
    };
    const double inner = side(c[0], c[1]);
    if (inner == 0.0) continue;  // a degenerate triangle: keep it, as the bounding box did
    const bool all_outside = inner * side(x0, y0) < 0.0 && inner * side(x1, y0) < 0.0 &&
                             inner * side(x0, y1) < 0.0 && inner * side(x1, y1) < 0.0;
    if (all_outside) return false;
  }
  return true;
}

}  // namespace

bool inside_triangle(const DirectionTriangulation& tri, std::uint32_t triangle, double x, double y) {
  const auto& t = tri.triangles[triangle];
  const Point &a = tri.points[t[0]], &b = tri.points[t[1]], &c = tri.points[t[2]];
  const double area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
  const double la = ((b[0] - x) * (c[1] - y) - (b[1] - y) * (c[0] - x)) / area;
  const double lb = ((x - a[0]) * (c[1] - a[1]) - (y - a[1]) * (c[0] - a[0])) / area;
  return la >= -1e-12 && lb >= -1e-12 && 1.0 - la - lb >= -1e-12;
}

bool inside_triangulation(const DirectionTriangulation& tri, double x, double y) {
  for (std::uint32_t t = 0; t < tri.triangles.size(); ++t) {
    if (inside_triangle(tri, t, x, y)) return true;
  }
  return false;
}

double boundary_edge_distance(const DirectionTriangulation& tri, std::uint32_t edge, double x, double y) {
  const Point& a = tri.points[tri.boundary[edge][0]];
  const Point& b = tri.points[tri.boundary[edge][1]];
  const double ex = b[0] - a[0], ey = b[1] - a[1];
  const double length2 = ex * ex + ey * ey;
  const double t = length2 > 0 ? std::clamp(((x - a[0]) * ex + (y - a[1]) * ey) / length2, 0.0, 1.0) : 0.0;
  return std::hypot(a[0] + t * ex - x, a[1] + t * ey - y);
}

DirectionLookupGrid build_direction_lookup(const DirectionTriangulation& tri, std::uint32_t grid_size) {
  grid_size = std::clamp(grid_size, 1u, 256u);
  DirectionLookupGrid grid;
  grid.grid_size = grid_size;
  grid.cell_starts.reserve(std::size_t{grid_size} * grid_size + 1);
  const double cell = 2.0 / grid_size;
  // Bounding boxes meet when they overlap by less than this: a point on a shared border belongs to both.
  constexpr double kSlack = 1e-6;
  for (std::uint32_t y = 0; y < grid_size; ++y) {
    for (std::uint32_t x = 0; x < grid_size; ++x) {
      grid.cell_starts.push_back(static_cast<std::uint32_t>(grid.entries.size()));
      const double x0 = -1.0 + x * cell, y0 = -1.0 + y * cell, x1 = x0 + cell, y1 = y0 + cell;
      for (std::uint32_t t = 0; t < tri.triangles.size(); ++t) {
        double lo[2] = {1e30, 1e30}, hi[2] = {-1e30, -1e30};
        for (std::uint32_t k : tri.triangles[t]) {
          for (int d = 0; d < 2; ++d) {
            lo[d] = std::min(lo[d], tri.points[k][d]);
            hi[d] = std::max(hi[d], tri.points[k][d]);
          }
        }
        if (lo[0] <= x1 + kSlack && hi[0] >= x0 - kSlack && lo[1] <= y1 + kSlack && hi[1] >= y0 - kSlack &&
            triangle_meets_box(tri, t, x0 - kSlack, y0 - kSlack, x1 + kSlack, y1 + kSlack)) {
          grid.entries.push_back(t);
        }
      }
      // The triangulation is convex, so a cell whose corners are all inside it lies inside.
      const Point corners[4] = {{x0, y0}, {x1, y0}, {x0, y1}, {x1, y1}};
      bool partly_outside = false;
      for (const Point& corner : corners)
        partly_outside = partly_outside || !inside_triangulation(tri, corner[0], corner[1]);
      if (!partly_outside || tri.boundary.empty()) continue;
      // An edge can be nearest to some point of the cell only if it is within the nearest edge's
      // distance from the centre plus the cell's diameter.
      const Point centre{0.5 * (x0 + x1), 0.5 * (y0 + y1)};
      const double radius = 0.5 * std::sqrt(2.0) * cell;
      double nearest = std::numeric_limits<double>::infinity();
      for (std::uint32_t e = 0; e < tri.boundary.size(); ++e) {
        nearest = std::min(nearest, boundary_edge_distance(tri, e, centre[0], centre[1]));
      }
      for (std::uint32_t e = 0; e < tri.boundary.size(); ++e) {
        if (boundary_edge_distance(tri, e, centre[0], centre[1]) <= nearest + 2.0 * radius + kSlack) {
          grid.entries.push_back(gpu::CARBTF_LOOKUP_EDGE_BIT | e);
        }
      }
    }
  }
  grid.cell_starts.push_back(static_cast<std::uint32_t>(grid.entries.size()));
  return grid;
}

DirectionWeights lookup_direction_weights(const DirectionLookupGrid& grid, const DirectionTriangulation& tri,
                                          float x, float y, float min_weight) {
  DirectionWeights w;
  w.weight = {1.0f, 0.0f, 0.0f};
  if (grid.grid_size == 0) return w;
  const int g = static_cast<int>(grid.grid_size);
  const int cx =
      std::clamp(static_cast<int>(std::floor((x * 0.5f + 0.5f) * static_cast<float>(g))), 0, g - 1);
  const int cy =
      std::clamp(static_cast<int>(std::floor((y * 0.5f + 0.5f) * static_cast<float>(g))), 0, g - 1);
  const std::size_t c = static_cast<std::size_t>(cy) * grid.grid_size + static_cast<std::size_t>(cx);
  auto point = [&](std::uint32_t i) {
    return std::array<float, 2>{static_cast<float>(tri.points[i][0]), static_cast<float>(tri.points[i][1])};
  };
  float best_inside = -1.0e30f, best_distance = 1.0e30f;
  DirectionWeights edge_weights = w;
  for (std::uint32_t e = grid.cell_starts[c]; e < grid.cell_starts[c + 1]; ++e) {
    const std::uint32_t entry = grid.entries[e];
    if ((entry & gpu::CARBTF_LOOKUP_EDGE_BIT) == 0) {
      const auto& t = tri.triangles[entry];
      const auto a = point(t[0]), b = point(t[1]), q = point(t[2]);
      const float area = (b[0] - a[0]) * (q[1] - a[1]) - (b[1] - a[1]) * (q[0] - a[0]);
      const float la = ((b[0] - x) * (q[1] - y) - (b[1] - y) * (q[0] - x)) / area;
      const float lb = ((x - a[0]) * (q[1] - a[1]) - (y - a[1]) * (q[0] - a[0])) / area;
      float l[3] = {la, lb, 1.0f - la - lb};
      const float inside = std::min({l[0], l[1], l[2]});
      if (inside > best_inside) {
        best_inside = inside;
        for (float& v : l) v = std::max(v, 0.0f);
        const float sum = l[0] + l[1] + l[2];
        for (int k = 0; k < 3; ++k) {
          w.index[k] = t[k];
          w.weight[k] = l[k] / sum;
        }
      }
    } else {
      const auto& edge = tri.boundary[entry & ~gpu::CARBTF_LOOKUP_EDGE_BIT];
      const auto a = point(edge[0]), b = point(edge[1]);
      const float ex = b[0] - a[0], ey = b[1] - a[1];
      const float s = std::clamp(((x - a[0]) * ex + (y - a[1]) * ey) / (ex * ex + ey * ey), 0.0f, 1.0f);
      const float dx = a[0] + s * ex - x, dy = a[1] + s * ey - y;
      if (dx * dx + dy * dy < best_distance) {
        best_distance = dx * dx + dy * dy;
        edge_weights.index = {edge[0], edge[1], edge[1]};
        edge_weights.weight = {1.0f - s, s, 0.0f};
      }
    }
  }
  DirectionWeights& chosen =
      best_inside < -gpu::CARBTF_LOOKUP_INSIDE_SLACK && best_distance < 1.0e30f ? edge_weights : w;
  float sum = 0.0f;
  for (float& weight : chosen.weight) {
    if (weight < min_weight) weight = 0.0f;
    sum += weight;
  }
  for (float& weight : chosen.weight) weight /= sum;
  return chosen;
}

}  // namespace carbtf
