// The tool's host code, called directly (carbtf_cli): scenes from the command's options, orbits, the
// option checks every command shares, and the fidelity run's choice of pairs. The subprocess tests
// (test_cli.cpp and others) cannot see these: the GPU and its CPU twin take the same scene, so a
// flipped angle there would pass them.
#include <catch2/catch.hpp>

#include <CLI/CLI.hpp>

#include <cmath>
#include <functional>
#include <map>
#include <numbers>
#include <regex>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "carbtf/analysis/btf/directions.hpp"
#include "cli/cli_support.hpp"
#include "cli/command_error.hpp"
#include "commands/commands.hpp"
#include "fidelity/fidelity_run.hpp"
#include "scene/orbit.hpp"
#include "test_materials.hpp"

using namespace carbtf;
using namespace carbtf::cli;

namespace cli_unit_tests {

void check_vector(const std::array<float, 3>& v, double x, double y, double z) {
  CHECK(v[0] == Approx(x).margin(1e-6));
  CHECK(v[1] == Approx(y).margin(1e-6));
  CHECK(v[2] == Approx(z).margin(1e-6));
}

// The whole command line as main() builds it, parsed without running a command (every case here is
// refused before any callback).
void parse(const std::vector<std::string>& arguments) {
  CLI::App app{"carbtf"};
  register_sample_command(app);
  register_analyze_command(app);
  register_render_command(app);
  register_fidelity_command(app);
  check_every_option(app);
  std::vector<std::string> reversed(arguments.rbegin(), arguments.rend());  // CLI11 takes them last first
  app.parse(reversed);
}

}  // namespace cli_unit_tests

TEST_CASE("directions in degrees: theta from +z, phi from +x towards +y", "[cli_units]") {
  using namespace cli_unit_tests;
  check_vector(unit_vector_degrees(0, 123), 0, 0, 1);
  check_vector(unit_vector_degrees(90, 0), 1, 0, 0);
  check_vector(unit_vector_degrees(90, 90), 0, 1, 0);  // a flipped azimuth gives -y
  check_vector(unit_vector_degrees(60, 180), -std::sin(std::numbers::pi / 3), 0, 0.5);
  check_vector(unit_vector_degrees(30, 270), 0, -0.5, std::cos(std::numbers::pi / 6));
}

TEST_CASE("render's scene from its options: orbit camera, directional and point lights", "[cli_units]") {
  using namespace cli_unit_tests;
  const RenderScene scene = scene_from_options({60, 90}, 40.0f, {{45, 120, 2}}, {{1, 2, 3}});
  // The camera 3.6 away towards (60, 90): over +y, above the plane, looking at the origin, z up.
  CHECK(scene.camera.eye[0] == Approx(0).margin(1e-5));
  CHECK(scene.camera.eye[1] == Approx(3.6 * std::sin(std::numbers::pi / 3)));
  CHECK(scene.camera.eye[2] == Approx(1.8));
  check_vector(scene.camera.up, 0, 0, 1);
  CHECK(scene.camera.fov_y_degrees == 40.0f);
  REQUIRE(scene.lights.size() == 2);
  CHECK_FALSE(scene.lights[0].point);
  const double s = std::sin(std::numbers::pi / 4);
  check_vector(scene.lights[0].position, s * std::cos(2 * std::numbers::pi / 3),
               s * std::sin(2 * std::numbers::pi / 3), std::cos(std::numbers::pi / 4));
  CHECK(scene.lights[0].colour[1] == 2.0f);
  CHECK(scene.lights[1].point);
  check_vector(scene.lights[1].position, 1, 2, 3);
  CHECK(scene.lights[1].colour[0] == 1.0f);

  // Straight down: the camera's up is +y, not the view axis.
  check_vector(scene_from_options({0, 0, 2}, 0.0f, {}, {}).camera.up, 0, 1, 0);
  // No light given: one at (45, 120).
  const RenderScene lit = scene_from_options({30, 0}, 40.0f, {}, {});
  REQUIRE(lit.lights.size() == 1);
  check_vector(lit.lights[0].position, s * std::cos(2 * std::numbers::pi / 3),
               s * std::sin(2 * std::numbers::pi / 3), std::cos(std::numbers::pi / 4));
  CHECK_THROWS_AS(scene_from_options({30, 0, -1}, 40.0f, {}, {}), CommandError);
  const std::vector<std::vector<double>> too_many(kMaxRenderLights + 1, std::vector<double>{45, 0});
  CHECK_THROWS_AS(scene_from_options({30, 0}, 40.0f, too_many, {}), CommandError);
}

