#include "carbtf/engine/material/direction_interpolation.hpp"

#include <carbtf_gpu_shared.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <utility>

namespace carbtf {
namespace {

using Point = std::array<double, 2>;
using Triangle = std::array<std::uint32_t, 3>;

double cross(const Point& o, const Point& a, const Point& b) {
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

struct Circle {
  Point centre;
  double radius2;
};

Circle circumcircle(const Point& a, const Point& b, const Point& c) {
  const double d = 2.0 * (a[0] * (b[1] - c[1]) + b[0] * (c[1] - a[1]) + c[0] * (a[1] - b[1]));
  const double a2 = a[0] * a[0] + a[1] * a[1], b2 = b[0] * b[0] + b[1] * b[1], c2 = c[0] * c[0] + c[1] * c[1];
  const Point centre{(a2 * (b[1] - c[1]) + b2 * (c[1] - a[1]) + c2 * (a[1] - b[1])) / d,
                     (a2 * (c[0] - b[0]) + b2 * (a[0] - c[0]) + c2 * (b[0] - a[0])) / d};
  const double dx = a[0] - centre[0], dy = a[1] - centre[1];
  return {centre, dx * dx + dy * dy};
}

// Bowyer-Watson over `points`; the last three points are the enclosing super-triangle.
std::vector<Triangle> delaunay(const std::vector<Point>& points, std::uint32_t real_count) {
  std::vector<Triangle> triangles{{real_count, real_count + 1, real_count + 2}};
  std::vector<Circle> circles{
      circumcircle(points[real_count], points[real_count + 1], points[real_count + 2])};
  for (std::uint32_t i = 0; i < real_count; ++i) {
    const Point& p = points[i];
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
    std::vector<Triangle> kept;
    std::vector<Circle> kept_circles;
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      const double dx = p[0] - circles[t].centre[0], dy = p[1] - circles[t].centre[1];
      // Strictly inside (cocircular points, common in ring-shaped direction sets, stay outside).
      if (dx * dx + dy * dy < circles[t].radius2 * (1.0 - 1e-12)) {
        for (int e = 0; e < 3; ++e) {
          std::uint32_t a = triangles[t][e], b = triangles[t][(e + 1) % 3];
          ++edges[{std::min(a, b), std::max(a, b)}];
        }
      } else {
        kept.push_back(triangles[t]);
        kept_circles.push_back(circles[t]);
      }
    }
    for (const auto& [edge, count] : edges) {
      if (count != 1) continue;
      Triangle t{edge.first, edge.second, i};
      if (cross(points[t[0]], points[t[1]], points[t[2]]) < 0.0) std::swap(t[0], t[1]);
      kept.push_back(t);
      kept_circles.push_back(circumcircle(points[t[0]], points[t[1]], points[t[2]]));
    }
    triangles = std::move(kept);
    circles = std::move(kept_circles);
  }
  std::erase_if(triangles, [&](const Triangle& t) {
    return t[0] >= real_count || t[1] >= real_count || t[2] >= real_count;
  });
  return triangles;
}

}  // namespace

std::array<double, 2> project_direction(double theta, double phi) {
  const double r = theta / (0.5 * std::numbers::pi);
  return {r * std::cos(phi), r * std::sin(phi)};
}

Status build_direction_triangulation(std::span<const MaterialDirection> directions,
                                     DirectionTriangulation& out) {
  DirectionTriangulation result;
  for (const MaterialDirection& d : directions) result.points.push_back(project_direction(d.theta, d.phi));
  const auto n = static_cast<std::uint32_t>(result.points.size());
  if (n == 0) return {ErrorCode::invalid_argument, "no directions to interpolate between"};
  for (std::uint32_t i = 0; i < n; ++i) {
    for (std::uint32_t j = 0; j < i; ++j) {
      if (std::hypot(result.points[i][0] - result.points[j][0], result.points[i][1] - result.points[j][1]) <
          1e-9) {
        return {ErrorCode::invalid_argument,
                "directions " + std::to_string(j) + " and " + std::to_string(i) + " are the same"};
      }
    }
  }
  if (n == 2) result.boundary.push_back({0, 1});
  if (n >= 3) {
    std::vector<Point> points = result.points;
    points.push_back({0.0, 100.0});
    points.push_back({-86.6, -50.0});
    points.push_back({86.6, -50.0});
    result.triangles = delaunay(points, n);
    if (result.triangles.empty())
      return {ErrorCode::invalid_argument, "the directions lie on one great circle: nothing to triangulate"};
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
    for (const Triangle& t : result.triangles) {
      for (int e = 0; e < 3; ++e) ++edges[{std::min(t[e], t[(e + 1) % 3]), std::max(t[e], t[(e + 1) % 3])}];
    }
    for (const auto& [edge, count] : edges) {
      if (count == 1) result.boundary.push_back({edge.first, edge.second});
    }
  }
  out = std::move(result);
  return {};
}

DirectionWeights direction_weights(const DirectionTriangulation& tri, double theta, double phi) {
  const Point q = project_direction(theta, phi);
  DirectionWeights w;
  w.weight = {1.0f, 0.0f, 0.0f};
  for (const Triangle& t : tri.triangles) {
    const Point &a = tri.points[t[0]], &b = tri.points[t[1]], &c = tri.points[t[2]];
    const double area = cross(a, b, c);
    const double la = cross(q, b, c) / area, lb = cross(a, q, c) / area, lc = 1.0 - la - lb;
    constexpr double kInside = -1e-12;
    if (la < kInside || lb < kInside || lc < kInside) continue;
    std::array<double, 3> l{std::max(la, 0.0), std::max(lb, 0.0), std::max(lc, 0.0)};
    const double sum = l[0] + l[1] + l[2];
    for (int k = 0; k < 3; ++k) {
      w.index[k] = t[k];
      w.weight[k] = static_cast<float>(l[k] / sum);
    }
    // At a measured direction the weight is exactly one.
    for (int k = 0; k < 3; ++k) {
      if (l[k] / sum > 1.0 - 1e-9) {
        w.weight = {0.0f, 0.0f, 0.0f};
        w.weight[k] = 1.0f;
      }
    }
    return w;
  }
  // Outside the measured directions: the nearest point of the boundary.
  double best = std::numeric_limits<double>::infinity();
  for (const auto& edge : tri.boundary) {
    const Point &a = tri.points[edge[0]], &b = tri.points[edge[1]];
    const double ex = b[0] - a[0], ey = b[1] - a[1];
    const double t = std::clamp(((q[0] - a[0]) * ex + (q[1] - a[1]) * ey) / (ex * ex + ey * ey), 0.0, 1.0);
    const double dx = a[0] + t * ex - q[0], dy = a[1] + t * ey - q[1];
    if (dx * dx + dy * dy < best) {
      best = dx * dx + dy * dy;
      w.index = {edge[0], edge[1], edge[1]};
      w.weight = {static_cast<float>(1.0 - t), static_cast<float>(t), 0.0f};
    }
  }
  if (tri.boundary.empty()) w.index = {0, 0, 0};  // a single direction
  return w;
}

namespace {

// Ascending direction index, by the fragment stage's compare-and-swap network.
DirectionWeights by_index(DirectionWeights w) {
  const auto order = [&w](int a, int b) {
    if (w.index[a] > w.index[b]) {
      std::swap(w.index[a], w.index[b]);
      std::swap(w.weight[a], w.weight[b]);
    }
  };
  order(0, 1);
  order(1, 2);
  order(0, 1);
  return w;
}

}  // namespace

PairWeights couple_pair_weights(const DirectionWeights& light, const DirectionWeights& view,
                                PairCoupling coupling) {
  PairWeights pair;
  if (coupling == PairCoupling::product) {
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        pair.light[i * 3 + j] = light.index[i];
        pair.view[i * 3 + j] = view.index[j];
        pair.weight[i * 3 + j] = light.weight[i] * view.weight[j];
      }
    }
    return pair;
  }
  const DirectionWeights l = by_index(light), v = by_index(view);
  std::uint32_t i = 0, j = 0;
  float light_left = l.weight[0], view_left = v.weight[0];
  for (std::uint32_t k = 0; k < gpu::CARBTF_STAIRCASE_STEPS; ++k) {
    pair.light[k] = l.index[i];
    pair.view[k] = v.index[j];
    // The sums of the two sides agree only to rounding: what one side overdraws is never negative mass.
    pair.weight[k] = std::max(std::min(light_left, view_left), 0.0f);
    if (gpu::carbtf_staircase_next_is_light(light_left, view_left, i, j)) {
      view_left -= light_left;
      i = std::min(i + 1, 2u);
      light_left = l.weight[i];
    } else {
      light_left -= view_left;
      j = std::min(j + 1, 2u);
      view_left = v.weight[j];
    }
  }
  return pair;
}

PairWeights pair_weights(const DirectionTriangulation& lights, const DirectionTriangulation& views,
                         double light_theta, double light_phi, double view_theta, double view_phi,
                         PairCoupling coupling) {
  return couple_pair_weights(direction_weights(lights, light_theta, light_phi),
                             direction_weights(views, view_theta, view_phi), coupling);
}

}  // namespace carbtf
