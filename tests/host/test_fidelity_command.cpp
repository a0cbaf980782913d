// `carbtf fidelity`: the calibrated measure through the render pass must see a deliberately broken
// model (its range map flattened) as worse than the fitted one, on each sample material (issues 13 and
// 42: the measure can fail), and the model without its relief tone, pair gains or highlights as worse too.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "carbtf/engine/material/material_file.hpp"
#include "cli_run.hpp"
#include "scratch_folder.hpp"

namespace fs = std::filesystem;
using namespace carbtf;
using test::run;
using test::Run;

namespace {

// The mean of column `wanted` of fidelity.csv (6: rel; 7: s; 13: the model's colour group, the transport
// between its Lab marginals and the measurement's in units of 2 Lab units).
double mean_column(const fs::path& csv, int wanted) {
  std::ifstream file(csv);
  std::string line;
  std::getline(file, line);
  double sum = 0.0;
  int rows = 0;
  while (std::getline(file, line)) {
    std::stringstream fields(line);
    std::string field;
    for (int column = 0; column <= wanted && std::getline(fields, field, ','); ++column) {
      if (column == wanted) sum += std::stod(field);
    }
    ++rows;
  }
  REQUIRE(rows > 0);
  return sum / rows;
}

double fidelity_of(const fs::path& material, const fs::path& btf, const fs::path& out) {
  const Run r =
      run("fidelity " + material.string() + " " + btf.string() + " --validation --out " + out.string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("s mean") && Catch::Contains("rel mean") &&
                           Catch::Contains("fidelity_grid.png"));
  CHECK(fs::exists(out / "fidelity_grid.png"));
  CHECK(fs::exists(out / "fidelity.md"));
  return mean_column(out / "fidelity.csv", 6);
}

// The (light, view) index pairs of fidelity.csv's rows, and the largest view elevation among them.
std::vector<std::pair<int, int>> scored_pairs(const fs::path& csv, double& steepest_view) {
  std::ifstream file(csv);
  std::string line;
  std::getline(file, line);
  std::vector<std::pair<int, int>> pairs;
  steepest_view = 0.0;
  while (std::getline(file, line)) {
    std::stringstream fields(line);
    std::string light, view, light_theta, light_phi, view_theta;
    std::getline(fields, light, ',');
    std::getline(fields, view, ',');
    std::getline(fields, light_theta, ',');
    std::getline(fields, light_phi, ',');
    std::getline(fields, view_theta, ',');
    pairs.emplace_back(std::stoi(light), std::stoi(view));
    steepest_view = std::max(steepest_view, std::stod(view_theta));
  }
  return pairs;
}

// One sample's checks, each sample its own test case so that CTest runs them side by side.
void check_fidelity_ranking(const std::string& name) {
  const fs::path folder = test::scratch_folder("fidelity_" + name);
  REQUIRE(run("sample " + name + " --size 64 --out " + (folder / "sample").string()).status == 0);
  const fs::path btf = folder / "sample" / "btf";
  const fs::path fitted_path = folder / "fitted.cbtf";
  REQUIRE(run("analyze " + btf.string() + " --out " + fitted_path.string()).status == 0);
  Material fitted;
  REQUIRE(read_material_file(fitted_path.string(), fitted).ok());
  const double fitted_rel = fidelity_of(fitted_path, btf, folder / "fitted");

  // Broken where the render pass shows it: the range map flattened. The CAR's noise (sigma halved or
  // doubled, a coefficient's sign flipped) is tested where it is visible, on the subspace images
  // (analysis_tests "[noise]"): leather's fitted noise is nearly silent through the render.
  Material flat = fitted;
  flat.range = {};
  {
    const fs::path path = folder / "range_flattened.cbtf";
    REQUIRE(write_material_file(path.string(), flat).ok());
    const double broken_rel = fidelity_of(path, btf, folder / "range_flattened");
    INFO(name << ": fitted rel " << fitted_rel << ", range flattened rel " << broken_rel);
    CHECK(broken_rel > fitted_rel);
  }
  // Issue 13 item 3c: the relief tone (on by default) must look nearer the measurement than the same
  // analysis without it.
  const fs::path without_tone = folder / "without_tone.cbtf";
  REQUIRE(run("analyze " + btf.string() + " --no-relief-tone --out " + without_tone.string()).status == 0);
  const double without_tone_rel = fidelity_of(without_tone, btf, folder / "without_tone");
  INFO(name << ": fitted rel " << fitted_rel << ", without the relief tone " << without_tone_rel);
  CHECK(without_tone_rel > fitted_rel);
  // The pair gains (on by default) give each pair its measured mean colour: the colour group and rel fall.
  // Since the subspace models are chosen as the render shows them (docs/design.md 5.2), at 64^2 the colour
  // group is, with the gains / without, fidelity seeds 1-3: leather 0.623 / 0.633 / 0.614 against 0.730 /
  // 0.722 / 0.717, fabric 0.327 / 0.364 / 0.337 against 0.466 / 0.466 / 0.460; coast_sand_rocks' no longer
  // falls at this size (0.283 / 0.321 / 0.385 against 0.273 / 0.268 / 0.344), though at 256^2 the gains
  // pay there too (docs/design.md 5.2).
  if (name != "coast_sand_rocks") {
    const fs::path without_gains = folder / "without_gains.cbtf";
    REQUIRE(run("analyze " + btf.string() + " --no-pair-gains --out " + without_gains.string()).status == 0);
    const double without_gains_rel = fidelity_of(without_gains, btf, folder / "without_gains");
    const double colour = mean_column(folder / "fitted" / "fidelity.csv", 13);
    const double without_gains_colour = mean_column(folder / "without_gains" / "fidelity.csv", 13);
    INFO(name << ": fitted rel " << fitted_rel << " colour " << colour << ", without pair gains rel "
              << without_gains_rel << " colour " << without_gains_colour);
    CHECK(without_gains_colour > colour);
    // On the whole (rel) as well: leather 0.099 / 0.098 / 0.092 with, 0.130 / 0.124 / 0.115 without;
    // fabric 0.073 / 0.080 / 0.078 with, 0.079 / 0.084 / 0.083 without.
    CHECK(without_gains_rel > fitted_rel);
  }
  const std::string info = run("info " + fitted_path.string()).output;
  if (name == "fabric") {
    // Its threads are blue and white: the analysis gives the tone a plane per colour channel.
    CHECK_THAT(info, Catch::Contains("tone colour:  per texel (R, G and B planes)"));
  }
  if (name == "coast_sand_rocks") {
    // Relief that darkens every channel alike: the analysis keeps the tone grey. Leather's is grey at
    // 256^2 (colour deviation 0.084), but at 64^2 its lobe (gloss 16) is wider than the sample's
    // highlights, and the tone of the images with that lobe taken out is coloured (deviation 0.181; 0.026
    // with their highlights left in). Decided on the images with their highlights (a temporary build), its
    // tone was grey and its lobe left out, and the model looked further (rel 0.111 / 0.168 / 0.142 against
    // 0.099 / 0.098 / 0.092, fidelity seeds 1-3).
    CHECK_THAT(info, Catch::Contains("tone colour:  grey"));
  }
  // The analysis keeps the relief's specular lobe on every sample: fabric's glossy threads, leather's
  // faint sheen and coast_sand_rocks' stones. It puts their highlights on the relief's facets where the
  // CAR could only scatter them, and the model without it looks further.
  CHECK_THAT(info, Catch::Contains("highlights:   a specular lobe on the relief"));
  Material dull = fitted;
  dull.range.specular_strength = 0.0f;
  const fs::path dull_path = folder / "without_highlights.cbtf";
  REQUIRE(write_material_file(dull_path.string(), dull).ok());
  const double dull_rel = fidelity_of(dull_path, btf, folder / "without_highlights");
  INFO(name << ": fitted rel " << fitted_rel << ", without its highlights " << dull_rel);
  CHECK(dull_rel > fitted_rel);
  fs::remove_all(folder);
}

}  // namespace

