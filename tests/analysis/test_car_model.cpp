// The CAR estimator, neighbourhood selection and stability repair (analysis/model/car_fit.hpp), on
// fields made by the CPU reference recursion (analysis/reference/include/carbtf/reference/car_synthesis.hpp).
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "carbtf/analysis/model/car_fit.hpp"
#include "carbtf/engine/internal/synthesis_layout.hpp"
#include "carbtf/reference/car_synthesis.hpp"
#include "carbtf/reference/noise.hpp"

namespace carbtf {
namespace {

CarBandModel true_model(int candidate, std::vector<float> gamma, float sigma, float mean = 0.0f) {
  CarBandModel model;
  model.neighbourhood = car_candidate_neighbourhoods().at(static_cast<std::size_t>(candidate));
  model.gamma = std::move(gamma);
  model.sigma = sigma;
  model.mean = mean;
  return model;
}

Plane synthesize_plane(const CarBandModel& model, std::uint32_t size, std::uint64_t seed,
                       std::uint32_t margin = 64) {
  reference::CarFieldBlock block;
  block.seed = seed;
  block.width = block.height = size;
  block.margin = margin;
  std::vector<float> values(std::size_t{size} * size);
  reference::synthesize_car_block(model, block, values);
  Plane plane(size, size);
  for (std::uint32_t i = 0; i < size * size; ++i) plane(i / size, i % size) = values[i];
  return plane;
}

double synthesized_max_deviation(const CarBandModel& model, std::uint32_t size) {
  reference::CarFieldBlock block;
  block.seed = 99;
  block.width = block.height = size;
  std::vector<float> values(std::size_t{size} * size);
  reference::synthesize_car_block(model, block, values);
  double worst = 0.0;
  for (float v : values) {
    if (!std::isfinite(v)) return INFINITY;
    worst = std::max(worst, std::abs(double{v} - model.mean));
  }
  return worst;
}

struct KnownModel {
  int candidate;
  std::vector<float> gamma;
};

const std::vector<KnownModel>& known_models() {
  static const std::vector<KnownModel> models{
      {0, {0.6f}},
      {2, {0.45f, 0.35f}},
      {3, {0.5f, 0.4f, -0.2f}},
      {5, {0.4f, -0.15f, 0.45f, 0.2f}},
      {6, {0.5f, -0.1f, -0.15f, 0.4f, 0.1f, 0.1f}},
  };
  return models;
}

}  // namespace

TEST_CASE(
    "the CAR estimator recovers gamma and sigma^2 of synthetic fields within 5 standard errors and stores "
    "gamma to that precision",
    "[car]") {
  for (const KnownModel& known : known_models()) {
    const CarBandModel truth = true_model(known.candidate, known.gamma, 0.7f, 2.0f);
    REQUIRE(car_spectral_radius(truth.neighbourhood, {known.gamma.begin(), known.gamma.end()}) < 0.95);
    const Plane field = synthesize_plane(truth, 256, 1000 + known.candidate);
    CarFitOptions options;
    options.only_candidate = known.candidate;
    const CarFit fit = fit_car_band(field, options);
    INFO("candidate " << known.candidate);
    REQUIRE(fit.candidate == known.candidate);
    REQUIRE(fit.model.flags == 0u);
    REQUIRE(fit.model.gamma.size() == known.gamma.size());
    for (std::size_t k = 0; k < known.gamma.size(); ++k) {
      INFO("gamma " << k << ": fitted " << fit.model.gamma[k] << ", true " << known.gamma[k] << ", se "
                    << fit.gamma_standard_error[k]);
      CHECK(std::abs(fit.model.gamma[k] - known.gamma[k]) <= 5.0 * fit.gamma_standard_error[k]);
      CHECK(fit.gamma_standard_error[k] < 0.01);
      // Stored to the precision of its estimate: a multiple of the power-of-two step at most 1/8 of
      // its standard error, so the bits below carry nothing the file has to keep.
      const double step = std::exp2(std::floor(std::log2(fit.gamma_standard_error[k] / 8.0)));
      CHECK(std::fmod(double{fit.model.gamma[k]}, step) == 0.0);
    }
    const double sigma2 = double{fit.model.sigma} * fit.model.sigma;
    const double true_sigma2 = 0.49;
    INFO("sigma^2 fitted " << sigma2 << ", true " << true_sigma2);
    CHECK(std::abs(sigma2 / true_sigma2 - 1.0) <= 5.0 * std::sqrt(2.0 / static_cast<double>(fit.samples)));
  }
}

TEST_CASE("neighbourhood selection by posterior probability picks the true neighbourhood", "[car]") {
  for (const KnownModel& known : known_models()) {
    const CarBandModel truth = true_model(known.candidate, known.gamma, 1.0f);
    for (std::uint64_t seed : {7u, 8u}) {
      const Plane field = synthesize_plane(truth, 192, seed * 31 + known.candidate);
      const CarFit fit = fit_car_band(field);
      INFO("true candidate " << known.candidate << ", seed " << seed);
      CHECK(fit.candidate == known.candidate);
      CHECK(fit.log_posterior.size() == car_candidate_neighbourhoods().size());
    }
  }
}

TEST_CASE("spectral radius: stable, unit-root and explosive recursions", "[car]") {
  const auto& left = car_candidate_neighbourhoods()[0];
  CHECK(car_spectral_radius(left, {0.5}) == Approx(0.5));
  CHECK(car_spectral_radius(left, {-1.2}) == Approx(1.2));
  const auto& left_up = car_candidate_neighbourhoods()[2];
  CHECK(car_spectral_radius(left_up, {0.4, 0.4}) < 1.0);
  CHECK(car_spectral_radius(left_up, {0.5, 0.5}) >= 0.999);  // gain 1 at frequency 0: a unit root
  CHECK(car_spectral_radius(left_up, {0.6, 0.6}) > 1.0);
  // The stationary gain of a first-order recursion is 1 / (1 - a^2).
  CHECK(car_stationary_gain(left, {0.6}) == Approx(1.0 / (1.0 - 0.36)).epsilon(1e-6));
}

TEST_CASE("stiff and extreme bands give bounded models, and repairs are reported", "[car][stiff]") {
  const std::uint32_t size = 128;
  auto random_plane = [&](std::uint64_t seed) {
    Plane plane(size, size);
    for (std::uint32_t r = 0; r < size; ++r)
      for (std::uint32_t c = 0; c < size; ++c)
        plane(r, c) =
            reference::gaussian_noise(seed, 0, static_cast<std::int32_t>(r), static_cast<std::int32_t>(c));
    return plane;
  };
  auto require_bounded = [&](const CarFit& fit, const char* what) {
    INFO(what << ": note '" << fit.note << "', radius " << fit.spectral_radius);
    REQUIRE(fit.spectral_radius <= 0.99 + 1e-9);
    const double worst = synthesized_max_deviation(fit.model, 512);
    REQUIRE(std::isfinite(worst));
    // A stationary Gaussian field of 512^2 samples stays within about 6 standard deviations.
    REQUIRE(worst <= 8.0 * std::max<double>(fit.model.band_std, 1e-30) + 1e-30);
  };

  SECTION("non-stationary: a random walk in both directions (unit root)") {
    Plane walk = random_plane(1);
    for (Eigen::Index r = 0; r < walk.rows(); ++r)
      for (Eigen::Index c = 1; c < walk.cols(); ++c) walk(r, c) += walk(r, c - 1);
    for (Eigen::Index r = 1; r < walk.rows(); ++r) walk.row(r) += walk.row(r - 1);
    const CarFit fit = fit_car_band(walk);
    CHECK(fit.fitted_spectral_radius > 0.99);
    CHECK((fit.model.flags & car_band_repaired) != 0u);
    CHECK_FALSE(fit.note.empty());
    require_bounded(fit, "random walk");
  }
  SECTION("near unit root: a smooth ramp with a little noise") {
    Plane ramp = random_plane(2) * 1e-3;
    for (Eigen::Index r = 0; r < ramp.rows(); ++r)
      for (Eigen::Index c = 0; c < ramp.cols(); ++c) ramp(r, c) += 0.01 * double(r + c);
    require_bounded(fit_car_band(ramp), "ramp");
  }
  SECTION("explosive recursion of a synthetic model is detected and repaired") {
    const auto& left_up = car_candidate_neighbourhoods()[2];
    CHECK(car_spectral_radius(left_up, {0.7, 0.7}) > 1.0);
  }
  SECTION("constant band") {
    const CarFit fit = fit_car_band(Plane::Constant(size, size, 0.25));
    CHECK(fit.model.flags == car_band_constant);
    CHECK(fit.model.sigma == 0.0f);
    CHECK(fit.model.gamma.empty());
    CHECK(synthesized_max_deviation(fit.model, 64) == 0.0);
  }
  SECTION("two-valued band (a checkerboard and random binary)") {
    Plane checker(size, size);
    Plane binary = random_plane(3);
    for (Eigen::Index r = 0; r < checker.rows(); ++r)
      for (Eigen::Index c = 0; c < checker.cols(); ++c) {
        checker(r, c) = ((r + c) % 2) ? 1.0 : 0.0;
        binary(r, c) = binary(r, c) > 0.0 ? 5.0 : -5.0;
      }
    require_bounded(fit_car_band(checker), "checkerboard");
    require_bounded(fit_car_band(binary), "random binary");
  }
  SECTION("smaller than the neighbourhood") {
    for (int n : {1, 2, 3, 5}) {
      const Plane tiny = random_plane(4).topLeftCorner(n, n);
      const CarFit fit = fit_car_band(tiny);
      INFO("size " << n);
      CHECK(fit.model.flags != 0u);
      CHECK(fit.model.gamma.empty());
      require_bounded(fit, "tiny");
    }
  }
  SECTION("scaled to 1e-6 and 1e6: the same gamma, sigma scaled") {
    const CarBandModel truth = true_model(2, {0.45f, 0.35f}, 1.0f);
    const Plane field = synthesize_plane(truth, size, 5);
    const CarFit unit = fit_car_band(field);
    for (double scale : {1e-6, 1e6}) {
      const CarFit scaled = fit_car_band(field * scale);
      INFO("scale " << scale);
      REQUIRE(scaled.candidate == unit.candidate);
      for (std::size_t k = 0; k < unit.model.gamma.size(); ++k)
        CHECK(scaled.model.gamma[k] == Approx(unit.model.gamma[k]).epsilon(1e-5));
      CHECK(scaled.model.sigma == Approx(unit.model.sigma * scale).epsilon(1e-5));
      require_bounded(scaled, "scaled");
    }
  }
  SECTION("HDR: a log-normal band spanning seven decades") {
    const CarBandModel truth = true_model(2, {0.5f, 0.4f}, 1.2f);
    const Plane hdr = synthesize_plane(truth, size, 6).exp();
    INFO("range " << hdr.minCoeff() << " .. " << hdr.maxCoeff());
    REQUIRE(hdr.maxCoeff() / hdr.minCoeff() > 1e5);
    require_bounded(fit_car_band(hdr), "HDR");
  }
}

}  // namespace carbtf

