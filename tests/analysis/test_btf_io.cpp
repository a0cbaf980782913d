// BTF data: UBO2003 names, sample -> folder / zip -> read back, partial datasets, and one test per bad
// input, each checking that the error names the file and the problem.
#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <zip.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>

#include <cmath>
#include <filesystem>

#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <sstream>
#include "scratch_folder.hpp"
#include "test_materials.hpp"

#include "carbtf/analysis/btf/btf_reader.hpp"
#include "carbtf/analysis/btf/ubo2003_names.hpp"
#include "carbtf/analysis/btf/ubo2003_writer.hpp"
#include "carbtf/analysis/image_io.hpp"
#include "carbtf/analysis/input_error.hpp"
#include "carbtf/analysis/sample/height_field_renderer.hpp"
#include "carbtf/analysis/sample/sample_materials.hpp"
#include "carbtf/engine/material/material_file.hpp"  // crc32, the PNG chunk checksum too

using namespace carbtf;
namespace fs = std::filesystem;

namespace {

using test::scratch_folder;

const BtfLoadOptions kQuiet{0, false};

// A uniform image file named for UBO2003 pair (light, view).
void write_uniform(const fs::path& path, std::uint32_t size, float value) {
  std::vector<float> rgb(std::size_t{size} * size * 3, value);
  write_rgb_image(path, rgb, size, size);
}

std::string name_of(std::uint32_t light, std::uint32_t view, const std::string& ext = ".png") {
  return ubo2003_file_name(light, view, ext);
}

// Requires load_btf(path) to throw InputError whose message contains every fragment.
void require_input_error(const fs::path& path, const std::vector<std::string>& fragments) {
  std::vector<std::string> warnings;
  try {
    load_btf(path, kQuiet, warnings);
    FAIL("loading " << path << " did not fail");
  } catch (const InputError& e) {
    const std::string message = e.what();
    INFO("message: " << message);
    for (const std::string& fragment : fragments) CHECK_THAT(message, Catch::Contains(fragment));
  }
}

struct RenderedSample {
  Surface surface;
  std::map<std::uint32_t, std::vector<float>> images;  // key light * 81 + view
};

const RenderedSample& rendered_leather() {
  static const RenderedSample sample = [] {
    RenderedSample s;
    s.surface = make_sample_surface("leather", 16, 5);
    std::mutex mutex;
    RenderOptions options;
    options.progress = false;
    render_btf(s.surface, ubo2003_directions(), ubo2003_directions(), options,
               [&](std::uint32_t l, std::uint32_t v, std::span<const float> image) {
                 std::lock_guard<std::mutex> lock(mutex);
                 s.images[l * 81 + v].assign(image.begin(), image.end());
               });
    return s;
  }();
  return sample;
}

void write_sample(const fs::path& out, const std::string& extension, bool zip) {
  const RenderedSample& s = rendered_leather();
  Ubo2003Writer writer(out, extension, zip);
  for (const auto& [key, image] : s.images) writer.write(key / 81, key % 81, image, 16, 16);
  writer.finish();
}

// Largest and RMS difference, in 8-bit sRGB steps, between a loaded image and the rendered one.
void srgb_difference(const BtfDataset& dataset, LightView pair, const std::vector<float>& rendered,
                     double& max_steps, double& rms_steps) {
  std::vector<float> loaded(dataset.pixel_count() * 3);
  dataset.linear_rgb(pair, loaded);
  double sum = 0;
  max_steps = 0;
  for (std::size_t i = 0; i < loaded.size(); ++i) {
    const double a = linear_to_srgb(loaded[i]) * 255.0;
    const double b = linear_to_srgb(std::clamp(rendered[i], 0.0f, 1.0f)) * 255.0;
    max_steps = std::max(max_steps, std::abs(a - b));
    sum += (a - b) * (a - b);
  }
  rms_steps = std::sqrt(sum / static_cast<double>(loaded.size()));
}

}  // namespace

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

TEST_CASE("bad input: a missing folder", "[btf][bad-input]") {
  require_input_error("/nonexistent/carbtf/btf", {"/nonexistent/carbtf/btf", "no such file or folder"});
}