TEST_CASE("carbtf fidelity ranks a deliberately broken leather model worse than the fitted one",
          "[cli][fidelity][slow]") {
  check_fidelity_ranking("leather");
}

TEST_CASE("carbtf fidelity ranks a deliberately broken fabric model worse than the fitted one",
          "[cli][fidelity][slow]") {
  check_fidelity_ranking("fabric");
}

TEST_CASE("carbtf fidelity ranks a deliberately broken coast_sand_rocks model worse than the fitted one",
          "[cli][fidelity][slow]") {
  check_fidelity_ranking("coast_sand_rocks");
}

TEST_CASE("carbtf bench fidelity sets each model option's size beside its fidelity",
          "[cli][fidelity][bench][slow]") {
  const fs::path folder = test::scratch_folder("bench_fidelity");
  REQUIRE(run("sample leather --size 64 --out " + (folder / "sample").string()).status == 0);
  const fs::path btf = folder / "sample" / "btf";
  const fs::path out = folder / "out";
  const Run r =
      run("bench fidelity " + btf.string() + " --variants paper,tone64 --validation --out " + out.string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("paper") && Catch::Contains("tone64") && Catch::Contains("KiB"));
  CHECK(fs::exists(out / "fidelity_size.png"));
  // The Markdown table scripts/figures.sh assembles docs/figures.md from: a row per variant.
  std::ifstream markdown(out / "fidelity_size.md");
  const std::string table((std::istreambuf_iterator<char>(markdown)), std::istreambuf_iterator<char>());
  CHECK_THAT(table, Catch::Contains("| variant | KiB | mean s |") && Catch::Contains("| paper | ") &&
                        Catch::Contains("| tone64 | "));
  std::ifstream csv(out / "fidelity_size.csv");
  std::string line;
  std::getline(csv, line);
  CHECK(line.rfind("variant,description,bytes,mean_s,worst_s,mean_rel", 0) == 0);
  int rows = 0;
  while (std::getline(csv, line)) {
    std::stringstream fields(line);
    std::string variant;
    std::getline(fields, variant, ',');
    // The size column is the material file's size on disk.
    const std::size_t bytes_at = line.find("\",") + 2;
    const auto bytes = std::stoull(line.substr(bytes_at));
    CHECK(bytes == fs::file_size(out / (variant + ".cbtf")));
    ++rows;
  }
  CHECK(rows == 2);

  const Run unknown =
      run("bench fidelity " + btf.string() + " --variants nonsense --out " + (folder / "other").string());
  CHECK(unknown.status != 0);
  CHECK_THAT(unknown.output,
             Catch::Contains("unknown variant 'nonsense'") && Catch::Contains("known: paper"));
  CHECK_FALSE(fs::exists(folder / "other"));
  // A second run into the same folder refuses to overwrite the first's files.
  const Run again = run("bench fidelity " + btf.string() + " --variants paper --out " + out.string());
  CHECK(again.status != 0);
  fs::remove_all(folder);
}

