// The barycentric direction interpolation: weights sum to 1, are exact at measured directions, and are
// continuous, across triangle edges and beyond the last measured elevation; and the two couplings of a
// light's and a view's weights into pair weights (the paper's 9, the staircase's 5).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <random>

#include "carbtf/engine/internal/direction_lookup.hpp"
#include "carbtf/engine/material/direction_interpolation.hpp"
#include "carbtf/engine/material/material_directions.hpp"
#include "carbtf/reference/synthetic_material.hpp"
#include "test_materials.hpp"

namespace carbtf {
namespace {

// Weights spread over all directions, to compare two queries whatever triangles they fall in.
std::vector<double> dense(const DirectionWeights& w, std::size_t count) {
  std::vector<double> d(count, 0.0);
  for (int k = 0; k < 3; ++k) d[w.index[k]] += w.weight[k];
  return d;
}

double l1(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) s += std::abs(a[i] - b[i]);
  return s;
}

// The direction whose projection is (x, y).
std::pair<double, double> unproject(double x, double y) {
  return {std::hypot(x, y) * 0.5 * std::numbers::pi, std::atan2(y, x)};
}

// The weights of one query as a map from direction to weight, to compare two searches.
std::map<std::uint32_t, double> as_map(const DirectionWeights& w) {
  std::map<std::uint32_t, double> m;
  for (int k = 0; k < 3; ++k) {
    if (w.weight[k] != 0.0f) m[w.index[k]] += w.weight[k];
  }
  return m;
}

}  // namespace

TEST_CASE("the UBO2003 directions triangulate the disk of the outer ring", "[interpolation]") {
  const auto directions = test::ubo2003_material_directions();
  DirectionTriangulation tri;
  REQUIRE(build_direction_triangulation(directions, tri).ok());
  double area = 0.0;
  for (const auto& t : tri.triangles) {
    const auto &a = tri.points[t[0]], &b = tri.points[t[1]], &c = tri.points[t[2]];
    const double twice = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    REQUIRE(twice > 1e-6);  // counter-clockwise, not degenerate
    area += 0.5 * twice;
  }
  const double r = 75.0 / 90.0;
  // Directions are stored as float: the projected points carry float rounding (about 1e-7).
  CHECK(area == Approx(0.5 * 24 * r * r * std::sin(2 * std::numbers::pi / 24)).epsilon(1e-6));
  CHECK(tri.boundary.size() == 24u);
}

TEST_CASE("interpolation weights sum to 1 and are exact at measured directions", "[interpolation]") {
  const auto directions = test::ubo2003_material_directions();
  DirectionTriangulation tri;
  REQUIRE(build_direction_triangulation(directions, tri).ok());
  for (std::uint32_t i = 0; i < directions.size(); ++i) {
    const DirectionWeights w = direction_weights(tri, directions[i].theta, directions[i].phi);
    const std::vector<double> d = dense(w, directions.size());
    INFO("direction " << i);
    REQUIRE(d[i] == 1.0);
    REQUIRE(l1(d, std::vector<double>(d.size(), 0.0)) == 1.0);
  }
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> theta(0.0, 0.5 * std::numbers::pi), phi(0.0, 2.0 * std::numbers::pi);
  for (int i = 0; i < 10000; ++i) {
    const DirectionWeights w = direction_weights(tri, theta(rng), phi(rng));
    double sum = 0.0;
    for (float v : w.weight) {
      REQUIRE(v >= 0.0f);
      sum += v;
    }
    REQUIRE(sum == Approx(1.0).margin(1e-6));
  }
  SECTION("nine pair weights") {
    DirectionTriangulation views;
    REQUIRE(build_direction_triangulation(directions, views).ok());
    const PairWeights exact = pair_weights(tri, views, directions[20].theta, directions[20].phi,
                                           directions[50].theta, directions[50].phi);
    double at_pair = 0.0, sum = 0.0;
    for (int k = 0; k < 9; ++k) {
      sum += exact.weight[k];
      if (exact.light[k] == 20 && exact.view[k] == 50) at_pair += exact.weight[k];
    }
    CHECK(at_pair == 1.0);
    CHECK(sum == 1.0);
    const PairWeights between = pair_weights(tri, views, 0.4, 1.0, 1.4, 4.0);
    sum = 0.0;
    for (float v : between.weight) sum += v;
    CHECK(sum == Approx(1.0).margin(1e-6));
  }
}

