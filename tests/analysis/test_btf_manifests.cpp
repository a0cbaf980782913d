// Captures with their own direction sets: manifests (and their malformed lines), photometric-stereo sets
// with light files, sRGB encoding, and the built-in sample materials' determinism.
#include "btf_test_files.hpp"

using namespace carbtf;
using namespace carbtf::btf_test_files;

TEST_CASE("a manifest lists any capture with its own direction set", "[btf][manifest]") {
  const fs::path folder = scratch_folder("manifest");
  write_uniform(folder / "img" / "a.png", 8, 0.2f);
  write_uniform(folder / "img" / "b, with comma.png", 8, 0.4f);
  write_uniform(folder / "img" / "c.png", 8, 0.6f);
  std::ofstream(folder / "capture.csv") << "path,theta_i,phi_i,theta_v,phi_v\n"
                                           "# a comment\n"
                                           "img/a.png, 10, 0, 0, 0\n"
                                           "\"img/b, with comma.png\",20.5,90,0,0\n"
                                           "img/c.png,10,0,33,270\n";
  std::vector<std::string> warnings;
  const BtfDataset dataset = load_btf(folder / "capture.csv", kQuiet, warnings);
  REQUIRE(dataset.lights().size() == 2);
  REQUIRE(dataset.views().size() == 2);
  CHECK(dataset.lights()[1].theta_degrees() == Approx(20.5));
  CHECK(dataset.views()[1].phi_degrees() == Approx(270));
  CHECK(dataset.present_pairs().size() == 3);
  REQUIRE(warnings.size() == 1);  // (light 20.5, view 33) was not measured
  CHECK_THAT(warnings[0], Catch::Contains("1 of 4"));
  std::vector<float> pixels(dataset.pixel_count() * 3);
  dataset.linear_rgb({1, 0}, pixels);
  CHECK(linear_to_srgb(pixels[0]) == Approx(linear_to_srgb(0.4f)).margin(0.5 / 255));
  fs::remove_all(folder);
}

TEST_CASE("linear_to_srgb8 gives the rounded sRGB code of the power law exactly", "[btf][srgb]") {
  // The code it replaces, value by value.
  const auto by_power = [](float v) {
    return static_cast<int>(std::lround(linear_to_srgb(std::clamp(v, 0.0f, 1.0f)) * 255.0f));
  };
  const std::uint32_t zero = std::bit_cast<std::uint32_t>(0.0f), one = std::bit_cast<std::uint32_t>(1.0f);
  std::size_t checked = 0, mismatches = 0;
  const auto check_bits = [&](std::uint32_t bits) {
    const float v = std::bit_cast<float>(bits);
    mismatches += static_cast<int>(linear_to_srgb8(v)) != by_power(v);
    ++checked;
  };
  // Every float within 2048 ULPs of each value where the power law's code steps, and every 997th float
  // of [0, 1] between them.
  int previous = 0;
  for (std::uint32_t bits = zero; bits <= one; bits += 997) {
    const int code = by_power(std::bit_cast<float>(bits));
    if (code != previous) {
      std::uint32_t low = bits - 997, high = bits;  // the step lies in (low, high]
      while (high - low > 1) {
        const std::uint32_t middle = low + (high - low) / 2;
        (by_power(std::bit_cast<float>(middle)) == code ? high : low) = middle;
      }
      for (std::uint32_t b = high - std::min<std::uint32_t>(high - zero, 2048);
           b <= std::min(high + 2048, one); ++b)
        check_bits(b);
      previous = code;
    }
    check_bits(bits);
  }
  check_bits(one);
  INFO(checked << " floats checked");
  CHECK(checked > 1000000);
  CHECK(mismatches == 0);
  CHECK(previous == 255);
  // Outside [0, 1] it clamps, as the encoders did; NaN gives 0.
  CHECK(linear_to_srgb8(-0.5f) == 0);
  CHECK(linear_to_srgb8(-0.0f) == 0);
  CHECK(linear_to_srgb8(7.0f) == 255);
  CHECK(linear_to_srgb8(std::numeric_limits<float>::infinity()) == 255);
  CHECK(linear_to_srgb8(std::numeric_limits<float>::quiet_NaN()) == 0);
}

TEST_CASE("bad input: malformed manifests name the line and the problem", "[btf][manifest][bad-input]") {
  const fs::path folder = scratch_folder("manifest_bad");
  write_uniform(folder / "a.png", 8, 0.2f);
  for (const auto& [content, fragments] : std::vector<std::pair<std::string, std::vector<std::string>>>{
           {"a.png,10,0,0\n", {"bad.csv:1", "expected 5 fields"}},
           {"a.png,ten,0,0,0\n", {"bad.csv:1", "'ten' is not a number"}},
           {"a.png,10,0,0,0\na.png,95,0,0,0\n", {"bad.csv:2", "below the horizon"}},
           {"a.png,10,0,0,0\na.png,10,0,0,0\n", {"bad.csv:2", "duplicate", "line 1"}},
           {"missing.png,10,0,0,0\n", {"missing.png", "not a readable file"}},
           {"# nothing\n", {"bad.csv", "lists no images"}}}) {
    std::ofstream(folder / "bad.csv") << content;
    require_input_error(folder / "bad.csv", fragments);
  }
  fs::remove_all(folder);
}