TEST_CASE("bad input: a non-image file", "[btf][bad-input]") {
  const fs::path folder = scratch_folder("nonimage");
  write_uniform(folder / name_of(0, 0), 8, 0.5f);
  std::ofstream(folder / "notes.txt") << "measured on Tuesday\n";
  require_input_error(folder, {"notes.txt", "not an image file"});
  fs::remove_all(folder);
}

TEST_CASE("bad input: a corrupt JPEG", "[btf][bad-input]") {
  const fs::path folder = scratch_folder("corrupt");
  write_uniform(folder / name_of(0, 0, ".jpg"), 8, 0.5f);
  std::ofstream(folder / name_of(1, 0, ".jpg"), std::ios::binary) << "\xff\xd8 this is no JPEG stream at all";
  require_input_error(folder, {name_of(1, 0, ".jpg"), "image"});
  fs::remove_all(folder);
}

TEST_CASE("bad input: a truncated JPEG", "[btf][bad-input]") {
  const fs::path folder = scratch_folder("truncated");
  std::vector<float> rgb(64 * 64 * 3);
  for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<float>((i * 37) % 101) / 100.0f;
  write_rgb_image(folder / name_of(0, 0, ".jpg"), rgb, 64, 64);
  write_rgb_image(folder / name_of(1, 0, ".jpg"), rgb, 64, 64);
  const fs::path victim = folder / name_of(1, 0, ".jpg");
  fs::resize_file(victim, fs::file_size(victim) / 2);
  require_input_error(folder, {name_of(1, 0, ".jpg"), "corrupt or truncated"});
  fs::remove_all(folder);
}

TEST_CASE("bad input: mixed image sizes", "[btf][bad-input]") {
  const fs::path folder = scratch_folder("sizes");
  write_uniform(folder / name_of(0, 0), 8, 0.5f);
  write_uniform(folder / name_of(1, 0), 16, 0.5f);
  require_input_error(folder, {name_of(1, 0), "16x16", "8x8"});
  fs::remove_all(folder);
}

TEST_CASE("bad input: unparseable names", "[btf][bad-input]") {
  const fs::path folder = scratch_folder("names");
  write_uniform(folder / name_of(0, 0), 8, 0.5f);
  write_uniform(folder / "IMG_0042.png", 8, 0.5f);
  require_input_error(folder, {"IMG_0042.png", "UBO2003 form"});
  fs::remove_all(folder);
}

TEST_CASE("bad input: duplicate directions", "[btf][bad-input]") {
  const fs::path folder = scratch_folder("duplicates");
  write_uniform(folder / name_of(2, 0), 8, 0.5f);
  write_uniform(folder / ubo2003_view_folder(0) / name_of(2, 0), 8, 0.5f);
  require_input_error(folder, {name_of(2, 0), "duplicate"});
  fs::remove_all(folder);
}

TEST_CASE("bad input: a direction below the horizon", "[btf][bad-input]") {
  const fs::path folder = scratch_folder("horizon");
  write_uniform(folder / "00000 tl095 pl000 tv000 pv000.png", 8, 0.5f);
  require_input_error(folder, {"tl095", "below the horizon"});
  fs::remove_all(folder);
}

TEST_CASE("bad input: an index that contradicts its directions", "[btf][bad-input]") {
  const fs::path folder = scratch_folder("index");
  write_uniform(folder / "00007 tl000 pl000 tv000 pv000.png", 8, 0.5f);
  require_input_error(folder, {"00007", "does not match its directions"});
  fs::remove_all(folder);
}

TEST_CASE("bad input: NaN or Inf in an EXR", "[btf][bad-input]") {
  for (const float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    const fs::path folder = scratch_folder("nan");
    write_uniform(folder / name_of(0, 0, ".exr"), 8, 0.5f);
    std::vector<float> rgb(8 * 8 * 3, 0.5f);
    rgb[3 * (8 * 2 + 5) + 1] = bad;  // pixel (5, 2), green
    write_rgb_image(folder / name_of(1, 0, ".exr"), rgb, 8, 8);
    require_input_error(folder, {name_of(1, 0, ".exr"), std::isnan(bad) ? "NaN" : "Inf", "(5, 2)"});
    fs::remove_all(folder);
  }
}

