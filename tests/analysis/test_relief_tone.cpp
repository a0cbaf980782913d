// The relief tone (issue 13, item 3c): the brightness of the photometric-stereo view that the relit
// range map does not explain. On a rendered sample whose creases have a darker albedo, the tone must
// follow that albedo; on the same relief with a uniform albedo it must be far flatter.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "carbtf/analysis/btf/btf_dataset.hpp"
#include "carbtf/analysis/btf/directions.hpp"
#include "carbtf/analysis/model/relief_tone.hpp"
#include "carbtf/analysis/sample/height_field_renderer.hpp"
#include "carbtf/analysis/sample/sample_materials.hpp"
#include "test_top_view.hpp"

namespace carbtf {
namespace {

using test::heights_of;
using test::top_view_dataset;

double correlation(const Plane& a, const Plane& b) {
  const Plane da = a - a.mean(), db = b - b.mean();
  return (da * db).sum() / std::sqrt(da.square().sum() * db.square().sum());
}

double deviation(const Plane& a) {
  return std::sqrt((a - a.mean()).square().mean());
}

}  // namespace

TEST_CASE("the relief tone follows a crease-darkened albedo and stays flat without one", "[tone]") {
  constexpr std::uint32_t size = 64;
  const Surface surface = make_sample_surface("leather", size, 3);
  const Plane heights = heights_of(surface);
  const double z_floor = test::kTopViewLightZFloor;
  const Plane tone = relief_tone(top_view_dataset(surface), 0, heights, z_floor);

  Plane albedo(size, size);
  for (std::size_t p = 0; p < std::size_t{size} * size; ++p) {
    albedo(static_cast<Eigen::Index>(p / size), static_cast<Eigen::Index>(p % size)) =
        (surface.albedo[3 * p] + surface.albedo[3 * p + 1] + surface.albedo[3 * p + 2]) / 3.0;
  }
  REQUIRE(deviation(albedo) > 0.01);  // the sample does darken its creases
  CHECK(tone.minCoeff() >= kReliefToneFloor);
  CHECK(tone.maxCoeff() <= kReliefToneCeiling);
  CHECK(tone.mean() == Approx(1.0).margin(0.15));
  const double follows = correlation(tone, albedo);
  INFO("correlation of tone and albedo " << follows);
  CHECK(follows > 0.5);

  Surface uniform = surface;
  for (std::size_t p = 0; p < std::size_t{size} * size; ++p) {
    for (int k = 0; k < 3; ++k) uniform.albedo[3 * p + static_cast<std::size_t>(k)] = 0.5f;
  }
  const Plane flat_tone = relief_tone(top_view_dataset(uniform), 0, heights, z_floor);
  INFO("tone deviation with the crease albedo " << deviation(tone) << ", with a uniform albedo "
                                                << deviation(flat_tone));
  // What is left with a uniform albedo is occlusion and shadow, which the relit factor cannot give;
  // the darker crease albedo adds to it, and darkens the tone exactly where the albedo is dark.
  CHECK(deviation(flat_tone) < deviation(tone));
  const double dark_albedo = albedo.mean();
  double dark = 0.0, dark_flat = 0.0;
  int count = 0;
  for (Eigen::Index i = 0; i < albedo.size(); ++i) {
    if (albedo(i) >= dark_albedo) continue;
    dark += tone(i);
    dark_flat += flat_tone(i);
    ++count;
  }
  INFO("mean tone where the albedo is below its mean: " << dark / count << ", with a uniform albedo "
                                                        << dark_flat / count);
  CHECK(dark / count < dark_flat / count - 0.05);
}

TEST_CASE("clamping the remainder bounds each channel around its median", "[tone]") {
  std::vector<Plane> channels(2, Plane(8, 8));
  for (Eigen::Index i = 0; i < 64; ++i) {
    channels[0](i / 8, i % 8) = static_cast<double>(i % 4);  // upper median 2, MAD 1
    channels[1](i / 8, i % 8) = i == 5 ? 100.0 : 1.0;        // one spike on a flat field
  }
  clamp_remainder(channels, 1.0);
  CHECK(channels[0].minCoeff() == Approx(2.0 - 1.4826));  // the zeros are raised
  CHECK(channels[0].maxCoeff() == 3.0);                   // within 2 + 1.4826: untouched
  CHECK(channels[1].maxCoeff() == 1.0);                   // MAD 0: the spike is clamped to the median
}

TEST_CASE("the smooth texture is scaled so that the render keeps the measured mean", "[tone]") {
  // A measured image whose brightness follows the relief: bright where tone x relit is high. The
  // smooth remainder is what the CAR models, independently of the relief, so the render's mean is
  // mean(smooth) x mean(tone x relit), which is darker than the measurement before the scaling.
  const Eigen::Index n = 64;
  Plane tone(n, n), relit(n, n);
  std::vector<Plane> measured(3, Plane(n, n));
  for (Eigen::Index r = 0; r < n; ++r) {
    for (Eigen::Index c = 0; c < n; ++c) {
      tone(r, c) = 1.0 + 0.5 * std::sin(0.4 * static_cast<double>(c));
      relit(r, c) = 1.0 + 0.3 * std::cos(0.3 * static_cast<double>(r + c));
      const double relief = tone(r, c) * relit(r, c);
      for (int k = 0; k < 3; ++k)
        measured[static_cast<std::size_t>(k)](r, c) = (0.2 + 0.1 * k) * relief * relief;
    }
  }
  std::vector<Plane> smooth = measured;
  for (Plane& channel : smooth) channel /= tone;
  const double relief_mean = (tone * relit).mean();
  auto render_mean = [&](const std::vector<Plane>& channels) {
    double sum = 0.0;
    for (const Plane& channel : channels) sum += channel.mean() * relief_mean;
    return sum;
  };
  double target = 0.0;
  for (const Plane& channel : measured) target += channel.mean();
  REQUIRE(render_mean(smooth) < 0.97 * target);  // the case is one the scaling has to mend
  const std::vector<Plane> before = smooth;
  match_render_mean(smooth, measured,
                    weighted_tone(std::span<const Plane>(&tone, 1), 1.0, {1.0f, 1.0f, 1.0f}), relit);
  CHECK(render_mean(smooth) == Approx(target).epsilon(1e-12));
  // One gain for all channels: the colour's chroma stays the smooth texture's.
  const double gain = smooth[0].mean() / before[0].mean();
  CHECK(gain > 1.0);
  for (std::size_t k = 0; k < 3; ++k)
    CHECK(((smooth[k] - gain * before[k]).abs() < 1e-12 * gain * before[k].abs().maxCoeff()).all());

  // Nothing to match: a black measurement leaves the texture as it was.
  std::vector<Plane> black(3, Plane::Zero(n, n));
  std::vector<Plane> unchanged = before;
  match_render_mean(unchanged, black,
                    weighted_tone(std::span<const Plane>(&tone, 1), 1.0, {1.0f, 1.0f, 1.0f}), relit);
  for (std::size_t k = 0; k < 3; ++k) CHECK((unchanged[k] == before[k]).all());
}

TEST_CASE("a two-colour weave gets a coloured tone and a leather a grey one", "[tone]") {
  constexpr std::uint32_t size = 64;
  const double z_floor = test::kTopViewLightZFloor;
  auto chroma_of = [&](const Surface& surface) {
    const BtfDataset dataset = top_view_dataset(surface);
    const Plane heights = heights_of(surface);
    return relief_tone_chroma(dataset, 0, heights, z_floor, relief_tone(dataset, 0, heights, z_floor));
  };
  // The fabric sample's raised threads are white and its sunken ones blue: where the tone is dark the
  // blue channel stays relatively bright, so blue follows the tone least and red most.
  const std::array<float, 3> fabric = chroma_of(make_sample_surface("fabric", size, 1));
  INFO("fabric tone chroma " << fabric[0] << " " << fabric[1] << " " << fabric[2]);
  CHECK(fabric[0] > 1.1f);
  CHECK(fabric[2] < 0.8f);
  CHECK(fabric[2] < fabric[1]);
  CHECK(fabric[1] < fabric[0]);
  // The leather's creases darken every channel about alike: its slopes explain too little to keep.
  const std::array<float, 3> leather = chroma_of(make_sample_surface("leather", size, 3));
  CHECK(leather == std::array<float, 3>{1.0f, 1.0f, 1.0f});
  // A grey material's channel tones equal the grey tone: nothing departs from grey, so grey it stays.
  Surface uniform = make_sample_surface("leather", size, 3);
  for (float& a : uniform.albedo) a = 0.5f;
  CHECK(chroma_of(uniform) == std::array<float, 3>{1.0f, 1.0f, 1.0f});
}

}  // namespace carbtf

