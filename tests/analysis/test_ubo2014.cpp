// Bonn UBO2014 .btf files written by carbtf in both layouts and read back value for value against the
// same material read from UBO2003 images (the files laid out by hand and the bad files are in
// test_ubo2014_files.cpp).
#include <catch2/catch.hpp>

#include <Imath/half.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <vector>

#include "carbtf/analysis/btf/btf_reader.hpp"
#include "carbtf/analysis/btf/ubo2003_writer.hpp"
#include "carbtf/analysis/btf/ubo2014_writer.hpp"
#include "carbtf/analysis/input_error.hpp"
#include "carbtf/analysis/sample/height_field_renderer.hpp"
#include "carbtf/analysis/sample/sample_materials.hpp"
#include "scratch_folder.hpp"

using namespace carbtf;
namespace fs = std::filesystem;

// Named, not anonymous: the tests build as one unity source, where other files have helpers of the
// same names.
namespace ubo2014_tests {

const BtfLoadOptions kQuiet{0, false};
constexpr std::uint32_t kSize = 16;
// 8 of the 81 UBO2003 directions, from the pole to 75 degrees, for lights and for views.
const std::vector<std::uint32_t> kLights{0, 7, 13, 20, 33, 45, 60, 75};
const std::vector<std::uint32_t> kViews{0, 3, 10, 21, 30, 40, 55, 70};

// The fabric sample's 8 x 8 pairs written as UBO2003 EXR images and read back as a folder.
const BtfDataset& ubo2003_folder_dataset() {
  static const BtfDataset dataset = [] {
    const fs::path folder = test::scratch_folder("ubo2014_images");
    const Surface surface = make_sample_surface("fabric", kSize, 3);
    std::vector<Direction> lights, views;
    for (auto l : kLights) lights.push_back(ubo2003_directions()[l]);
    for (auto v : kViews) views.push_back(ubo2003_directions()[v]);
    {
      Ubo2003Writer writer(folder, ".exr", false);
      RenderOptions render;
      render.progress = false;
      render_btf(surface, lights, views, render,
                 [&](std::uint32_t l, std::uint32_t v, std::span<const float> image) {
                   writer.write(kLights[l], kViews[v], image, kSize, kSize);
                 });
      writer.finish();
    }
    std::vector<std::string> warnings;  // the other 81 x 81 - 64 pairs are missing
    return load_btf(folder, kQuiet, warnings);
  }();
  return dataset;
}

// The same 64 images in an 8 x 8 table.
BtfDataset table_of_8x8() {
  const BtfDataset& folder = ubo2003_folder_dataset();
  std::vector<Direction> lights, views;
  for (auto l : kLights) lights.push_back(ubo2003_directions()[l]);
  for (auto v : kViews) views.push_back(ubo2003_directions()[v]);
  BtfDataset table(lights, views, kSize, kSize, ColorEncoding::linear_half);
  std::vector<float> rgb(folder.pixel_count() * 3);
  for (std::uint32_t l = 0; l < 8; ++l) {
    for (std::uint32_t v = 0; v < 8; ++v) {
      folder.linear_rgb({kLights[l], kViews[v]}, rgb);
      table.set_linear({l, v}, rgb);
    }
  }
  return table;
}

std::vector<float> image_of(const BtfDataset& dataset, LightView pair) {
  std::vector<float> rgb(dataset.pixel_count() * 3);
  dataset.linear_rgb(pair, rgb);
  return rgb;
}

// The largest difference between `btf` and the UBO2003 folder over every pair, and the folder's
// largest value.
std::pair<float, float> largest_difference(const BtfDataset& btf) {
  const BtfDataset& folder = ubo2003_folder_dataset();
  float difference = 0, largest = 0;
  for (std::uint32_t l = 0; l < 8; ++l) {
    for (std::uint32_t v = 0; v < 8; ++v) {
      const auto a = image_of(btf, {l, v});
      const auto b = image_of(folder, {kLights[l], kViews[v]});
      for (std::size_t i = 0; i < a.size(); ++i) {
        difference = std::max(difference, std::abs(a[i] - b[i]));
        largest = std::max(largest, b[i]);
      }
    }
  }
  return {difference, largest};
}

BtfDataset write_and_read(const Ubo2014WriteOptions& options, const std::string& name) {
  const fs::path path = test::scratch_folder("ubo2014_" + name) / (name + ".btf");
  write_ubo2014_btf(path, table_of_8x8(), options);
  std::vector<std::string> warnings;
  BtfDataset dataset = load_btf(path, kQuiet, warnings);
  CHECK(warnings.empty());
  return dataset;
}

}  // namespace ubo2014_tests

