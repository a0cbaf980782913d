// BTF data as UBO2003 folders and zips: the names and directions, sample -> folder / zip -> read back,
// partial datasets, flat and enclosing folders.
#include "btf_test_files.hpp"

using namespace carbtf;
using namespace carbtf::btf_test_files;

TEST_CASE("the UBO2003 direction table and names agree with the database's conventions", "[btf]") {
  const auto& d = ubo2003_directions();
  REQUIRE(d.size() == 81);
  const auto stored = test::ubo2003_material_directions();  // the engine tests' copy of the set
  for (std::size_t i = 0; i < d.size(); ++i) {
    CHECK(stored[i].theta == static_cast<float>(d[i].theta));
    CHECK(stored[i].phi == static_cast<float>(d[i].phi));
  }
  CHECK(ubo2003_index(0, 0) == 0u);
  CHECK(ubo2003_index(15, 60) == 2u);
  CHECK(ubo2003_index(75, 345) == 80u);
  CHECK_FALSE(ubo2003_index(75, 344).has_value());
  CHECK(ubo2003_file_name(0, 0, ".jpg") == "00000 tl000 pl000 tv000 pv000.jpg");
  CHECK(ubo2003_file_name(80, 1, ".jpg") == "06481 tl075 pl345 tv015 pv000.jpg");
  CHECK(ubo2003_view_folder(7) == "tv030_pv000");
  for (std::uint32_t l = 0; l < 81; ++l) {
    for (std::uint32_t v = 0; v < 81; ++v) {
      const auto parsed = parse_ubo2003_name(ubo2003_file_name(l, v, ".JPG"));
      REQUIRE(parsed.has_value());
      REQUIRE(parsed->index == l * 81 + v);
      REQUIRE(ubo2003_index(parsed->theta_light, parsed->phi_light) == l);
      REQUIRE(ubo2003_index(parsed->theta_view, parsed->phi_view) == v);
      REQUIRE(parsed->extension == ".jpg");
    }
  }
  CHECK_FALSE(parse_ubo2003_name("0000 tl000 pl000 tv000 pv000.jpg").has_value());
  CHECK_FALSE(parse_ubo2003_name("00000 tl000 pl000 tv000 pv000").has_value());
  CHECK_FALSE(parse_ubo2003_name("00000_tl000_pl000_tv000_pv000.jpg").has_value());
}

TEST_CASE("a sample written as a UBO2003 folder and as a zip reads back the same", "[btf][roundtrip][slow]") {
  const RenderedSample& sample = rendered_leather();
  const fs::path folder = scratch_folder("roundtrip");
  for (const std::string extension : {".jpg", ".png", ".exr"}) {
    DYNAMIC_SECTION("format " << extension) {
      write_sample(folder / ("btf" + extension), extension, false);
      write_sample(folder / ("btf" + extension + ".zip"), extension, true);
      std::vector<std::string> warnings;
      const BtfDataset from_folder = load_btf(folder / ("btf" + extension), kQuiet, warnings);
      const BtfDataset from_zip = load_btf(folder / ("btf" + extension + ".zip"), kQuiet, warnings);
      CHECK(warnings.empty());
      for (const BtfDataset* dataset : {&from_folder, &from_zip}) {
        REQUIRE(dataset->lights().size() == 81);
        REQUIRE(dataset->views().size() == 81);
        REQUIRE(dataset->width() == 16);
        REQUIRE(dataset->missing_pairs().empty());
        CHECK(dataset->encoding() ==
              (extension == ".exr" ? ColorEncoding::linear_half : ColorEncoding::srgb8));
        // The JPEGs' 4:2:0 chroma has half the brightness's resolution; PNG and EXR keep it whole.
        CHECK(dataset->chroma_halvings == (extension == ".jpg" ? 1u : 0u));
      }
      double worst_max = 0, worst_rms = 0;
      for (const auto& [key, rendered] : sample.images) {
        const LightView pair{key / 81, key % 81};
        double max_steps = 0, rms_steps = 0;
        srgb_difference(from_folder, pair, rendered, max_steps, rms_steps);
        worst_max = std::max(worst_max, max_steps);
        worst_rms = std::max(worst_rms, rms_steps);
        // Folder and zip hold the same bytes, so they decode to the same pixels.
        std::vector<float> a(from_folder.pixel_count() * 3), b(a.size());
        from_folder.linear_rgb(pair, a);
        from_zip.linear_rgb(pair, b);
        REQUIRE(a == b);
      }
      INFO("worst max " << worst_max << " and worst RMS " << worst_rms << " sRGB steps");
      if (extension == ".jpg") {
        // JPEG at quality 95 with chroma subsampling on 16x16 images of sharp creases.
        CHECK(worst_rms < 6.0);
      } else {
        // PNG: 8-bit rounding only (half a step); EXR: half precision (well under a step).
        CHECK(worst_max <= 0.5 + 1e-3);
      }
    }
  }
  fs::remove_all(folder);
}

TEST_CASE("a partial dataset loads with a warning listing what is missing", "[btf]") {
  const fs::path folder = scratch_folder("partial");
  write_sample(folder / "btf", ".png", false);
  fs::remove(folder / "btf" / ubo2003_view_folder(0) / name_of(5, 0));
  fs::remove_all(folder / "btf" / ubo2003_view_folder(80));
  std::vector<std::string> warnings;
  const BtfDataset dataset = load_btf(folder / "btf", kQuiet, warnings);
  CHECK(dataset.missing_pairs().size() == 82);
  CHECK_FALSE(dataset.has_image({5, 0}));
  CHECK(dataset.has_image({6, 0}));
  REQUIRE(warnings.size() == 1);
  CHECK_THAT(warnings[0], Catch::Contains("82 of 6561") &&
                              Catch::Contains("light theta 15, phi 240 / view theta 0, phi 0"));
  std::vector<float> out(dataset.pixel_count() * 3);
  CHECK_THROWS_AS(dataset.linear_rgb({5, 0}, out), std::out_of_range);
  fs::remove_all(folder);
}

TEST_CASE("flat folders and enclosing folders in zips are read too", "[btf]") {
  const fs::path folder = scratch_folder("flat");
  write_uniform(folder / "flat" / name_of(0, 0), 8, 0.5f);
  write_uniform(folder / "flat" / name_of(3, 10), 8, 0.25f);
  std::vector<std::string> warnings;
  const BtfDataset flat = load_btf(folder / "flat", kQuiet, warnings);
  CHECK(flat.has_image({0, 0}));
  CHECK(flat.has_image({3, 10}));
  CHECK(flat.present_pairs().size() == 2);

  zip_t* archive = zip_open((folder / "nested.zip").c_str(), ZIP_CREATE | ZIP_TRUNCATE, nullptr);
  const std::vector<std::byte> png = read_file_bytes(folder / "flat" / name_of(0, 0));
  zip_source_t* source = zip_source_buffer(archive, png.data(), png.size(), 0);
  REQUIRE(zip_file_add(archive, ("wool/tv000_pv000/" + name_of(0, 0)).c_str(), source, 0) >= 0);
  REQUIRE(zip_close(archive) == 0);
  const BtfDataset nested = load_btf(folder / "nested.zip", kQuiet, warnings);
  CHECK(nested.present_pairs().size() == 1);
  fs::remove_all(folder);
}