namespace carbtf {

TEST_CASE("the tone's colour planes follow each thread's colour, and only a weave's colour counts as visible",
          "[tone]") {
  constexpr std::uint32_t size = 64;
  const double z_floor = test::kTopViewLightZFloor;
  auto planes_of = [&](const Surface& surface) {
    return relief_tone_planes(top_view_dataset(surface), 0, heights_of(surface), z_floor);
  };
  // The fabric sample's threads are blue or white: the blue-to-red ratio of the tone's planes follows
  // that of the albedo, texel by texel (which one grey plane with a slope per channel cannot).
  const Surface fabric = make_sample_surface("fabric", size, 1);
  const std::vector<Plane> planes = planes_of(fabric);
  REQUIRE(planes.size() == 3);
  std::vector<double> tone_hue, albedo_hue;
  for (std::uint32_t i = 0; i < size * size; ++i) {
    tone_hue.push_back(std::log(planes[2](i / size, i % size) / planes[0](i / size, i % size)));
    albedo_hue.push_back(std::log(double{fabric.albedo[3 * i + 2]} / double{fabric.albedo[3 * i]}));
  }
  auto correlation = [](const std::vector<double>& a, const std::vector<double>& b) {
    const auto n = static_cast<double>(a.size());
    double ma = 0.0, mb = 0.0, ab = 0.0, aa = 0.0, bb = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) ma += a[i] / n, mb += b[i] / n;
    for (std::size_t i = 0; i < a.size(); ++i) {
      ab += (a[i] - ma) * (b[i] - mb);
      aa += (a[i] - ma) * (a[i] - ma);
      bb += (b[i] - mb) * (b[i] - mb);
    }
    return ab / std::sqrt(aa * bb);
  };
  const double follows = correlation(tone_hue, albedo_hue);
  const double fabric_deviation = tone_colour_deviation(planes);
  INFO("hue correlation " << follows << ", colour deviation " << fabric_deviation);
  CHECK(follows > 0.9);
  CHECK(fabric_deviation >= kToneColourVisible);
  // The leather's creases darken every channel about alike; a grey albedo gives grey planes.
  const double leather_deviation = tone_colour_deviation(planes_of(make_sample_surface("leather", size, 3)));
  INFO("leather colour deviation " << leather_deviation);
  CHECK(leather_deviation < kToneColourVisible);
  Surface uniform = make_sample_surface("leather", size, 3);
  for (float& a : uniform.albedo) a = 0.5f;
  CHECK(tone_colour_deviation(planes_of(uniform)) < 1e-6);
  const std::vector<Plane> two(2, planes[0]);
  CHECK_THROWS_AS(tone_colour_deviation(two), std::invalid_argument);
  CHECK_THROWS_AS(weighted_tone(two, 1.0, {1.0f, 1.0f, 1.0f}), std::invalid_argument);
}

