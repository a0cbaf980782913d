#include "carbtf/analysis/model/car_fit.hpp"

#include "carbtf/engine/material/car_stability.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>

namespace carbtf {
namespace {

using Complex = std::complex<double>;

// Gammas are rounded to a power-of-two step of at most this share of their posterior standard error:
// each moves by at most 1/16 of its own uncertainty. 1/32 measured the same calibrated fidelity on
// leather at 256^2, pair for pair to three decimals, in a file 0.8 KB larger.
constexpr double kGammaStepPerError = 1.0 / 8.0;

struct Reach {
  int up = 0, left = 0, right = 0;  // rows above, columns left and right the support needs
};

Reach reach_of(const std::vector<CarNeighbour>& neighbourhood) {
  Reach reach;
  for (CarNeighbour n : neighbourhood) {
    reach.up = std::max(reach.up, -int{n.dr});
    reach.left = std::max(reach.left, -int{n.dc});
    reach.right = std::max(reach.right, int{n.dc});
  }
  return reach;
}

std::size_t sample_count(const Reach& reach, Eigen::Index rows, Eigen::Index cols) {
  const Eigen::Index r = rows - reach.up;
  const Eigen::Index c = cols - reach.left - reach.right;
  return r > 0 && c > 0 ? static_cast<std::size_t>(r * c) : 0;
}

std::size_t minimum_samples(std::size_t neighbours) {
  return 4 * (neighbours + 1) + 8;
}

struct CandidateFit {
  bool ok = false;
  double log_posterior = -std::numeric_limits<double>::infinity();
  Eigen::VectorXd gamma;
  double lambda = 0.0;
  Eigen::VectorXd gamma_variance_factor;  // diag(V_x^-1), for standard errors only
};

// Fits the candidate whose neighbours sit at `columns` (1-based, into the accumulated matrix).
CandidateFit fit_candidate(const Eigen::MatrixXd& accumulated, const std::vector<Eigen::Index>& columns,
                           std::size_t samples, const CarFitOptions& options) {
  const auto eta = static_cast<Eigen::Index>(columns.size());
  Eigen::MatrixXd vx(eta, eta);
  Eigen::VectorXd vxy(eta);
  for (Eigen::Index i = 0; i < eta; ++i) {
    vxy(i) = accumulated(columns[i], 0);
    for (Eigen::Index j = 0; j < eta; ++j) vx(i, j) = accumulated(columns[i], columns[j]);
  }
  vx.diagonal().array() += options.prior_delta;
  const double vy = accumulated(0, 0) + options.prior_delta;
  CandidateFit fit;
  double log_det = 0.0;
  Eigen::LLT<Eigen::MatrixXd> llt(vx);
  if (llt.info() == Eigen::Success) {
    fit.gamma = llt.solve(vxy);
    log_det = 2.0 * llt.matrixLLT().diagonal().array().log().sum();
    fit.gamma_variance_factor = llt.solve(Eigen::MatrixXd::Identity(eta, eta)).diagonal();
  } else {
    Eigen::LDLT<Eigen::MatrixXd> ldlt(vx);
    if (ldlt.info() != Eigen::Success || (ldlt.vectorD().array() <= 0.0).any()) return fit;
    fit.gamma = ldlt.solve(vxy);
    log_det = ldlt.vectorD().array().log().sum();
    fit.gamma_variance_factor = ldlt.solve(Eigen::MatrixXd::Identity(eta, eta)).diagonal();
  }
  fit.lambda = std::max(vy - vxy.dot(fit.gamma), std::numeric_limits<double>::min());
  const double beta = options.prior_beta0 + static_cast<double>(samples);
  // Terms common to every candidate (n, beta, beta0, the pi and Gamma factors) are left out.
  fit.log_posterior = 0.5 * static_cast<double>(eta) * std::log(options.prior_delta) - 0.5 * log_det -
                      0.5 * beta * std::log(fit.lambda);
  fit.ok = std::isfinite(fit.log_posterior) && fit.gamma.allFinite();
  return fit;
}

std::vector<double> to_vector(const Eigen::VectorXd& v) {
  return {v.data(), v.data() + v.size()};
}

}  // namespace

const std::vector<std::vector<CarNeighbour>>& car_candidate_neighbourhoods() {
  using N = CarNeighbour;
  static const std::vector<std::vector<CarNeighbour>> candidates{
      {N{0, -1}},
      {N{-1, 0}},
      {N{0, -1}, N{-1, 0}},
      {N{0, -1}, N{-1, 0}, N{-1, -1}},
      {N{0, -1}, N{-1, 0}, N{-1, 1}},
      {N{0, -1}, N{-1, -1}, N{-1, 0}, N{-1, 1}},
      {N{0, -1}, N{0, -2}, N{-1, -1}, N{-1, 0}, N{-1, 1}, N{-2, 0}},
      {N{0, -1}, N{0, -2}, N{-1, -2}, N{-1, -1}, N{-1, 0}, N{-1, 1}, N{-1, 2}, N{-2, -1}, N{-2, 0}, N{-2, 1}},
      {N{0, -1}, N{0, -2}, N{-1, -2}, N{-1, -1}, N{-1, 0}, N{-1, 1}, N{-1, 2}, N{-2, -2}, N{-2, -1}, N{-2, 0},
       N{-2, 1}, N{-2, 2}},
  };
  return candidates;
}

double car_stationary_gain(const std::vector<CarNeighbour>& neighbourhood, const std::vector<double>& gamma,
                           int grid) {
  double sum = 0.0;
  for (int i = 0; i < grid; ++i) {
    for (int j = 0; j < grid; ++j) {
      const double w1 = 2.0 * std::numbers::pi * i / grid;
      const double w2 = 2.0 * std::numbers::pi * j / grid;
      Complex a = 1.0;
      for (std::size_t k = 0; k < neighbourhood.size(); ++k)
        a -= gamma[k] * std::polar(1.0, w1 * neighbourhood[k].dr + w2 * neighbourhood[k].dc);
      sum += 1.0 / std::norm(a);
    }
  }
  return sum / (double(grid) * grid);
}

CarFit fit_car_band(const Plane& band, const CarFitOptions& options) {
  CarFit result;
  const double mean = band.size() ? band.mean() : 0.0;
  const double variance = band.size() ? (band - mean).square().mean() : 0.0;
  const double deviation = std::sqrt(variance);
  result.model.mean = static_cast<float>(mean);
  result.model.band_std = static_cast<float>(deviation);
  // Differences below float resolution of the mean cannot be stored or synthesized: constant.
  if (!(deviation > 0.0) || deviation <= 1e-7 * std::abs(mean)) {
    result.model.flags = car_band_constant;
    result.model.band_std = 0.0f;
    result.note = "constant band: no neighbours, sigma 0";
    return result;
  }
  const Plane z = (band - mean) / deviation;

  const auto& all = car_candidate_neighbourhoods();
  std::vector<int> considered;
  if (options.only_candidate >= 0) {
    considered.push_back(options.only_candidate);
  } else {
    const int last = options.max_candidate < 0
                         ? static_cast<int>(all.size()) - 1
                         : std::min<int>(options.max_candidate, static_cast<int>(all.size()) - 1);
    for (int c = 0; c <= last; ++c) considered.push_back(c);
  }
  // Drop candidates the band cannot support, then use the union's sample positions for all of them.
  std::vector<CarNeighbour> union_neighbours;
  for (bool changed = true; changed;) {
    union_neighbours.clear();
    for (int c : considered) {
      for (CarNeighbour n : all[static_cast<std::size_t>(c)]) {
        if (std::find(union_neighbours.begin(), union_neighbours.end(), n) == union_neighbours.end())
          union_neighbours.push_back(n);
      }
    }
    const std::size_t n = sample_count(reach_of(union_neighbours), z.rows(), z.cols());
    const auto before = considered.size();
    std::erase_if(considered,
                  [&](int c) { return n < minimum_samples(all[static_cast<std::size_t>(c)].size()); });
    changed = considered.size() != before;
  }
  if (considered.empty()) {
    result.model.flags = car_band_white_noise;
    result.model.sigma = static_cast<float>(deviation);
    result.note = "band of " + std::to_string(z.cols()) + "x" + std::to_string(z.rows()) +
                  " is too small for any neighbourhood: white noise";
    return result;
  }
  const Reach reach = reach_of(union_neighbours);
  const std::size_t samples = sample_count(reach, z.rows(), z.cols());
  result.samples = samples;

  // Data matrix: one row per sample position, [Y, X in union order]; V~ = D^T D.
  const auto width = static_cast<Eigen::Index>(union_neighbours.size()) + 1;
  Eigen::MatrixXd data(static_cast<Eigen::Index>(samples), width);
  Eigen::Index row = 0;
  for (Eigen::Index r = reach.up; r < z.rows(); ++r) {
    for (Eigen::Index c = reach.left; c < z.cols() - reach.right; ++c, ++row) {
      data(row, 0) = z(r, c);
      for (Eigen::Index k = 1; k < width; ++k) {
        const CarNeighbour n = union_neighbours[static_cast<std::size_t>(k - 1)];
        data(row, k) = z(r + n.dr, c + n.dc);
      }
    }
  }
  const Eigen::MatrixXd accumulated = data.transpose() * data;

  CandidateFit best;
  for (int c : considered) {
    std::vector<Eigen::Index> columns;
    for (CarNeighbour n : all[static_cast<std::size_t>(c)]) {
      columns.push_back(
          1 + (std::find(union_neighbours.begin(), union_neighbours.end(), n) - union_neighbours.begin()));
    }
    CandidateFit fit = fit_candidate(accumulated, columns, samples, options);
    result.log_posterior.push_back(fit.log_posterior);
    if (fit.ok && (!best.ok || fit.log_posterior > best.log_posterior)) {
      best = std::move(fit);
      result.candidate = c;
    }
  }
  if (!best.ok) {
    result.model.flags = car_band_white_noise;
    result.model.sigma = static_cast<float>(deviation);
    result.note = "no neighbourhood could be fitted: white noise";
    return result;
  }
  const double beta = options.prior_beta0 + static_cast<double>(samples);
  double sigma2 = best.lambda / beta;
  std::vector<double> gamma = to_vector(best.gamma);
  const auto& neighbourhood = all[static_cast<std::size_t>(result.candidate)];
  for (Eigen::Index k = 0; k < best.gamma.size(); ++k)
    result.gamma_standard_error.push_back(std::sqrt(sigma2 * best.gamma_variance_factor(k)));

  result.fitted_spectral_radius = car_spectral_radius(neighbourhood, gamma);
  result.spectral_radius = result.fitted_spectral_radius;
  const double limit = 1.0 - options.stability_margin;
  if (!(result.fitted_spectral_radius <= limit)) {
    double stable = 0.0, unstable = 1.0;
    for (int i = 0; i < 40; ++i) {
      const double s = 0.5 * (stable + unstable);
      std::vector<double> shrunk = gamma;
      for (double& g : shrunk) g *= s;
      (car_roots_within(neighbourhood, shrunk, limit) ? stable : unstable) = s;
    }
    for (double& g : gamma) g *= stable;
    result.shrink = stable;
    result.spectral_radius = car_spectral_radius(neighbourhood, gamma);
    sigma2 = 1.0 / car_stationary_gain(neighbourhood, gamma);
    result.model.flags |= car_band_repaired;
    char text[200];
    std::snprintf(text, sizeof text,
                  "fitted recursion has spectral radius %.4f (limit %.4f): gamma shrunk by %.4f, sigma "
                  "rescaled to the band variance",
                  result.fitted_spectral_radius, limit, stable);
    result.note = text;
  }
  // Each gamma is stored to the precision its estimate has: rounded to a power-of-two step of at most
  // kGammaStepPerError of its posterior standard error, which clears the low mantissa bits that carry
  // only estimation noise so that the file deflates them (3-3.5 KB of a 256^2 material). The
  // recursion moves by far less than its own uncertainty; the rounding is kept only where the rounded
  // recursion keeps the stability margin.
  std::vector<double> rounded = gamma;
  for (std::size_t k = 0; k < rounded.size(); ++k) {
    const double error = k < result.gamma_standard_error.size() ? result.gamma_standard_error[k] : 0.0;
    if (!(error > 0.0) || !std::isfinite(error)) continue;
    const double step = std::exp2(std::floor(std::log2(kGammaStepPerError * error)));
    rounded[k] = std::round(rounded[k] / step) * step;
  }
  if (car_roots_within(neighbourhood, rounded, limit)) gamma = rounded;
  result.model.neighbourhood = neighbourhood;
  for (double g : gamma) result.model.gamma.push_back(static_cast<float>(g));
  result.model.sigma = static_cast<float>(std::sqrt(sigma2) * deviation);
  return result;
}

}  // namespace carbtf
