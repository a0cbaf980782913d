// The CPU reference of the Gaussian noise: Philox known answers, accuracy of the division-free
// functions, and the statistics of the resulting fields.
#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "carbtf/analysis/field_statistics.hpp"
#include "carbtf/reference/noise.hpp"

using namespace carbtf;

TEST_CASE("Philox4x32-10 matches Random123's known-answer vectors", "[noise]") {
  using reference::philox4x32_10;
  using Words = std::array<std::uint32_t, 4>;
  CHECK(philox4x32_10({0, 0, 0, 0}, {0, 0}) == Words{0x6627e8d5, 0xe169c58d, 0xbc57ac4c, 0x9b00dbd8});
  CHECK(philox4x32_10({0xffffffff, 0xffffffff, 0xffffffff, 0xffffffff}, {0xffffffff, 0xffffffff}) ==
        Words{0x408f276d, 0x41c83b0e, 0xa20bc7c6, 0x6d5451fd});
  CHECK(philox4x32_10({0x243f6a88, 0x85a308d3, 0x13198a2e, 0x03707344}, {0xa4093822, 0x299f31d0}) ==
        Words{0xd16cfe09, 0x94fdcceb, 0x5001e420, 0x24126ea1});
}

namespace {
constexpr double kEps = std::numeric_limits<float>::epsilon();
}

TEST_CASE("division-free log is accurate to a few float ulps over its whole input range", "[noise]") {
  // Every reachable input is k * 2^-24; sweep them with a stride plus both ends.
  double worst = 0;
  for (std::uint32_t k = 1; k <= (1u << 24); k += (k < 4096 ? 1 : 997)) {
    const float u = static_cast<float>(k) * 0x1p-24f;
    const double exact = std::log(static_cast<double>(u));
    const double error = std::abs(reference::noise_log(u) - exact) / std::max(1.0, std::abs(exact));
    worst = std::max(worst, error);
  }
  INFO("worst error relative to max(1, |ln u|): " << worst);
  CHECK(worst < 4 * kEps);
  CHECK(reference::noise_log(1.0f) == 0.0f);
}

TEST_CASE("division-free cos(2 pi t) and sqrt are accurate to a few float ulps", "[noise]") {
  double worst_cos = 0, worst_sqrt = 0;
  for (std::uint32_t k = 0; k < (1u << 24); k += 331) {
    const float t = static_cast<float>(k) * 0x1p-24f;
    worst_cos =
        std::max(worst_cos, std::abs(reference::noise_cos2pi(t) - std::cos(2 * std::numbers::pi * t)));
    const float v = 34.0f * t;  // -2 ln u reaches 33.3
    if (v > 0) {
      worst_sqrt = std::max(worst_sqrt,
                            std::abs(reference::noise_sqrt(v) - std::sqrt(double{v})) / std::sqrt(double{v}));
    }
  }
  INFO("cos abs error " << worst_cos << ", sqrt relative error " << worst_sqrt);
  CHECK(worst_cos < 4 * kEps);
  CHECK(worst_sqrt < 2 * kEps);
  CHECK(reference::noise_sqrt(0.0f) == 0.0f);
}

TEST_CASE("each noise sample equals double-precision Box-Muller of its quad's Philox words", "[noise]") {
  double worst = 0;
  for (std::int32_t row = -40; row < 40; ++row) {
    for (std::int32_t col = -40; col < 40; ++col) {
      const std::uint64_t seed = 0x0123456789abcdefull;
      const auto column = static_cast<std::uint32_t>(col);
      const auto words = reference::philox4x32_10(
          {column >> 2, static_cast<std::uint32_t>(row), 3u, 0u},
          {static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32)});
      // Columns 4q, 4q + 1 share the pair (w0, w1); 4q + 2, 4q + 3 share (w2, w3).
      const std::uint32_t pair = (column & 3u) / 2u;
      const double u = ((words[2 * pair] >> 8) + 1.0) * 0x1p-24, v = (words[2 * pair + 1] >> 8) * 0x1p-24;
      const double angle = 2 * std::numbers::pi * v;
      const double exact =
          std::sqrt(-2 * std::log(u)) * ((column & 1u) == 0 ? std::cos(angle) : std::sin(angle));
      worst = std::max(worst, std::abs(reference::gaussian_noise(seed, 3, row, col) - exact));
    }
  }
  INFO("worst abs error " << worst);
  CHECK(worst < 16 * kEps);  // |z| <= 5.8: a few ulps of the largest sample
}

