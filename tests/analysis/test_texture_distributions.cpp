// The measure on distributions (analysis/quality/texture_distributions, issue 42) against the order a
// person sees (docs/design.md 5), on each sample material at five lights (15 to 75 degrees, from azimuth
// 30), each comparison a CHECK on measured distances:
//  - another region of the same image below a 1-pixel blur, +10% gain, a 10 degree hue shift and a
//    quarter turn;
//  - each of those below the phase-randomised version (the same spectrum, no crease, thread or rock), that
//    below another material under the same light, and that below white noise of the measured colours;
//  - in a bank of every material under 5 lights, two disjoint crops each, each crop's nearest neighbour
//    its own image's other crop, and every crop of its material nearer than any other material's.
// One exception, measured and not asserted: coast_sand_rocks' quarter turn under a light under 45 degrees
// from the pole. Its rocks' shading there is weaker than the moss's colour (the lighting vectors of two
// crops differ by more than a turn moves them), so a turned crop is another crop of the same material;
// under lights from opposite azimuths at 45 degrees the measure does not tell its images apart either, and
// neither could I by eye, so the bank's five lights differ in elevation (docs/design.md 5.1).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "carbtf/analysis/quality/texture_distributions.hpp"
#include "carbtf/analysis/quality/texture_references.hpp"
#include "texture_cases.hpp"