TEST_CASE("bench frame's orbit turns the camera and spreads the lights the other way", "[cli_units]") {
  using namespace cli_unit_tests;
  const RenderScene first = orbiting_scene(0, 4, 2);
  const RenderScene second = orbiting_scene(1, 4, 2);
  const auto camera = [](const RenderScene& scene) {
    return std::atan2(scene.camera.eye[1], scene.camera.eye[0]) * 180.0 / std::numbers::pi;
  };
  CHECK(camera(first) == Approx(35.0));
  CHECK(std::remainder(camera(second) - camera(first), 360.0) == Approx(90.0));  // a quarter turn a frame
  REQUIRE(first.lights.size() == 2);
  for (const auto& light : first.lights) {
    CHECK(std::acos(light.position[2]) * 180.0 / std::numbers::pi == Approx(40.0));
    CHECK(light.colour[0] == Approx(0.5f));
  }
  CHECK_THROWS_AS(orbiting_scene(0, 4, 0), CommandError);
  CHECK_THROWS_AS(orbiting_scene(0, 4, kMaxRenderLights + 1), CommandError);
}

TEST_CASE("the fidelity run's pairs: the default five and the spread", "[cli_units]") {
  using namespace cli_unit_tests;
  Material material;  // the pair choice reads only the direction sets
  material.lights = test::ubo2003_material_directions();
  material.views = material.lights;
  const auto degrees = [](float radians) { return std::lround(radians * 180.0 / std::numbers::pi); };
  const std::vector<FidelityPair> pairs = default_fidelity_pairs(material);
  REQUIRE(pairs.size() == 5);
  const long light_thetas[] = {15, 45, 75, 45, 45};
  const long view_thetas[] = {0, 0, 0, 45, 60};
  for (std::size_t i = 0; i < 5; ++i) {
    INFO(pairs[i].label);
    CHECK(degrees(material.lights[pairs[i].light].theta) == light_thetas[i]);
    CHECK(degrees(material.views[pairs[i].view].theta) == view_thetas[i]);
  }

  // 64^2: at this size views up to 70.5 degrees cover a third of the frame (smaller images drop more).
  BtfDataset dataset(ubo2003_directions(), ubo2003_directions(), 64, 64, ColorEncoding::linear_half);
  const std::vector<float> grey(64 * 64 * 3, 0.5f);
  for (std::uint32_t l = 0; l < 81; ++l) {
    for (std::uint32_t v = 0; v < 81; ++v) dataset.set_linear({l, v}, grey);
  }
  const std::vector<FidelityPair> spread = spread_fidelity_pairs(material, dataset, 16);
  CHECK(spread.size() == 16);
  std::set<std::pair<std::uint32_t, std::uint32_t>> distinct;
  std::set<std::uint32_t> lights;
  for (const FidelityPair& p : spread) {
    distinct.insert({p.light, p.view});
    lights.insert(p.light);
    CHECK(degrees(material.views[p.view].theta) <= 70);  // views over 70.5 degrees are skipped
  }
  CHECK(distinct.size() == spread.size());
  CHECK(lights.size() >= 12);  // spread, not clustered
  const std::vector<FidelityPair> again = spread_fidelity_pairs(material, dataset, 16);
  for (std::size_t i = 0; i < spread.size(); ++i)
    CHECK((again[i].light == spread[i].light && again[i].view == spread[i].view));
}

