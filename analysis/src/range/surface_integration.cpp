#include "carbtf/analysis/range/surface_integration.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "../quality/fourier_2d.hpp"
#include "median.hpp"

namespace carbtf {
namespace {

// The equations' weights before the robust reweighting. A central difference spans two texels:
// (h[+1] - h[-1]) / 2 = g, weight 1, is h[+1] - h[-1] = 2 g at weight 1/4.
constexpr double kCentralWeight = 0.25;
constexpr double kEvenOddTie = 0.1;

// One equation of the fit: weight x (heights[to] - heights[from] - step)^2 in the sum minimized.
struct StepEquation {
  int from = 0;
  int to = 0;
  double step = 0.0;
  double scale = 0.0;   // the equation's own weight
  double weight = 0.0;  // scale x its robust weight
};

// The equations of a periodic width x height grid with gradients p (along a row) and q (down a
// column). Per texel and direction: the render pass's central difference, h[+1] - h[-1] = 2 g, and a
// weaker forward difference, h[+1] - h[0] = the mean of the two texels' g, since the central
// differences alone never compare neighbouring texels and would leave a checkerboard free.
std::vector<StepEquation> step_equations(const std::vector<double>& p, const std::vector<double>& q,
                                         std::uint32_t width, std::uint32_t height) {
  std::vector<StepEquation> equations;
  equations.reserve(std::size_t{width} * height * 4);
  const auto add = [&](std::size_t from, std::size_t to, double step, double scale) {
    equations.push_back({static_cast<int>(from), static_cast<int>(to), step, scale, scale});
  };
  for (std::uint32_t r = 0; r < height; ++r) {
    const std::size_t row = std::size_t{r} * width, above = std::size_t{(r + height - 1) % height} * width,
                      below = std::size_t{(r + 1) % height} * width;
    for (std::uint32_t c = 0; c < width; ++c) {
      const std::uint32_t left = (c + width - 1) % width, right = (c + 1) % width;
      const std::size_t i = row + c;
      add(row + left, row + right, 2.0 * p[i], kCentralWeight);
      add(above + c, below + c, 2.0 * q[i], kCentralWeight);
      add(i, row + right, 0.5 * (p[i] + p[row + right]), kEvenOddTie);
      add(i, below + c, 0.5 * (q[i] + q[below + c]), kEvenOddTie);
    }
  }
  return equations;
}

// The weighted least-squares heights of `equations` (those of step_equations() for a width x height
// grid), by conjugate gradients preconditioned with the same system at full weight: that one is
// circulant, so the Fourier transform solves it exactly, and the robust weights, which only lower
// some equations' weights, leave it solvable. The creases' low weights cost iterations (from 90 for
// the first reweighting to 450 for the last, at 256^2): 2.3 s at 256^2 and 23 s at 512^2 on this
// project's 2-core machine, where a sparse Cholesky factorization of the periodic grid's system,
// which fills in, took 9 and 170 s. The heights are defined up to a constant; the iterates keep a
// zero mean.
class WeightedPoisson {
 public:
  WeightedPoisson(std::uint32_t width, std::uint32_t height) : width_(width), height_(height) {
    symbol_.resize(std::size_t{width} * height);
    for (std::uint32_t r = 0; r < height; ++r) {
      const double wy = 2.0 * std::numbers::pi * detail::signed_frequency(r, height);
      for (std::uint32_t c = 0; c < width; ++c) {
        const double wx = 2.0 * std::numbers::pi * detail::signed_frequency(c, width);
        double value = 0.0;
        for (const double w : {wx, wy})
          value += kCentralWeight * (2.0 - 2.0 * std::cos(2.0 * w)) + kEvenOddTie * (2.0 - 2.0 * std::cos(w));
        symbol_[std::size_t{r} * width + c] = value;
      }
    }
  }