TEST_CASE("the band-limited tone keeps coarse periods and the mean, and spreads a one-texel line",
          "[analysis][tone]") {
  const Eigen::Index n = 32;
  const double pi = 3.14159265358979323846;
  // Periods of 8 texels along the rows, of 2 along the columns, and a constant, in three planes.
  std::vector<Plane> planes(3, Plane(n, n));
  for (Eigen::Index r = 0; r < n; ++r) {
    for (Eigen::Index c = 0; c < n; ++c) {
      planes[0](r, c) = 1.0 + 0.5 * std::cos(2.0 * pi * static_cast<double>(c) / 8.0);
      planes[1](r, c) = (r % 2 == 0) ? 1.5 : 0.5;
      planes[2](r, c) = 0.7;
    }
  }
  for (Plane& plane : planes) plane = band_limited_tone(plane);
  // Away from the edges, a period of p keeps 1 - 2w + 2w cos(2 pi / p) of its amplitude.
  const double w = kToneBandLimitSide;
  const double kept8 = 1.0 - 2.0 * w + 2.0 * w * std::cos(pi / 4.0), kept2 = 1.0 - 4.0 * w;
  for (Eigen::Index r = 2; r < n - 2; ++r) {
    for (Eigen::Index c = 2; c < n - 2; ++c) {
      REQUIRE(planes[0](r, c) ==
              Approx(1.0 + 0.5 * kept8 * std::cos(2.0 * pi * static_cast<double>(c) / 8.0)).margin(1e-12));
      REQUIRE(planes[1](r, c) == Approx(1.0 + ((r % 2 == 0) ? 0.5 : -0.5) * kept2).margin(1e-12));
    }
  }
  CHECK(kept2 < 0.5);  // the finest period loses over half its amplitude
  // A constant stays, edges included.
  CHECK((planes[2] - 0.7).abs().maxCoeff() < 1e-12);

  // A crease drawn as a one-texel dark line becomes a three-texel softer one of the same total darkness.
  Plane line = Plane::Ones(n, n);
  line.col(16) = 0.2;
  line = band_limited_tone(line);
  CHECK(line(10, 16) == Approx(1.0 - 0.8 * (1.0 - 2.0 * w)));
  CHECK(line(10, 15) == Approx(1.0 - 0.8 * w));
  CHECK(line(10, 17) == Approx(1.0 - 0.8 * w));
  CHECK(line(10, 14) == Approx(1.0));
  CHECK(line.row(10).sum() == Approx(static_cast<double>(n) - 0.8));
}

}  // namespace carbtf
