// Stability of a 2D causal autoregressive (CAR) recursion, shared by the analysis (which repairs fitted
// models that miss the margin) and validate_material() (which refuses files that miss it), so that a
// material is accepted exactly when the analysis could have written it.
//
// The recursion y(r) = sum_k gamma[k] y(r + n_k) + e(r) on a non-symmetric half-plane is stable when
// the within-row recursion and, for every column frequency w, the row-to-row recursion
// a0(w) Y_r = sum_j a_j(w) Y_{r-j} have all characteristic roots inside the unit circle (Ekstrom &
// Woods). Roots are never computed: the Schur-Cohn reduction decides whether every root of a
// polynomial lies inside a disc, exactly up to rounding, with no iteration that could fail to converge.
//
// Thread safety: pure functions. Cost: O(frequencies * order^2) per decision, order <= 16 here.
#pragma once

#include <vector>

#include "carbtf/engine/material/material.hpp"

namespace carbtf {

// True when every characteristic root of the recursion has modulus < `radius`, checked at
// `frequencies` evenly spaced column frequencies. gamma has one entry per neighbour.
bool car_roots_within(const std::vector<CarNeighbour>& neighbourhood, const std::vector<double>& gamma,
                      double radius, int frequencies = 256);

// The largest characteristic root modulus (< 1: stable), to about 1e-12 by bisection on
// car_roots_within(); +infinity when it exceeds 1e6 or the recursion is degenerate.
double car_spectral_radius(const std::vector<CarNeighbour>& neighbourhood, const std::vector<double>& gamma,
                           int frequencies = 256);

// The margin validate_material() demands: every root modulus below 1 - kCarStabilityMargin. It is half
// the analysis's default margin, so that rounding the fitted gamma to float32 keeps a fitted model valid.
inline constexpr double kCarStabilityMargin = 0.005;

}  // namespace carbtf