TEST_CASE("UBO2014 files read back value for value in both layouts", "[ubo2014]") {
  using namespace ubo2014_tests;  // here, not at file scope: one unity source
  const BtfDataset& folder = ubo2003_folder_dataset();
  REQUIRE(folder.present_pairs().size() == 64);

  SECTION("raw (BDI)") {
    Ubo2014WriteOptions options;
    options.layout = ubo2014::Layout::bdi;
    options.scan_lines_per_chunk = 3;  // 16 lines: the last chunk holds fewer
    const BtfDataset btf = write_and_read(options, "bdi");
    CHECK(btf.encoding() == ColorEncoding::linear_half);
    CHECK(largest_difference(btf).first == 0.0f);
  }
  SECTION("DFMF, one component per pair") {
    const BtfDataset btf = write_and_read({}, "dfmf");
    CHECK(btf.encoding() == ColorEncoding::decoded);
    CHECK(largest_difference(btf).first == 0.0f);
  }
  SECTION("the directions are the file's") {
    const BtfDataset btf = write_and_read({}, "directions");
    REQUIRE(btf.lights().size() == 8);
    REQUIRE(btf.views().size() == 8);
    for (std::size_t i = 0; i < 8; ++i) {
      CHECK(angle_between(btf.lights()[i], ubo2003_directions()[kLights[i]]) < 1e-6);
      CHECK(angle_between(btf.views()[i], ubo2003_directions()[kViews[i]]) < 1e-6);
    }
  }
}

TEST_CASE("UBO2014 files without the cosine in their data read as photographs", "[ubo2014]") {
  using namespace ubo2014_tests;  // here, not at file scope: one unity source
  Ubo2014WriteOptions options;
  options.cosine_in_data = false;  // the writer divides by cos(theta_light), the reader multiplies back
  for (const auto layout : {ubo2014::Layout::bdi, ubo2014::Layout::dfmf}) {
    options.layout = layout;
    const auto [difference, largest] = largest_difference(write_and_read(options, "cosine"));
    CHECK(difference > 0.0f);                      // the values went through the division
    CHECK(difference <= largest * (1.0f / 1024));  // and back, within half precision
  }
}

TEST_CASE("UBO2014 DFMF colour models and truncated factorisations", "[ubo2014]") {
  using namespace ubo2014_tests;  // here, not at file scope: one unity source
  Ubo2014WriteOptions options;
  options.scalar_bytes = 4;
  options.components = 64;  // full rank of 64 pairs: exact up to float rounding
  for (const auto model : {ubo2014::ColourModel::rgb, ubo2014::ColourModel::yuv, ubo2014::ColourModel::pca}) {
    options.colour_model = model;
    const auto [difference, largest] = largest_difference(write_and_read(options, "colour"));
    INFO("colour model " << static_cast<int>(model));
    CHECK(difference <= largest * 1e-4f);
  }
  // Fewer components, larger error: the factors are the data's, in the right orientation.
  options.colour_model = ubo2014::ColourModel::yuv;
  options.components = 4;
  const float rank_4 = largest_difference(write_and_read(options, "rank4")).first;
  options.components = 24;
  const float rank_24 = largest_difference(write_and_read(options, "rank24")).first;
  CHECK(rank_24 < rank_4);
}

TEST_CASE("A sparse UBO2014 raw file reads its mask", "[ubo2014]") {
  using namespace ubo2014_tests;  // here, not at file scope: one unity source
  BtfDataset table = table_of_8x8();
  table.mask.assign(table.pixel_count(), 255);
  for (std::size_t t = 0; t < table.mask.size(); t += 3) table.mask[t] = 0;
  Ubo2014WriteOptions options;
  options.layout = ubo2014::Layout::bdi;
  options.sparse = true;
  const fs::path path = test::scratch_folder("ubo2014_sparse") / "sparse.btf";
  write_ubo2014_btf(path, table, options);
  std::vector<std::string> warnings;
  const BtfDataset btf = load_btf(path, kQuiet, warnings);
  REQUIRE(btf.mask == table.mask);
  for (const LightView pair : {LightView{0, 0}, LightView{5, 7}}) {
    const auto read = image_of(btf, pair);
    const auto written = image_of(table, pair);
    for (std::size_t i = 0; i < read.size(); ++i) CHECK(read[i] == (table.mask[i / 3] ? written[i] : 0.0f));
  }
}