TEST_CASE("carbtf fidelity scores the pairs asked for or a spread over every light and view",
          "[cli][fidelity][slow]") {
  const fs::path folder = test::scratch_folder("fidelity_pairs");
  REQUIRE(run("sample leather --size 64 --out " + (folder / "sample").string()).status == 0);
  const fs::path btf = folder / "sample" / "btf", material = folder / "leather.cbtf";
  REQUIRE(run("analyze " + btf.string() + " --out " + material.string()).status == 0);
  const std::string fidelity = "fidelity " + material.string() + " " + btf.string();

  const Run chosen = run(fidelity + " --pairs 1,0,19,0 --validation --out " + (folder / "chosen").string());
  INFO(chosen.output);
  REQUIRE(chosen.status == 0);
  double steepest = 0.0;
  CHECK(scored_pairs(folder / "chosen" / "fidelity.csv", steepest) ==
        std::vector<std::pair<int, int>>{{1, 0}, {19, 0}});
  // Per pair, its octaves in order, periods doubling from 4 pixels, every value a number.
  std::ifstream octaves(folder / "chosen" / "fidelity_octaves.csv");
  std::string line;
  std::getline(octaves, line);
  CHECK(
      line.rfind(
          "light,view,octave,period_px,model_energy_db,model_a_energy_db,model_b_energy_db,model_skewness_x",
          0) == 0);
  std::vector<std::vector<double>> rows;
  while (std::getline(octaves, line)) {
    std::stringstream fields(line);
    std::string field;
    std::vector<double> row;
    while (std::getline(fields, field, ',')) row.push_back(std::stod(field));
    CHECK(row.size() == 22);
    CHECK(std::all_of(row.begin(), row.end(), [](double v) { return std::isfinite(v); }));
    rows.push_back(row);
  }
  REQUIRE(rows.size() >= 4);
  REQUIRE(rows.size() % 2 == 0);
  const std::size_t per_pair = rows.size() / 2;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    CHECK(rows[i][0] == (i < per_pair ? 1.0 : 19.0));
    CHECK(rows[i][2] == static_cast<double>(i % per_pair));
    CHECK(rows[i][3] == std::ldexp(4.0, static_cast<int>(i % per_pair)));
  }

  // Six distinct pairs, the same on every run, none so oblique that the 64-pixel plane is too thin to
  // score (the run fails on such a pair: cos 75 degrees x 64 is 16.6 pixels).
  const Run spread = run(fidelity + " --spread 6 --validation --out " + (folder / "spread").string());
  INFO(spread.output);
  REQUIRE(spread.status == 0);
  CHECK_THAT(spread.output, Catch::Contains("6 pairs"));
  const auto pairs = scored_pairs(folder / "spread" / "fidelity.csv", steepest);
  CHECK(pairs.size() == 6);
  CHECK(std::set<std::pair<int, int>>(pairs.begin(), pairs.end()).size() == pairs.size());
  CHECK(steepest < 75.0);
  CHECK(std::any_of(pairs.begin(), pairs.end(),
                    [](const auto& p) { return p.second != 0; }));  // not the top view alone
  REQUIRE(run(fidelity + " --spread 6 --out " + (folder / "again").string()).status == 0);
  double steepest_again = 0.0;
  CHECK(scored_pairs(folder / "again" / "fidelity.csv", steepest_again) == pairs);

  const Run odd = run(fidelity + " --pairs 1 --out " + (folder / "odd").string());
  CHECK(odd.status != 0);
  CHECK_THAT(odd.output, Catch::Contains("an even count"));
  const Run both = run(fidelity + " --pairs 1,0 --spread 3 --out " + (folder / "both").string());
  CHECK(both.status != 0);
  CHECK_THAT(both.output, Catch::Contains("excludes"));
  // At 16^2 even the top view's image is too thin for the spread's margin: an error, not the default pairs.
  REQUIRE(run("sample leather --size 16 --out " + (folder / "tiny").string()).status == 0);
  const fs::path tiny_btf = folder / "tiny" / "btf", tiny = folder / "tiny.cbtf";
  REQUIRE(run("analyze " + tiny_btf.string() + " --out " + tiny.string()).status == 0);
  const Run none = run("fidelity " + tiny.string() + " " + tiny_btf.string() + " --spread 4 --out " +
                       (folder / "none").string());
  CHECK(none.status != 0);
  CHECK_THAT(none.output, Catch::Contains("--spread: no measured pair") && Catch::Contains("too small"));
  fs::remove_all(folder);
}
