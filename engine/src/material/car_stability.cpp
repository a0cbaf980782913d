#include "carbtf/engine/material/car_stability.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>

namespace carbtf {
namespace {

using Complex = std::complex<double>;

// Schur-Cohn: with p(z) = sum a_k z^k of degree n and p*(z) = z^n conj(p(1 / conj z)), when
// |a_0| < |a_n| the polynomial conj(a_n) p - a_0 p* = z q(z) has as many roots inside the unit disc as
// p has, less one, and q has degree n - 1 (Rouche on |z| = 1, where |p*| = |p|). If |a_0| >= |a_n| the
// product of the roots has modulus >= 1, so not every root is inside.
bool roots_inside_unit_disc(std::vector<Complex> a) {
  while (a.size() > 1) {
    const std::size_t n = a.size() - 1;
    const Complex lead = a[n], constant = a[0];
    if (!(std::abs(constant) < std::abs(lead))) return false;
    std::vector<Complex> reduced(n);
    double scale = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
      reduced[k] = std::conj(lead) * a[k + 1] - constant * std::conj(a[n - k - 1]);
      scale = std::max(scale, std::abs(reduced[k]));
    }
    if (!(scale > 0.0) || !std::isfinite(scale)) return false;
    for (Complex& c : reduced) c /= scale;  // keeps the magnitudes from squaring away at each step
    a = std::move(reduced);
  }
  return true;
}

// Every root of sum a_k z^k (ascending, a.back() the leading coefficient) has modulus < radius.
bool roots_within(std::vector<Complex> a, double radius) {
  double power = 1.0;
  for (Complex& c : a) {
    c *= power;
    power *= radius;
  }
  return roots_inside_unit_disc(std::move(a));
}

}  // namespace

bool car_roots_within(const std::vector<CarNeighbour>& neighbourhood, const std::vector<double>& gamma,
                      double radius, int frequencies) {
  if (gamma.size() != neighbourhood.size() || !(radius > 0.0)) return false;
  for (double g : gamma) {
    if (!std::isfinite(g)) return false;
  }
  // Within-row recursion y[c] = sum_{dr = 0} gamma y[c + dc] + input: z^q - sum gamma z^(q + dc).
  int row_order = 0, up = 0;
  for (CarNeighbour n : neighbourhood) {
    if (n.dr == 0) row_order = std::max(row_order, -int{n.dc});
    up = std::max(up, -int{n.dr});
  }
  std::vector<Complex> row(static_cast<std::size_t>(row_order) + 1, 0.0);
  row[static_cast<std::size_t>(row_order)] = 1.0;
  for (std::size_t k = 0; k < neighbourhood.size(); ++k) {
    if (neighbourhood[k].dr == 0) row[static_cast<std::size_t>(row_order + neighbourhood[k].dc)] -= gamma[k];
  }
  if (!roots_within(row, radius)) return false;
  if (up == 0) return true;
  // Row to row, per column frequency: a0(w) z^q - sum_j a_j(w) z^(q - j).
  for (int f = 0; f < frequencies; ++f) {
    const double w = 2.0 * std::numbers::pi * f / frequencies;
    std::vector<Complex> poly(static_cast<std::size_t>(up) + 1, 0.0);
    poly[static_cast<std::size_t>(up)] = 1.0;
    for (std::size_t k = 0; k < neighbourhood.size(); ++k) {
      const Complex term = gamma[k] * std::polar(1.0, w * neighbourhood[k].dc);
      const int j = -int{neighbourhood[k].dr};
      poly[static_cast<std::size_t>(up - j)] -= term;
    }
    if (std::abs(poly[static_cast<std::size_t>(up)]) < 1e-12) return false;
    if (!roots_within(poly, radius)) return false;
  }
  return true;
}

double car_spectral_radius(const std::vector<CarNeighbour>& neighbourhood, const std::vector<double>& gamma,
                           int frequencies) {
  constexpr double kLargest = 1e6;
  if (!car_roots_within(neighbourhood, gamma, kLargest, frequencies))
    return std::numeric_limits<double>::infinity();
  double inside = 1.0, outside = 0.0;  // every root has modulus < inside; some root has modulus >= outside
  while (!car_roots_within(neighbourhood, gamma, inside, frequencies)) {
    outside = inside;
    inside *= 2.0;
  }
  for (int i = 0; i < 64 && inside - outside > 1e-13 * inside; ++i) {
    const double middle = 0.5 * (inside + outside);
    (car_roots_within(neighbourhood, gamma, middle, frequencies) ? inside : outside) = middle;
  }
  return inside;
}

}  // namespace carbtf