TEST_CASE("interpolation weights are continuous across triangle edges and the last ring", "[interpolation]") {
  const auto directions = test::ubo2003_material_directions();
  DirectionTriangulation tri;
  REQUIRE(build_direction_triangulation(directions, tri).ok());
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (const auto& t : tri.triangles)
    for (int e = 0; e < 3; ++e) ++edges[{std::min(t[e], t[(e + 1) % 3]), std::max(t[e], t[(e + 1) % 3])}];
  int interior = 0;
  for (const auto& [edge, count] : edges) {
    const auto &a = tri.points[edge.first], &b = tri.points[edge.second];
    const double mx = 0.5 * (a[0] + b[0]), my = 0.5 * (a[1] + b[1]);
    const double nx = -(b[1] - a[1]), ny = b[0] - a[0];
    const double eps = 1e-7 / std::hypot(nx, ny);
    const auto [t1, p1] = unproject(mx + eps * nx, my + eps * ny);
    const auto [t2, p2] = unproject(mx - eps * nx, my - eps * ny);
    const double jump = l1(dense(direction_weights(tri, t1, p1), directions.size()),
                           dense(direction_weights(tri, t2, p2), directions.size()));
    INFO("edge " << edge.first << "-" << edge.second);
    CHECK(jump < 1e-5);
    interior += count == 2;
  }
  CHECK(interior > 100);
  // Beyond the last measured elevation (75 degrees) only the outer ring carries weight, continuously.
  for (double phi = 0.0; phi < 2.0 * std::numbers::pi; phi += 0.05) {
    const double ring = 75.0 * std::numbers::pi / 180.0;
    const auto inside = dense(direction_weights(tri, ring - 1e-8, phi), directions.size());
    const auto outside = dense(direction_weights(tri, ring + 1e-8, phi), directions.size());
    const auto grazing = direction_weights(tri, 0.5 * std::numbers::pi, phi);
    CHECK(l1(inside, outside) < 1e-5);
    for (int k = 0; k < 3; ++k) {
      if (grazing.weight[k] > 0.0f) CHECK(grazing.index[k] >= 57u);
    }
  }
}

namespace {

using PairMap = std::map<std::pair<std::uint32_t, std::uint32_t>, double>;

PairMap by_pair(const PairWeights& w) {
  PairMap m;
  for (std::size_t k = 0; k < w.weight.size(); ++k) {
    if (w.weight[k] != 0.0f) m[{w.light[k], w.view[k]}] += w.weight[k];
  }
  return m;
}

double l1(const PairMap& a, const PairMap& b) {
  double s = 0.0;
  for (const auto& [pair, w] : a) s += std::abs(w - (b.contains(pair) ? b.at(pair) : 0.0));
  for (const auto& [pair, w] : b) {
    if (!a.contains(pair)) s += std::abs(w);
  }
  return s;
}

}  // namespace