  // From `heights` (the last solution, or zeros) to the solution for `equations`' weights.
  Eigen::VectorXd solve(const std::vector<StepEquation>& equations, Eigen::VectorXd heights) const {
    Eigen::VectorXd right_side = Eigen::VectorXd::Zero(heights.size());
    for (const StepEquation& e : equations) {
      right_side[e.to] += e.weight * e.step;
      right_side[e.from] -= e.weight * e.step;
    }
    Eigen::VectorXd residual = right_side - apply(equations, heights);
    Eigen::VectorXd preconditioned = precondition(residual);
    Eigen::VectorXd direction = preconditioned;
    double alignment = residual.dot(preconditioned);
    const double target = kIntegrationTolerance * right_side.norm();
    for (int iteration = 0; iteration < kMaxIterations && residual.norm() > target; ++iteration) {
      const Eigen::VectorXd applied = apply(equations, direction);
      const double curvature = direction.dot(applied);
      if (!(curvature > 0.0)) break;
      const double step = alignment / curvature;
      heights += step * direction;
      residual -= step * applied;
      preconditioned = precondition(residual);
      const double next = residual.dot(preconditioned);
      direction = preconditioned + (next / alignment) * direction;
      alignment = next;
    }
    return heights;
  }

 private:
  // The residual's norm at which a solve stops, relative to the right side's: the heights then agree
  // with a direct solve's to 1e-4 texels (leather, 256^2), far below the stored heights' step.
  static constexpr double kIntegrationTolerance = 1e-5;
  static constexpr int kMaxIterations = 2000;

  // The normal equations' matrix (a weighted graph Laplacian) times x.
  static Eigen::VectorXd apply(const std::vector<StepEquation>& equations, const Eigen::VectorXd& x) {
    Eigen::VectorXd result = Eigen::VectorXd::Zero(x.size());
    for (const StepEquation& e : equations) {
      const double flow = e.weight * (x[e.to] - x[e.from]);
      result[e.to] += flow;
      result[e.from] -= flow;
    }
    return result;
  }

  // The full-weight system solved for `residual`, without its constant part (the null space).
  Eigen::VectorXd precondition(const Eigen::VectorXd& residual) const {
    detail::ComplexField field(residual.data(), residual.data() + residual.size());
    detail::fourier_2d(field, width_, height_);
    field[0] = 0.0;
    for (std::size_t i = 1; i < field.size(); ++i) field[i] /= symbol_[i];
    detail::fourier_2d(field, width_, height_, true);
    Eigen::VectorXd result(residual.size());
    for (Eigen::Index i = 0; i < result.size(); ++i) result[i] = field[static_cast<std::size_t>(i)].real();
    return result;
  }

  std::uint32_t width_, height_;
  std::vector<double> symbol_;  // the full-weight system's eigenvalue per frequency
};

}  // namespace

Plane integrate_normals(std::span<const float> normals, std::uint32_t width, std::uint32_t height) {
  const std::size_t pixels = std::size_t{width} * height;
  if (normals.size() < pixels * 3 || pixels == 0)
    throw std::invalid_argument("integrate_normals: the normal map is empty or too small");
  // Gradients in image coordinates: dh/dcol = -nx / nz, dh/drow = +ny / nz (row grows downwards, y up).
  std::vector<double> p(pixels), q(pixels);
  for (std::size_t i = 0; i < pixels; ++i) {
    const double nz = std::max(double{normals[i * 3 + 2]}, 0.1);
    p[i] = -double{normals[i * 3]} / nz;
    q[i] = double{normals[i * 3 + 1]} / nz;
  }
  std::vector<StepEquation> equations = step_equations(p, q, width, height);
  const WeightedPoisson poisson(width, height);
  Eigen::VectorXd heights =
      poisson.solve(equations, Eigen::VectorXd::Zero(static_cast<Eigen::Index>(pixels)));
  std::vector<double> residuals(equations.size());
  for (int round = 0; round < kRobustIntegrationRounds; ++round) {
    for (std::size_t e = 0; e < equations.size(); ++e)
      residuals[e] = std::abs(heights[equations[e].to] - heights[equations[e].from] - equations[e].step);
    // Cauchy weights at the residuals' robust standard deviation: an equation far off the surface the
    // others agree on (a crease's wrong normal) counts little, one near it fully.
    const double spread = std::max(1.4826 * detail::median(residuals), 1e-6);
    for (std::size_t e = 0; e < equations.size(); ++e) {
      const double relative = residuals[e] / spread;
      equations[e].weight = equations[e].scale / (1.0 + relative * relative);
    }
    heights = poisson.solve(equations, heights);
  }
  Plane range(height, width);
  for (std::uint32_t r = 0; r < height; ++r) {
    for (std::uint32_t c = 0; c < width; ++c)
      range(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = heights[std::size_t{r} * width + c];
  }
  range -= range.mean();
  return range;
}

}  // namespace carbtf