TEST_CASE("bad input: an image of more than 16 channels", "[btf][bad-input]") {
  const fs::path folder = scratch_folder("channels");
  write_uniform(folder / name_of(0, 0, ".exr"), 8, 0.5f);
  auto out = OIIO::ImageOutput::create((folder / name_of(1, 0, ".exr")).string());
  REQUIRE(out);
  const OIIO::ImageSpec spec(8, 8, 17, OIIO::TypeDesc::FLOAT);
  REQUIRE(out->open((folder / name_of(1, 0, ".exr")).string(), spec));
  const std::vector<float> values(8 * 8 * 17, 0.5f);
  REQUIRE(out->write_image(OIIO::TypeDesc::FLOAT, values.data()));
  REQUIRE(out->close());
  require_input_error(folder, {name_of(1, 0, ".exr"), "has 17 channels", "up to 16"});
  fs::remove_all(folder);
}

TEST_CASE("bad input: an empty zip, and a file that is no zip", "[btf][bad-input]") {
  const fs::path folder = scratch_folder("emptyzip");
  zip_t* archive = zip_open((folder / "empty.zip").c_str(), ZIP_CREATE | ZIP_TRUNCATE, nullptr);
  zip_source_t* source = zip_source_buffer(archive, "hello", 5, 0);
  REQUIRE(zip_file_add(archive, "README.txt", source, 0) >=
          0);  // libzip writes no file for an archive with no entries
  REQUIRE(zip_close(archive) == 0);
  require_input_error(folder / "empty.zip", {"README.txt", "not an image file"});
  // A valid archive with no entries at all: just the 22-byte end-of-central-directory record.
  const char empty_archive[22] = {'P', 'K', 5, 6};
  std::ofstream(folder / "zero_entries.zip", std::ios::binary).write(empty_archive, sizeof empty_archive);
  require_input_error(folder / "zero_entries.zip", {"zero_entries.zip", "archive holds no images"});
  std::ofstream(folder / "none.zip") << "";
  require_input_error(folder / "none.zip", {"none.zip", "zip"});
  std::ofstream(folder / "text.zip") << "just text";
  require_input_error(folder / "text.zip", {"text.zip", "not a readable zip archive"});
  fs::remove_all(folder);
}