namespace {

// A photometric-stereo folder: the leather's top view under `count` UBO2003 lights, with a light
// file, per-light intensities (images scaled by them) and a mask.
std::vector<Direction> write_ps_set(const fs::path& folder, std::size_t count, float intensity) {
  const RenderedSample& s = rendered_leather();
  std::vector<Direction> lights;
  std::ofstream directions(folder / "light_directions.txt"), intensities(folder / "light_intensities.txt");
  for (std::uint32_t l = 1; l <= count; ++l) {
    std::vector<float> image = s.images.at(l * 81 + 0);
    for (float& v : image) v *= intensity;
    char name[32];
    std::snprintf(name, sizeof name, "%03u.png", l);
    write_rgb_image(folder / name, image, 16, 16);
    const Direction d = ubo2003_directions()[l];
    const auto v = d.vector();
    directions << v[0] << " " << v[1] << " " << v[2] << "\n";
    intensities << intensity << " " << intensity << " " << intensity << "\n";
    lights.push_back(d);
  }
  std::vector<float> mask(16 * 16 * 3, 0.0f);
  for (std::size_t i = 0; i < 16 * 8 * 3; ++i) mask[i] = 1.0f;  // top half
  write_rgb_image(folder / "mask.png", mask, 16, 16, false);
  return lights;
}

}  // namespace

TEST_CASE("a photometric-stereo set loads with its lights, intensities and mask",
          "[btf][photometric-stereo]") {
  const fs::path folder = scratch_folder("ps");
  const std::vector<Direction> lights = write_ps_set(folder, 12, 0.5f);
  std::vector<std::string> warnings;
  const BtfDataset dataset = load_btf(folder, kQuiet, warnings);
  CHECK(warnings.empty());
  REQUIRE(dataset.lights().size() == 12);
  REQUIRE(dataset.views().size() == 1);
  CHECK(dataset.views()[0].theta == 0.0);
  for (std::size_t i = 0; i < lights.size(); ++i) CHECK(angle_between(dataset.lights()[i], lights[i]) < 1e-5);
  CHECK(dataset.encoding() == ColorEncoding::linear_half);  // divided by the intensities
  REQUIRE(dataset.mask.size() == 256);
  CHECK(std::count(dataset.mask.begin(), dataset.mask.end(), 255) == 128);
  // Undoing the 0.5 intensity recovers the rendering within 8-bit quantisation of the darker image.
  double worst = 0;
  std::vector<float> pixels(dataset.pixel_count() * 3);
  dataset.linear_rgb({3, 0}, pixels);
  const std::vector<float>& rendered = rendered_leather().images.at(4 * 81 + 0);
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    worst = std::max(worst, std::abs(double{pixels[i]} - std::min(1.0f, rendered[i] * 0.5f) / 0.5));
  }
  INFO("worst linear error " << worst);
  CHECK(worst < 0.02);
  fs::remove_all(folder);
}

TEST_CASE("bad input: a light file whose line count does not match the images",
          "[btf][photometric-stereo][bad-input]") {
  const fs::path folder = scratch_folder("ps_bad");
  write_ps_set(folder, 6, 1.0f);
  std::ofstream(folder / "light_directions.txt", std::ios::app) << "0 0 1\n";
  require_input_error(folder, {"light_directions.txt", "7 light directions", "6 images"});
  std::ofstream(folder / "light_directions.txt") << "0 0 1\n0 0 1\n0 0 1\n0 0 1\n0 0 1\n0.5 0 -1\n";
  require_input_error(folder, {"light_directions.txt:6", "below the horizon"});
  fs::remove_all(folder);
}

TEST_CASE("sample materials are deterministic for a seed and differ between seeds", "[btf][sample]") {
  for (const std::string name : {"leather", "fabric", "coast_sand_rocks"}) {
    INFO(name);
    const Surface a = make_sample_surface(name, 32, 11), b = make_sample_surface(name, 32, 11);
    CHECK(a.height == b.height);
    CHECK(a.albedo == b.albedo);
    const auto [lo, hi] = std::minmax_element(a.height.begin(), a.height.end());
    CHECK(*hi - *lo > 0.5f);           // a real relief, in texels
    if (name != "coast_sand_rocks") {  // the scan is fixed; procedural surfaces follow the seed
      const Surface c = make_sample_surface(name, 32, 12);
      CHECK((c.height != a.height || c.albedo != a.albedo));  // the weave's geometry is regular by design
    }
  }
  CHECK_THROWS_AS(make_sample_surface("velvet", 32, 1), InputError);
}