namespace carbtf {
namespace {

struct Ranking {
  double crop = 0, blur = 0, gain = 0, hue = 0, turned = 0, gaussian = 0, other = 0, noise = 0;
};

// The distances to the left half of `name`'s image at light `theta` of what DESIGN.md 5 orders.
Ranking ranking_of(const std::string& name, const std::string& other_name, double theta) {
  const RgbField image = test::rendered_sample(name, theta);
  const std::uint32_t w = test::kSize / 2, h = test::kSize;
  const RgbField a = crop(image, 0, 0, w, h), b = crop(image, 0, w, w, h);
  const DistributionStatistics reference = distribution_statistics(a.rgb, w, h);
  auto d = [&](const RgbField& x) {
    return distribution_distance(distribution_statistics(x.rgb, x.width, x.height), reference).total;
  };
  Ranking r;
  r.crop = d(b);
  r.blur = d(test::blurred(b, 1.0));
  r.gain = d(test::brighter(b, 1.1));
  r.hue = d(test::hue_shifted(b, 10.0));
  r.turned = d(test::rotated(b));
  // One draw of random phases scatters: the ranking is of the mean over five.
  for (std::uint64_t seed = 1; seed <= 5; ++seed) r.gaussian += d(phase_randomised(b, seed)) / 5.0;
  r.other = d(crop(test::rendered_sample(other_name, theta), 0, w, w, h));
  r.noise = d(white_noise_like(b, 3));
  return r;
}

}  // namespace

TEST_CASE(
    "the distribution measure ranks mild distortions below phase-randomising, and that below another "
    "material and white noise",
    "[quality][distributions][slow]") {
  const auto [name, other] = GENERATE(table<std::string, std::string>(
      {{"leather", "fabric"}, {"fabric", "coast_sand_rocks"}, {"coast_sand_rocks", "leather"}}));
  const double theta = GENERATE(15.0, 30.0, 45.0, 60.0, 75.0);
  const Ranking r = ranking_of(name, other, theta);
  std::printf(
      "%-17s light %2.0f: crop %.3f  blur %.3f  gain %.3f  hue %.3f  turned %.3f | phase-randomised %.3f | "
      "%s %.3f | noise %.3f\n",
      name.c_str(), theta, r.crop, r.blur, r.gain, r.hue, r.turned, r.gaussian, other.c_str(), r.other,
      r.noise);
  INFO(name << " at light " << theta << ": crop " << r.crop << ", blurred " << r.blur << ", +10% " << r.gain
            << ", hue +10 " << r.hue << ", quarter turn " << r.turned << ", phase-randomised " << r.gaussian
            << ", " << other << " " << r.other << ", white noise " << r.noise);
  for (const double mild : {r.blur, r.gain, r.hue}) CHECK(r.crop < mild);
  if (name != "coast_sand_rocks" || theta >= 45.0) CHECK(r.crop < r.turned);
  for (const double mild : {r.blur, r.gain, r.hue, r.turned}) CHECK(mild < r.gaussian);
  CHECK(r.gaussian < r.other);
  CHECK(r.other < r.noise);
}

TEST_CASE("the distribution measure retrieves a crop's own image first and its own material before any other",
          "[quality][distributions]") {
  struct Crop {
    std::string material;
    int image = 0;
    DistributionStatistics statistics;
  };
  std::vector<Crop> bank;
  const double lights[5][2] = {{15, 30}, {30, 150}, {45, 270}, {60, 30}, {75, 90}};
  int image_index = 0;
  for (const std::string name : {"leather", "fabric", "coast_sand_rocks"}) {
    for (const auto& light : lights) {
      const RgbField image = test::rendered_sample(name, light[0], light[1]);
      const std::uint32_t w = test::kSize / 2;
      for (std::uint32_t half = 0; half < 2; ++half) {
        const RgbField part = crop(image, 0, half * w, w, test::kSize);
        bank.push_back({name, image_index, distribution_statistics(part.rgb, part.width, part.height)});
      }
      ++image_index;
    }
  }
  int own_image_first = 0;
  for (std::size_t q = 0; q < bank.size(); ++q) {
    std::size_t nearest = q == 0 ? 1 : 0;
    double nearest_distance = 1e30, farthest_same = 0.0, nearest_other = 1e30;
    for (std::size_t i = 0; i < bank.size(); ++i) {
      if (i == q) continue;
      const double d = distribution_distance(bank[q].statistics, bank[i].statistics).total;
      if (d < nearest_distance) {
        nearest = i;
        nearest_distance = d;
      }
      if (bank[i].material == bank[q].material) {
        farthest_same = std::max(farthest_same, d);
      } else {
        nearest_other = std::min(nearest_other, d);
      }
    }
    INFO(bank[q].material << " image " << bank[q].image << ": farthest crop of its material " << farthest_same
                          << ", nearest of another " << nearest_other);
    CHECK(farthest_same < nearest_other);
    CHECK(bank[nearest].image == bank[q].image);
    own_image_first += bank[nearest].image == bank[q].image;
  }
  std::printf("retrieval: the crop's own image's other crop is nearest for %d of %zu crops\n",
              own_image_first, bank.size());
}

TEST_CASE("the distribution measure is zero for an image against itself and needs images of one size class",
          "[quality][distributions]") {
  const RgbField image = test::rendered_sample("leather", 45.0);
  const DistributionStatistics s = distribution_statistics(image.rgb, image.width, image.height);
  CHECK(distribution_distance(s, s).total == 0.0);
  const RgbField small = crop(image, 0, 0, 20, 20);
  CHECK_THROWS_AS(distribution_distance(distribution_statistics(small.rgb, 20, 20), s),
                  std::invalid_argument);
  CHECK_THROWS_AS(distribution_statistics(image.rgb, 8, 8), std::invalid_argument);
}

TEST_CASE("calibrated fidelity puts the measurement near 0, white noise near 1 and the Gaussian between",
          "[quality][distributions]") {
  const RgbField image = test::rendered_sample("fabric", 45.0);
  const CalibratedFidelity itself = calibrated_fidelity(image, image);
  INFO("floor " << itself.floor << ", ceiling " << itself.ceiling << ", gaussian " << itself.gaussian
                << ", model " << itself.model);
  CHECK(itself.floor < itself.gaussian);
  CHECK(itself.gaussian < itself.ceiling);
  CHECK(std::abs(itself.rel) < 0.1);  // the model crop is the centre of the measurement
  CHECK(itself.structure < 0.2);
  CHECK(itself.gaussian_rel > 0.0);
  CHECK(itself.gaussian_rel < 1.0);
  const CalibratedFidelity noise = calibrated_fidelity(white_noise_like(image, 9), image);
  CHECK(noise.rel == Approx(1.0).margin(0.2));
  CHECK(noise.structure > 1.0);
  CHECK_THROWS_AS(calibrated_fidelity(crop(image, 0, 0, 64, 64), image), std::invalid_argument);
}

}  // namespace carbtf