namespace {

// A zip of one PNG member, stored or deflated, read back as bytes.
std::vector<std::uint8_t> zip_of_one_png(const fs::path& folder, bool stored) {
  write_uniform(folder / "member.png", 8, 0.4f);
  const std::vector<std::byte> png = read_file_bytes(folder / "member.png");
  const fs::path path = folder / "one.zip";
  zip_t* archive = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, nullptr);
  REQUIRE(archive != nullptr);
  zip_source_t* source = zip_source_buffer(archive, png.data(), png.size(), 0);
  const zip_int64_t index = zip_file_add(archive, name_of(0, 0).c_str(), source, 0);
  REQUIRE(index >= 0);
  REQUIRE(zip_set_file_compression(archive, static_cast<zip_uint64_t>(index),
                                   stored ? ZIP_CM_STORE : ZIP_CM_DEFLATE, 0) == 0);
  REQUIRE(zip_close(archive) == 0);
  std::ifstream file(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

// Offsets of every record with the little-endian signature `signature`.
std::vector<std::size_t> records(const std::vector<std::uint8_t>& bytes, std::uint32_t signature) {
  std::vector<std::size_t> at;
  for (std::size_t i = 0; i + 4 <= bytes.size(); ++i) {
    std::uint32_t word = 0;
    std::memcpy(&word, bytes.data() + i, 4);
    if (word == signature) at.push_back(i);
  }
  return at;
}

}  // namespace

TEST_CASE("bad input: a zip member whose data does not match its CRC-32 is refused, naming the member",
          "[btf][bad-input][zip]") {
  const fs::path folder = scratch_folder("zipcrc");
  for (const bool stored : {true, false}) {
    INFO((stored ? "stored" : "deflated") << " member");
    const std::vector<std::uint8_t> good = zip_of_one_png(folder, stored);
    const std::vector<std::size_t> local = records(good, 0x04034b50), central = records(good, 0x02014b50);
    REQUIRE(local.size() == 1);
    REQUIRE(central.size() == 1);
    std::vector<std::string> warnings;
    CHECK(load_btf(folder / "one.zip", kQuiet, warnings).present_pairs().size() == 1);

    // The recorded CRC changed in both headers (they agree, so the archive opens), the data intact.
    std::vector<std::uint8_t> bad_crc = good;
    bad_crc[local[0] + 14] ^= 0x01;
    bad_crc[central[0] + 16] ^= 0x01;
    std::ofstream(folder / "crcbad.zip", std::ios::binary)
        .write(reinterpret_cast<const char*>(bad_crc.data()), static_cast<std::streamsize>(bad_crc.size()));
    require_input_error(folder / "crcbad.zip", {"crcbad.zip:" + name_of(0, 0) + ": CRC-32 mismatch"});

    if (stored) {
      // The data changed, its CRC as before: a PNG byte past its signature.
      std::uint16_t name_length = 0, extra_length = 0;
      std::memcpy(&name_length, good.data() + local[0] + 26, 2);
      std::memcpy(&extra_length, good.data() + local[0] + 28, 2);
      std::vector<std::uint8_t> bad_data = good;
      bad_data[local[0] + 30 + name_length + extra_length + 20] ^= 0x40;
      std::ofstream(folder / "databad.zip", std::ios::binary)
          .write(reinterpret_cast<const char*>(bad_data.data()),
                 static_cast<std::streamsize>(bad_data.size()));
      require_input_error(folder / "databad.zip", {"databad.zip:" + name_of(0, 0) + ": CRC-32 mismatch"});
    }
  }
  fs::remove_all(folder);
}

TEST_CASE("bad input: a manifest whose direction table would be too large is refused before it is allocated",
          "[btf][manifest][bad-input]") {
  const fs::path folder = scratch_folder("manifest_large");
  // 10,000 rows at 10,000 distinct light and view directions: a table of 10^8 pairs.
  std::ostringstream many;
  for (int i = 0; i < 10000; ++i)
    many << "a.png," << 0.008 * i << "," << 0.03 * i << "," << 0.008 * i << "," << 0.05 * i << "\n";
  std::ofstream(folder / "many.csv") << many.str();
  require_input_error(folder / "many.csv", {"many.csv", "more than 1024 distinct light directions"});

  // 300 rows, 300 lights x 300 views: 90,000 pairs of which 300 measured.
  std::ostringstream sparse;
  for (int i = 0; i < 300; ++i) sparse << "a.png," << 0.25 * i << ",0," << 0.25 * i << ",90\n";
  std::ofstream(folder / "sparse.csv") << sparse.str();
  require_input_error(folder / "sparse.csv",
                      {"sparse.csv", "measures 300 of the 300 x 300 = 90000", "at least 1 in 4"});
  fs::remove_all(folder);
}

TEST_CASE("bad input: zip entries with absolute or ../ paths are refused", "[btf][bad-input]") {
  for (const std::string& entry :
       std::vector<std::string>{"../" + name_of(0, 0), "/tmp/" + name_of(0, 0), "tv000_pv000/../../x.png"}) {
    const fs::path folder = scratch_folder("zipslip");
    const fs::path png = folder / "source.png";
    write_uniform(png, 8, 0.5f);
    const std::vector<std::byte> bytes = read_file_bytes(png);
    zip_t* archive = zip_open((folder / "evil.zip").c_str(), ZIP_CREATE | ZIP_TRUNCATE, nullptr);
    zip_source_t* source = zip_source_buffer(archive, bytes.data(), bytes.size(), 0);
    REQUIRE(zip_file_add(archive, entry.c_str(), source, 0) >= 0);
    REQUIRE(zip_close(archive) == 0);
    require_input_error(folder / "evil.zip", {entry, "absolute or '..' path"});
    // Nothing was written next to the archive or above it.
    CHECK_FALSE(fs::exists(fs::temp_directory_path() / name_of(0, 0)));
    CHECK_FALSE(fs::exists("/tmp/tmp"));
    fs::remove_all(folder);
  }
}

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

namespace {

// Runs `action`, which must throw an InputError whose message holds every fragment.
template <typename Action>
void check_input_error(Action&& action, const std::string& name, const std::string& problem) {
  try {
    action();
    FAIL("no error for " << name);
  } catch (const InputError& e) {
    INFO("message: " << e.what());
    CHECK_THAT(std::string(e.what()), Catch::Contains(name) && Catch::Contains(problem));
  }
}

// A PNG of a few dozen bytes whose header claims `width` x `height` 16-bit RGB pixels: a decompression
// bomb, as far as a reader that trusts the header is concerned.
std::vector<std::byte> png_claiming(std::uint32_t width, std::uint32_t height) {
  std::vector<std::uint8_t> png{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  auto chunk = [&](const char* tag, std::vector<std::uint8_t> data) {
    const auto size = static_cast<std::uint32_t>(data.size());
    for (int shift = 24; shift >= 0; shift -= 8) png.push_back(static_cast<std::uint8_t>(size >> shift));
    std::vector<std::uint8_t> tagged(tag, tag + 4);
    tagged.insert(tagged.end(), data.begin(), data.end());
    png.insert(png.end(), tagged.begin(), tagged.end());
    const std::uint32_t crc = crc32(tagged);
    for (int shift = 24; shift >= 0; shift -= 8) png.push_back(static_cast<std::uint8_t>(crc >> shift));
  };
  std::vector<std::uint8_t> header;
  for (std::uint32_t v : {width, height}) {
    for (int shift = 24; shift >= 0; shift -= 8) header.push_back(static_cast<std::uint8_t>(v >> shift));
  }
  header.insert(header.end(), {16, 2, 0, 0, 0});  // 16-bit, RGB, deflate, adaptive filter, no interlace
  chunk("IHDR", header);
  chunk("IDAT", {0x78, 0x9c, 0x03, 0x00, 0x00, 0x00, 0x00, 0x01});
  chunk("IEND", {});
  std::vector<std::byte> bytes(png.size());
  std::memcpy(bytes.data(), png.data(), png.size());
  return bytes;
}

}  // namespace

TEST_CASE("bad input: an image header claiming 16384x16384 is refused before any pixel is decoded",
          "[btf][bad-input]") {
  // Decoding would take 16384^2 x 3 floats (3 GiB); the check reads the header only.
  const std::vector<std::byte> bomb = png_claiming(16384, 16384);
  CHECK(bomb.size() < 100);
  check_input_error([&] { decode_rgb_image("bomb.png", bomb); }, "bomb.png", "claims 16384x16384 pixels");
  // Within the cap but not the dataset's size: refused from the header too.
  const ImageShape first{64, 64, true};
  check_input_error([&] { decode_rgb_image("other.png", png_claiming(4000, 4000), &first); }, "other.png",
                    "but the others are 64x64");
}

TEST_CASE("bad input: an image is read only by the reader its name gives", "[btf][bad-input]") {
  const std::vector<float> grey(8 * 8 * 3, 0.5f);
  const std::vector<std::byte> png = encode_rgb_image("x.png", grey, 8, 8);
  const std::vector<std::byte> jpeg = encode_rgb_image("x.jpg", grey, 8, 8);
  CHECK(decode_rgb_image("x.png", png).width == 8);
  // No other installed reader (FFmpeg's video readers among them) is tried on what the name does not
  // promise: a name the fuzzer found, with a NUL byte before a QuickTime extension, reached FFmpeg.
  check_input_error([&] { decode_rgb_image("clip.qt", png); }, "clip.qt",
                    "is not named as an image carbtf reads (.png");
  check_input_error([&] { decode_rgb_image(std::string("c.png\0.qt", 9), png); }, "c.png?.qt",
                    "is not named as an image carbtf reads");
  check_input_error([&] { decode_rgb_image("mislabelled.png", jpeg); }, "mislabelled.png",
                    "not a readable image");
}

TEST_CASE("bad input: a FIFO in a dataset folder is refused, not waited on", "[btf][bad-input]") {
  const fs::path folder = scratch_folder("fifo");
  const fs::path fifo = folder / "image.png";
  REQUIRE(mkfifo(fifo.c_str(), 0600) == 0);
  check_input_error([&] { read_file_bytes(fifo); }, fifo.string(), "is not a regular file");
  fs::remove_all(folder);
}
