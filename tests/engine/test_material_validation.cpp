// What makes a material valid (validate_material): safe to synthesize; and the Schur-Cohn stability test
// the validation and the analysis rely on.
#include <catch2/catch.hpp>

#include "material_file_samples.hpp"

namespace carbtf {

using namespace material_file_samples;

TEST_CASE("a material is valid only if it is safe to synthesize", "[material_file]") {
  const Material good = sample_material();
  REQUIRE(validate_material(good).ok());
  auto refused = [](const Material& m) {
    const Status s = validate_material(m);
    REQUIRE_FALSE(s.ok());
    CHECK(s.code() == ErrorCode::invalid_material);
    return s.message();
  };
  SECTION("a diverging CAR recursion names its subspace, level and band, and the rule") {
    Material m = good;
    m.subspaces[2].bands[4].gamma.assign(m.subspaces[2].bands[4].gamma.size(), 1.5f);
    CHECK_THAT(refused(m), Catch::Contains("subspace 2 level 1 band 1") && Catch::Contains("unstable"));
    // One gamma of 1.1 on the left neighbour alone: a within-row root at 1.1.
    Material one = good;
    CarBandModel& band = one.subspaces[0].bands[0];
    band.neighbourhood = {{0, -1}};
    band.gamma = {1.1f};
    CHECK_THAT(refused(one),
               Catch::Contains("subspace 0 level 0 band 0") && Catch::Contains("spectral radius 1.1"));
    // Inside the margin but past it: a root at 0.997 is refused, one at 0.99 (the analysis's own
    // limit) is kept.
    band.gamma = {0.997f};
    CHECK_THAT(refused(one), Catch::Contains("unstable"));
    band.gamma = {0.99f};
    CHECK(validate_material(one).ok());
  }
  SECTION("numbers beyond the documented range are refused") {
    for (int field = 0; field < 5; ++field) {
      Material m = good;
      SubspaceModel& s = m.subspaces[1];
      const float huge = 3.4e38f;
      if (field == 0) s.bands[0].sigma = huge;
      if (field == 1) s.bands[0].mean = huge;
      if (field == 2) s.colour_transform[4] = -huge;
      if (field == 3) s.colour_mean[0] = std::numeric_limits<float>::quiet_NaN();
      if (field == 4) m.range.height_scale = 1e3f;  // 65535 steps of 1e3 texels
      INFO("field " << field);
      CHECK_THAT(refused(m), Catch::Contains("beyond +-1000000"));
    }
  }
  SECTION("two equal directions are refused before any render needs them") {
    Material m = good;
    m.views[3] = m.views[1];
    CHECK_THAT(refused(m), Catch::Contains("view directions: directions 1 and 3 are the same"));
  }
  SECTION("a hostile file with valid CRCs is refused, naming the file") {
    Material marked = good;
    marked.subspaces[0].bands[1].gamma[0] = 0.0123f;  // a marker no other float of the file equals
    std::vector<std::uint8_t> bytes = encoded(marked);
    REQUIRE(test::replace_float(bytes, 0.0123f, 1.5f) == 1);
    test::fix_crcs(bytes);
    Material m;
    const Status s = decode_material(bytes, "hostile.cbtf", m);
    REQUIRE_FALSE(s.ok());
    CHECK_THAT(s.message(),
               Catch::StartsWith("hostile.cbtf: subspace 0 level 0 band 1 is an unstable recursion"));
  }
}

TEST_CASE("the Schur-Cohn stability test agrees with known roots", "[material_file]") {
  const std::vector<CarNeighbour> left{{0, -1}};
  CHECK(car_spectral_radius(left, {0.5}) == Approx(0.5).epsilon(1e-9));
  CHECK(car_spectral_radius(left, {-1.2}) == Approx(1.2).epsilon(1e-9));
  // Separable (1 - a z1)(1 - b z2): roots a and b.
  const std::vector<CarNeighbour> separable{{0, -1}, {-1, 0}, {-1, -1}};
  CHECK(car_spectral_radius(separable, {0.99, 0.7, -0.693}) == Approx(0.99).epsilon(1e-6));
  CHECK(car_spectral_radius(separable, {0.3, 0.8, -0.24}) == Approx(0.8).epsilon(1e-6));
  // Second-order within-row recursion z^2 - 1.6 z + 0.89: complex roots of modulus sqrt(0.89).
  const std::vector<CarNeighbour> two{{0, -1}, {0, -2}};
  CHECK(car_spectral_radius(two, {1.6, -0.89}) == Approx(std::sqrt(0.89)).epsilon(1e-9));
  CHECK(car_roots_within(two, {1.6, -0.89}, 0.95));
  CHECK_FALSE(car_roots_within(two, {1.6, -0.89}, 0.94));
  CHECK(car_spectral_radius(left, {std::numeric_limits<double>::quiet_NaN()}) ==
        std::numeric_limits<double>::infinity());
}

}  // namespace carbtf