TEST_CASE("the staircase coupling keeps the light's and the view's weights in at most 5 pairs",
          "[interpolation]") {
  const auto directions = test::ubo2003_material_directions();
  DirectionTriangulation tri;
  REQUIRE(build_direction_triangulation(directions, tri).ok());
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> theta(0.0, 0.5 * std::numbers::pi), phi(0.0, 2.0 * std::numbers::pi);
  double largest_difference_from_product = 0.0;
  for (int q = 0; q < 5000; ++q) {
    const DirectionWeights light = direction_weights(tri, theta(rng), phi(rng));
    const DirectionWeights view = direction_weights(tri, theta(rng), phi(rng));
    const PairWeights staircase = couple_pair_weights(light, view, PairCoupling::staircase);
    const PairWeights product = couple_pair_weights(light, view, PairCoupling::product);
    INFO("query " << q);
    int nonzero = 0;
    for (std::size_t k = 0; k < staircase.weight.size(); ++k) {
      REQUIRE(staircase.weight[k] >= 0.0f);
      nonzero += staircase.weight[k] != 0.0f;
      if (k >= 5) REQUIRE(staircase.weight[k] == 0.0f);
    }
    REQUIRE(nonzero <= 5);
    // The sums over views are the light's weights and the sums over lights the view's, as for the product.
    const std::vector<double> light_dense = dense(light, directions.size()),
                              view_dense = dense(view, directions.size());
    std::vector<double> light_sums(directions.size(), 0.0), view_sums(directions.size(), 0.0);
    for (const auto& [pair, w] : by_pair(staircase)) {
      light_sums[pair.first] += w;
      view_sums[pair.second] += w;
    }
    REQUIRE(l1(light_sums, light_dense) < 1e-6);
    REQUIRE(l1(view_sums, view_dense) < 1e-6);
    // The order the lookups list their directions in does not matter.
    DirectionWeights light_turned = light, view_turned = view;
    std::rotate(light_turned.index.begin(), light_turned.index.begin() + 1, light_turned.index.end());
    std::rotate(light_turned.weight.begin(), light_turned.weight.begin() + 1, light_turned.weight.end());
    std::swap(view_turned.index[0], view_turned.index[2]);
    std::swap(view_turned.weight[0], view_turned.weight[2]);
    REQUIRE(l1(by_pair(couple_pair_weights(light_turned, view_turned, PairCoupling::staircase)),
               by_pair(staircase)) < 1e-7);
    largest_difference_from_product =
        std::max(largest_difference_from_product, l1(by_pair(staircase), by_pair(product)));
  }
  // Another interpolation than the product's between the measured pairs (at the centroids of both
  // triangles the product spreads 1/9 over 9 pairs, the staircase 1/3 over 3).
  CHECK(largest_difference_from_product > 0.5);

  SECTION("exact at the measured pairs") {
    for (std::uint32_t i = 0; i < directions.size(); i += 7) {
      for (std::uint32_t j = 0; j < directions.size(); j += 5) {
        const PairMap m =
            by_pair(pair_weights(tri, tri, directions[i].theta, directions[i].phi, directions[j].theta,
                                 directions[j].phi, PairCoupling::staircase));
        INFO("light " << i << ", view " << j);
        REQUIRE(m.size() == 1u);
        REQUIRE(m.begin()->first == std::make_pair(i, j));
        REQUIRE(m.begin()->second == 1.0);
      }
    }
  }
  SECTION("continuous across the edges of either triangulation") {
    // Two light directions either side of each edge, one view between measured directions, and the
    // same with the roles swapped: the pair weights hardly move.
    const DirectionWeights between = direction_weights(tri, 0.55, 2.2);
    int edges = 0;
    for (const auto& t : tri.triangles) {
      for (int e = 0; e < 3; ++e) {
        const auto &a = tri.points[t[e]], &b = tri.points[t[(e + 1) % 3]];
        const double mx = 0.4 * a[0] + 0.6 * b[0], my = 0.4 * a[1] + 0.6 * b[1];
        const double nx = -(b[1] - a[1]), ny = b[0] - a[0];
        const double eps = 1e-7 / std::hypot(nx, ny);
        const auto [t1, p1] = unproject(mx + eps * nx, my + eps * ny);
        const auto [t2, p2] = unproject(mx - eps * nx, my - eps * ny);
        const DirectionWeights one = direction_weights(tri, t1, p1), other = direction_weights(tri, t2, p2);
        INFO("edge " << t[e] << "-" << t[(e + 1) % 3]);
        REQUIRE(l1(by_pair(couple_pair_weights(one, between, PairCoupling::staircase)),
                   by_pair(couple_pair_weights(other, between, PairCoupling::staircase))) < 1e-5);
        REQUIRE(l1(by_pair(couple_pair_weights(between, one, PairCoupling::staircase)),
                   by_pair(couple_pair_weights(between, other, PairCoupling::staircase))) < 1e-5);
        ++edges;
      }
    }
    CHECK(edges > 300);
  }
}

TEST_CASE("degenerate direction sets", "[interpolation]") {
  DirectionTriangulation tri;
  const std::vector<MaterialDirection> one{{0.0f, 0.0f}};
  REQUIRE(build_direction_triangulation(one, tri).ok());
  const DirectionWeights w = direction_weights(tri, 0.7, 2.0);
  CHECK(w.weight[0] == 1.0f);
  CHECK(w.index[0] == 0u);
  const std::vector<MaterialDirection> same{{0.3f, 1.0f}, {0.3f, 1.0f}, {0.5f, 2.0f}};
  CHECK(build_direction_triangulation(same, tri).code() == ErrorCode::invalid_argument);
  const std::vector<MaterialDirection> empty;
  CHECK_FALSE(build_direction_triangulation(empty, tri).ok());
}

