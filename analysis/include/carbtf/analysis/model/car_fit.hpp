// Fitting one 2D causal autoregressive (CAR) model to one band (paper Sec. IV, eq. 1-2; docs/design.md 4.3).
//
// The band is centred and scaled to unit variance first, so every constant below is scale-free and a
// band of 1e-6 or 1e6 fits the same as one of 1. On the normalized band:
// - Prior: normal-gamma with V(0) = delta * I over (Y, X) and beta(0) = beta0 (defaults below): a
//   ridge of delta = 1e-2 against about one unit per sample on the diagonal, enough to keep V_x
//   positive definite for constant, two-valued or perfectly collinear data, and negligible otherwise.
// - Estimates (eq. 2): gamma = V_x^-1 V_xy solved by Cholesky (LLT, LDLT as fallback), never an
//   explicit inverse; lambda = V_y - V_xy^T gamma; sigma^2 = lambda / beta, beta = beta0 + n.
// - Neighbourhood: every candidate is fitted on the same sample positions (those where the largest
//   candidate that fits the band has its full support), and the one with the highest posterior
//   probability (the normal-gamma marginal likelihood, uniform prior over candidates) wins:
//   ln p = -n/2 ln pi + eta/2 ln delta - 1/2 ln|V_x| + beta0/2 ln delta - beta/2 ln lambda
//          + ln Gamma(beta/2) - ln Gamma(beta0/2).
// - Stability: the recursion is stable when the within-row recursion and, for every column frequency,
//   the row-to-row recursion have all characteristic roots inside the unit circle (Ekstrom & Woods'
//   condition for non-symmetric half-plane filters; engine/car_stability.hpp); car_spectral_radius() gives
//   the largest root modulus. If it exceeds 1 - stability_margin (unstable, or so close to a unit root that
//   synthesis would drift), gamma is repaired by shrinking it towards zero, gamma *= s with the largest s
//   (found by bisection) that meets the margin, and sigma is rescaled so the model's stationary variance
//   equals the band's variance. The band is flagged car_band_repaired and the log says so.
// - A constant band gets no neighbours and sigma 0; a band too small for any candidate (fewer than
//   4 (eta + 1) + 8 samples) is white noise of the band's variance.
#pragma once

#include <string>
#include <vector>

#include "carbtf/analysis/model/plane.hpp"
#include "carbtf/engine/material/car_stability.hpp"  // car_spectral_radius, car_roots_within
#include "carbtf/engine/material/material.hpp"

namespace carbtf {

// The candidate neighbourhoods, smallest first: the paper's fewer-than-four-neighbour ones (left, up,
// left+up, and the two 3-neighbour ones), then the 4-neighbour half-plane, 6 and 10 neighbours, and
// the full radius-2 half-plane of 12.
const std::vector<std::vector<CarNeighbour>>& car_candidate_neighbourhoods();

struct CarFitOptions {
  double prior_delta = 1e-2;       // V(0) = delta * I on the unit-variance band
  double prior_beta0 = 1.0;        // beta(0)
  double stability_margin = 0.01;  // required distance of every characteristic root from the unit circle
  int max_candidate = -1;          // consider candidates 0..max_candidate (-1: all)
  int only_candidate = -1;         // fit this candidate only (tests; -1: select by posterior)
};

struct CarFit {
  CarBandModel model;
  int candidate = -1;                        // the chosen candidate, -1 for constant / white noise
  std::vector<double> log_posterior;         // per candidate considered (-inf when it did not fit)
  std::vector<double> gamma_standard_error;  // posterior standard deviation of each gamma (unit band)
  std::size_t samples = 0;                   // n
  double fitted_spectral_radius = 0.0;       // before any repair
  double spectral_radius = 0.0;              // of the stored model
  double shrink = 1.0;                       // the repair factor s (1: no repair)
  std::string note;                          // empty, or what was repaired and why (for the log)
};

CarFit fit_car_band(const Plane& band, const CarFitOptions& options = {});

// Stationary variance of the recursion driven by unit-variance white noise: the mean of 1 / |A|^2 over
// a grid of `grid` x `grid` frequencies (finite only for a stable recursion).
double car_stationary_gain(const std::vector<CarNeighbour>& neighbourhood, const std::vector<double>& gamma,
                           int grid = 128);

}  // namespace carbtf