namespace carbtf {

TEST_CASE("an octave's light vectors point along the light's azimuth and turn with it",
          "[quality][distributions]") {
  // Leather at 45 degrees, lit from azimuth 0 (along +x) and from the opposite side: at the creases'
  // octave the vectors turn over, and a Gaussian field of the same spectrum has almost none.
  const RgbField from_0 = test::rendered_sample("leather", 45.0, 0.0);
  const RgbField from_180 = test::rendered_sample("leather", 45.0, 180.0);
  const DistributionStatistics a = distribution_statistics(from_0.rgb, from_0.width, from_0.height);
  const DistributionStatistics b = distribution_statistics(from_180.rgb, from_180.width, from_180.height);
  const RgbField gaussian_image = phase_randomised(from_0, 1);
  const DistributionStatistics gaussian =
      distribution_statistics(gaussian_image.rgb, gaussian_image.width, gaussian_image.height);
  const auto dot = [](const std::array<double, 2>& u, const std::array<double, 2>& v) {
    return u[0] * v[0] + u[1] * v[1];
  };
  const auto length = [](const std::array<double, 2>& u) { return std::hypot(u[0], u[1]); };
  const OctaveProfile pa = octave_profile(a, 0), pb = octave_profile(b, 0), pg = octave_profile(gaussian, 0);
  CHECK(dot(pa.skewness, pb.skewness) < -0.5 * length(pa.skewness) * length(pb.skewness));
  CHECK(dot(pa.dark_side, pb.dark_side) < -0.5 * length(pa.dark_side) * length(pb.dark_side));
  CHECK(length(pg.skewness) < 0.25 * length(pa.skewness));
  // Along the light's azimuth (x) or against it, not across it.
  CHECK(std::abs(pa.skewness[0]) > 0.9 * length(pa.skewness));
  CHECK(std::abs(pb.dark_side[0]) > 0.9 * length(pb.dark_side));
  // The energy is the band's, the same for both lights to within what the shading moves it, and the
  // phase-randomised field keeps it.
  CHECK(pg.energy_db == Approx(pa.energy_db).margin(1.0));
  CHECK(pa.energy_db > octave_profile(a, a.octaves - 1).energy_db);
  CHECK_THROWS_AS(octave_profile(a, a.octaves), std::out_of_range);
}

TEST_CASE("an octave's chroma energies are its a* and b* bands", "[quality][distributions]") {
  // A grey field whose red and green trade places every 2 pixels along x (the finest octave, periods of
  // 4) at about the same luminance: a* swings there and b* hardly does; coarser octaves hold little.
  constexpr std::uint32_t kSide = 128;
  std::vector<float> rgb(3 * kSide * kSide);
  for (std::uint32_t r = 0; r < kSide; ++r) {
    for (std::uint32_t c = 0; c < kSide; ++c) {
      const bool red = (c / 2) % 2 == 0;
      float* p = &rgb[3 * (r * kSide + c)];
      p[0] = red ? 0.30f : 0.15f;
      p[1] = red ? 0.15f : 0.22f;
      p[2] = 0.18f;
    }
  }
  const DistributionStatistics s = distribution_statistics(rgb, kSide, kSide);
  const OctaveProfile fine = octave_profile(s, 0), coarse = octave_profile(s, s.octaves - 1);
  INFO("finest a* " << fine.chroma_energy_db[0] << " dB, b* " << fine.chroma_energy_db[1]
                    << " dB; coarsest a* " << coarse.chroma_energy_db[0] << " dB");
  CHECK(fine.chroma_energy_db[0] > fine.chroma_energy_db[1] + 6.0);
  CHECK(fine.chroma_energy_db[0] > coarse.chroma_energy_db[0] + 10.0);
}

}  // namespace carbtf