TEST_CASE("MaterialDirections builds both sets once and answers weights and the subspaces they need",
          "[interpolation]") {
  Material m = synthetic_material(3, 1);
  MaterialDirections directions;
  REQUIRE(MaterialDirections::build(m, directions, 16).ok());
  CHECK(directions.light_grid().grid_size == 16);
  CHECK(directions.view_triangulation().points.size() == m.views.size());
  DirectionTriangulation lights, views;
  REQUIRE(build_direction_triangulation(m.lights, lights).ok());
  REQUIRE(build_direction_triangulation(m.views, views).ok());
  const PairWeights expected = pair_weights(lights, views, 0.4, 1.0, 0.9, 2.5);
  const PairWeights got = directions.weights(0.4, 1.0, 0.9, 2.5);
  CHECK(got.light == expected.light);
  CHECK(got.view == expected.view);
  CHECK(got.weight == expected.weight);

  std::vector<std::uint32_t> needed;
  for (std::size_t k = 0; k < 9; ++k) {
    const std::uint32_t s = subspace_of(m, got.light[k], got.view[k]);
    if (got.weight[k] != 0.0f && std::find(needed.begin(), needed.end(), s) == needed.end())
      needed.push_back(s);
  }
  CHECK(directions.subspaces_of(got) == needed);
  const std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs = {{6, 6}, {0, 0}, {6, 6}, {1, 0}};
  std::vector<std::uint32_t> of_pairs = {subspace_of(m, 6, 6), subspace_of(m, 0, 0), subspace_of(m, 1, 0)};
  std::sort(of_pairs.begin(), of_pairs.end());
  of_pairs.erase(std::unique(of_pairs.begin(), of_pairs.end()), of_pairs.end());
  CHECK(directions.subspaces_of(pairs) == of_pairs);

  SECTION("a grid size out of range") {
    const Status s = MaterialDirections::build(m, directions, 0);
    CHECK(s.code() == ErrorCode::invalid_argument);
    CHECK_THAT(s.message(), Catch::Contains("outside 1..256"));
  }
  SECTION("an index table of the wrong size") {
    m.subspace_index.pop_back();
    const Status s = MaterialDirections::build(m, directions);
    CHECK(s.code() == ErrorCode::invalid_argument);
    CHECK_THAT(s.message(), Catch::Contains("48 entries for 7 x 7 directions"));
  }
  SECTION("a view set that cannot be triangulated") {
    m.views[1] = m.views[0];
    const Status s = MaterialDirections::build(m, directions);
    CHECK(s.code() == ErrorCode::invalid_argument);
    CHECK_THAT(s.message(), Catch::Contains("view directions: directions 0 and 1 are the same"));
  }
}

TEST_CASE("lookup grids give the triangulation's weights, inside and beyond the measured directions",
          "[interpolation][lookup]") {
  for (const auto& directions : {test::ubo2003_material_directions(), synthetic_material(1, 1).lights}) {
    DirectionTriangulation triangulation;
    REQUIRE(build_direction_triangulation(directions, triangulation).ok());
    for (std::uint32_t grid_size : {1u, 7u, 32u, 64u}) {
      const DirectionLookupGrid grid = build_direction_lookup(triangulation, grid_size);
      REQUIRE(grid.cell_starts.size() == std::size_t{grid_size} * grid_size + 1);
      std::mt19937 random(5);
      std::uniform_real_distribution<double> theta(0.0, 1.5707), phi(0.0, 6.2831);
      double worst = 0.0;
      for (int i = 0; i < 4000; ++i) {
        const double t = theta(random), p = phi(random);
        const auto q = project_direction(t, p);
        const auto expected = as_map(direction_weights(triangulation, t, p));
        const auto actual = as_map(lookup_direction_weights(grid, triangulation, static_cast<float>(q[0]),
                                                            static_cast<float>(q[1])));
        for (const auto& [index, weight] : expected) {
          const double got = actual.count(index) ? actual.at(index) : 0.0;
          worst = std::max(worst, std::abs(got - weight));
        }
        for (const auto& [index, weight] : actual) {
          if (!expected.count(index)) worst = std::max(worst, weight);
        }
      }
      INFO(directions.size() << " directions, grid " << grid_size);
      // Float rounding of the barycentrics; a wrong triangle or edge would differ by O(0.1).
      CHECK(worst < 2e-4);
    }
  }
}

}  // namespace carbtf