TEST_CASE("the four samples of one counter call are independent of each other", "[noise]") {
  // Box-Muller's cosine and sine of one radius are independent normals; a slip that reused a word or an
  // angle would correlate the samples or their magnitudes.
  const std::uint32_t quads = 1 << 18;
  std::vector<float> row(4 * std::size_t{quads});
  reference::fill_noise_block(21, 4, 3, 0, 4 * quads, 1, row);
  auto correlation = [&](std::uint32_t a, std::uint32_t b, auto transform) {
    double sa = 0, sb = 0, sab = 0, saa = 0, sbb = 0;
    for (std::uint32_t q = 0; q < quads; ++q) {
      const double x = transform(row[4 * q + a]), y = transform(row[4 * q + b]);
      sa += x, sb += y, sab += x * y, saa += x * x, sbb += y * y;
    }
    const double n = quads;
    return (sab / n - sa / n * sb / n) / std::sqrt((saa / n - sa / n * sa / n) * (sbb / n - sb / n * sb / n));
  };
  const double bound = 5.0 / std::sqrt(static_cast<double>(quads));
  for (std::uint32_t a = 0; a < 4; ++a) {
    for (std::uint32_t b = a + 1; b < 4; ++b) {
      INFO("components " << a << " and " << b);
      CHECK(std::abs(correlation(a, b, [](double x) { return x; })) < bound);
      CHECK(std::abs(correlation(a, b, [](double x) { return std::abs(x); })) < bound);
    }
  }
}

namespace {

// Sample statistics of n iid N(0,1) values have these standard deviations (large n); each check allows
// five of them. The fields are seeded, so a pass is reproducible, not luck.
void require_standard_normal(const std::vector<float>& values, std::uint32_t width, std::uint32_t height) {
  const FieldStatistics s = field_statistics(values, width, height);
  const double n = static_cast<double>(s.count);
  const double k = 5.0;
  INFO("mean " << s.mean << ", variance " << s.variance << ", skewness " << s.skewness << ", excess kurtosis "
               << s.excess_kurtosis << ", lag-1 h " << s.lag1_horizontal << ", v " << s.lag1_vertical);
  CHECK(std::abs(s.mean) < k / std::sqrt(n));
  CHECK(std::abs(s.variance - 1) < k * std::sqrt(2 / n));
  CHECK(std::abs(s.skewness) < k * std::sqrt(6 / n));
  CHECK(std::abs(s.excess_kurtosis) < k * std::sqrt(24 / n));
  CHECK(std::abs(s.lag1_horizontal) < k / std::sqrt(n));
  CHECK(std::abs(s.lag1_vertical) < k / std::sqrt(n));
}

}  // namespace

TEST_CASE("noise fields are standard normal and uncorrelated between neighbours", "[noise]") {
  const std::uint32_t n = 1024;
  std::vector<float> field(std::size_t{n} * n);
  for (std::uint64_t seed : {0ull, 7ull, 0xfedcba9876543210ull}) {
    DYNAMIC_SECTION("seed " << seed) {
      reference::fill_noise_block(seed, 0, 0, 0, n, n, field);
      require_standard_normal(field, n, n);
    }
  }
}

TEST_CASE("different fields and seeds give uncorrelated noise", "[noise]") {
  const std::uint32_t n = 512;
  std::vector<float> a(std::size_t{n} * n), b(a.size()), c(a.size());
  reference::fill_noise_block(11, 0, 0, 0, n, n, a);
  reference::fill_noise_block(11, 1, 0, 0, n, n, b);
  reference::fill_noise_block(12, 0, 0, 0, n, n, c);
  auto correlation = [](const std::vector<float>& x, const std::vector<float>& y) {
    double sxy = 0, sxx = 0, syy = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      sxy += double{x[i]} * y[i];
      sxx += double{x[i]} * x[i];
      syy += double{y[i]} * y[i];
    }
    return sxy / std::sqrt(sxx * syy);
  };
  const double bound = 5.0 / std::sqrt(static_cast<double>(a.size()));
  CHECK(std::abs(correlation(a, b)) < bound);
  CHECK(std::abs(correlation(a, c)) < bound);
}

TEST_CASE("a noise block equals the same region of a larger field, on any thread count", "[noise]") {
  const std::uint32_t n = 96;
  std::vector<float> whole(std::size_t{n} * n), block(40 * 24);
  reference::fill_noise_block(5, 2, -30, -50, n, n, whole, 1);
  reference::fill_noise_block(5, 2, -30 + 17, -50 + 9, 40, 24, block, 2);
  for (std::uint32_t r = 0; r < 24; ++r) {
    for (std::uint32_t c = 0; c < 40; ++c) {
      INFO("row " << r << ", col " << c);
      REQUIRE(std::bit_cast<std::uint32_t>(block[r * 40 + c]) ==
              std::bit_cast<std::uint32_t>(whole[(r + 17) * n + c + 9]));
      // The row cursor's four-at-a-time draws are the per-sample function's.
      REQUIRE(std::bit_cast<std::uint32_t>(block[r * 40 + c]) ==
              std::bit_cast<std::uint32_t>(reference::gaussian_noise(
                  5, 2, -30 + 17 + static_cast<std::int32_t>(r), -50 + 9 + static_cast<std::int32_t>(c))));
    }
  }
}