namespace carbtf {

TEST_CASE("each band's burn-in is the fewest rows its slowest root needs to fade to a thousandth, capped",
          "[car][burn_in]") {
  // Separable (1 - a z1)(1 - b z2): roots a and b, so rho = max(|a|, |b|).
  const std::vector<CarNeighbour> separable{{0, -1}, {-1, 0}, {-1, -1}};
  auto band_of = [&](float a, float b) {
    CarBandModel band;
    band.neighbourhood = separable;
    band.gamma = {a, b, -a * b};
    band.sigma = 1.0f;
    return band;
  };
  for (const double rho : {0.3, 0.5, 0.8, 0.9}) {
    const CarBandModel band = band_of(static_cast<float>(rho), 0.2f);
    const std::uint32_t m = band_burn_in(band, 1000);
    INFO("rho " << rho << ": burn-in " << m);
    // rho^m <= 1e-3 < rho^(m - 1), up to the float rounding of gamma and the 64 sampled frequencies.
    CHECK(std::pow(rho, m) <= kBurnInResidual * 1.01);
    CHECK(std::pow(rho, m - 1.0) > kBurnInResidual * 0.99);
    CHECK(band_burn_in(band, m / 2) == m / 2);  // the request's margin caps it
  }
  CHECK(band_burn_in(band_of(0.5f, 0.2f), 1000) == 10);
  CHECK(band_burn_in(band_of(0.995f, 0.2f), 64) == 64);
  CHECK(band_burn_in(CarBandModel{}, 64) == 0);  // white noise needs none
  CHECK(band_burn_in(band_of(0.5f, 0.2f), 0) == 0);
}

TEST_CASE("a band started its own burn-in away differs from one started far away by under 1e-3 of its std",
          "[car][burn_in]") {
  // The premise of the rule: the zero start's trace in the region is below the residual. Compared with
  // the same block burnt in over 400 rows (a trace of 0.9^400: none), on a band with a within-row,
  // a vertical and two diagonal taps.
  CarBandModel band;
  band.neighbourhood = {{0, -1}, {-1, 0}, {-1, -1}, {-1, 1}};
  band.gamma = {0.55f, 0.45f, -0.2f, 0.1f};
  band.sigma = 1.0f;
  const std::uint32_t m = band_burn_in(band, 1000);
  REQUIRE(m > 4);
  REQUIRE(m < 400);
  reference::CarFieldBlock block;
  block.seed = 9;
  block.field_id = 3;
  block.width = 96;
  block.height = 64;
  std::vector<double> own(std::size_t{block.width} * block.height), far(own.size());
  block.margin = m;
  reference::synthesize_car_block(band, block, std::span<double>(own));
  block.margin = 400;
  reference::synthesize_car_block(band, block, std::span<double>(far));
  double sum = 0, squares = 0, worst = 0;
  for (std::size_t i = 0; i < far.size(); ++i) {
    sum += far[i];
    squares += far[i] * far[i];
    worst = std::max(worst, std::abs(own[i] - far[i]));
  }
  const double n = static_cast<double>(far.size());
  const double std_dev = std::sqrt(squares / n - (sum / n) * (sum / n));
  INFO("burn-in " << m << ", worst difference " << worst << ", band std " << std_dev);
  CHECK(worst < kBurnInResidual * std_dev);
  // ... and a margin a quarter as long leaves a visible trace: the test can fail.
  block.margin = m / 4;
  reference::synthesize_car_block(band, block, std::span<double>(own));
  double short_worst = 0;
  for (std::size_t i = 0; i < far.size(); ++i) short_worst = std::max(short_worst, std::abs(own[i] - far[i]));
  CHECK(short_worst > 10 * kBurnInResidual * std_dev);
}

}  // namespace carbtf