TEST_CASE("fidelity integrates a camera pixel's footprint: more samples per pixel at oblique views",
          "[cli_units]") {
  using namespace cli_unit_tests;
  // The measured directions as the material stores them (floats), where 60 degrees is 2.0000001 texels.
  const std::vector<MaterialDirection> views = test::ubo2003_material_directions();
  std::map<long, std::uint32_t> samples_at;  // view theta in degrees -> samples per side
  for (const MaterialDirection& v : views) {
    const long degrees = std::lround(v.theta * 180.0 / std::numbers::pi);
    const std::uint32_t samples = camera_samples_per_side(v.theta);
    const auto at = samples_at.emplace(degrees, samples).first;
    CHECK(at->second == samples);  // every azimuth of a ring alike
  }
  CHECK(samples_at == std::map<long, std::uint32_t>{{0, 1}, {15, 1}, {30, 1}, {45, 2}, {60, 2}, {75, 4}});
  CHECK(camera_samples_per_side(70.0 * std::numbers::pi / 180.0) == 4);  // 2.92 texels
  CHECK(camera_samples_per_side(std::numbers::pi / 2) == 4);             // at most 4
}

// A measured figure in a help text goes stale with the next change of the model or the machine; the figures
// live in docs/figures.md (scripts/figures.sh) and the help says what an option does.
TEST_CASE("help texts say what an option does, not measured figures", "[cli_units]") {
  CLI::App app{"carbtf"};
  register_all_commands(app);
  const std::regex figure(
      R"((\d\.\d{2,})|(\d+(\.\d+)? ?(ms|%))|((fifth|quarter|third|half|twice|times) (faster|slower)))");
  std::vector<std::string> found;
  std::size_t texts = 0;
  const std::function<void(const CLI::App&, const std::string&)> walk = [&](const CLI::App& command,
                                                                            const std::string& path) {
    const auto check = [&](const std::string& where, const std::string& text) {
      ++texts;
      if (std::regex_search(text, figure)) found.push_back(where + ": " + text);
    };
    check(path, command.get_description());
    for (const CLI::Option* option : command.get_options())
      check(path + " " + option->get_name(), option->get_description());
    for (const CLI::App* sub : command.get_subcommands({})) walk(*sub, path + " " + sub->get_name());
  };
  walk(app, "carbtf");
  CHECK(texts > 150);  // every command, bench's subcommands and their options were reached
  for (const std::string& text : found) FAIL_CHECK(text);
  // The check itself sees a figure where one is.
  CHECK(std::regex_search(std::string("raise from 0.69 to 0.83"), figure));
  CHECK(std::regex_search(std::string("about 12 ms per frame"), figure));
  CHECK_FALSE(std::regex_search(std::string("format 1.5, docs/design.md 4.5"), figure));
}

TEST_CASE("every command's numbers are checked before it runs", "[cli_units]") {
  using namespace cli_unit_tests;
  CHECK_THROWS_AS(parse({"sample", "leather", "--size", "8", "--out", "x"}), CLI::ValidationError);
  CHECK_THROWS_AS(parse({"sample", "leather", "--out", "x", "--format", "tiff"}), CLI::ValidationError);
  CHECK_THROWS_AS(parse({"analyze", "d", "--out", "m.cbtf", "-k", "0"}), CLI::ValidationError);
  CHECK_THROWS_AS(parse({"render", "m.cbtf", "--light", "nan,0"}), CLI::ParseError);
  CHECK_THROWS_AS(parse({"render", "m.cbtf", "--camera", "inf,0"}), CLI::ParseError);
  CHECK_THROWS_AS(parse({"fidelity", "m.cbtf"}), CLI::RequiredError);
}
