// Bonn UBO2014 .btf files laid out byte by byte here, so that the order of lights, views, texels and
// channels is checked independently of carbtf's writer, and one test per bad file, each checking that
// the error names the file and the field. The reader alone (carbtf::btf_io): these run in the
// sanitized tree too ([btf]).
#include <catch2/catch.hpp>

#include <Imath/half.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "carbtf/analysis/btf/btf_reader.hpp"
#include "carbtf/analysis/input_error.hpp"
#include "scratch_folder.hpp"

using namespace carbtf;
namespace fs = std::filesystem;

// Named, not anonymous: the tests build as one unity source, where other files have helpers of the
// same names.
namespace ubo2014_file_tests {

const BtfLoadOptions kQuiet{0, false};

std::vector<float> image_of(const BtfDataset& dataset, LightView pair) {
  std::vector<float> rgb(dataset.pixel_count() * 3);
  dataset.linear_rgb(pair, rgb);
  return rgb;
}

struct Bytes {
  std::vector<std::uint8_t> data;
  template <class T>
  void put(T v) {
    const std::size_t at = data.size();
    data.resize(at + sizeof v);
    std::memcpy(&data[at], &v, sizeof v);
  }
  void put_text(const std::string& s) {
    const std::size_t at = data.size();
    data.resize(at + s.size());
    std::memcpy(&data[at], s.data(), s.size());
  }
  template <class T>
  void patch(std::size_t offset, T v) {
    std::memcpy(&data[offset], &v, sizeof v);
  }
  fs::path save(const std::string& name) const {
    const fs::path path = test::scratch_folder("ubo2014_bytes") / name;
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(data.data()), static_cast<std::streamsize>(data.size()));
    return path;
  }
};

// Meta data of version 4 (291 bytes), then `views` views at theta 0.2 * (v + 1), phi 0.5, each with
// lights at theta 0.3 * (l + 1), phi 1.0 * l, then width x height.
Bytes common_header(std::string_view signature, std::uint32_t views, std::uint32_t lights,
                    std::uint32_t width, std::uint32_t height, bool cosine_in_data = true) {
  Bytes b;
  b.put_text(std::string(signature));
  b.put(std::uint32_t{291});
  b.put(std::uint32_t{4});
  b.put_text(std::string(240, '\0'));
  b.put(1.0f);
  for (int c = 0; c < 3; ++c) b.put(1.0f);
  b.put(std::uint32_t{cosine_in_data});
  b.put(std::uint32_t{0});
  b.put(std::uint32_t{3});
  for (const char* name : {"R", "G", "B"}) {
    b.put(std::uint32_t{1});
    b.put_text(name);
  }
  b.put(views);
  for (std::uint32_t v = 0; v < views; ++v) {
    b.put(0.2f * static_cast<float>(v + 1));
    b.put(0.5f);
    b.put(lights);
    for (std::uint32_t l = 0; l < lights; ++l) {
      b.put(0.3f * static_cast<float>(l + 1));
      b.put(1.0f * static_cast<float>(l));
    }
  }
  b.put(width);
  b.put(height);
  return b;
}

// The value a hand-made file stores for channel c of light l, view v, texel (x, y): every one distinct.
float hand_value(int c, int l, int v, int x, int y) {
  return static_cast<float>(1 + c + 4 * l + 16 * v + 64 * x + 256 * y) / 1024.0f;
}

// A raw file of 2 views x 3 lights of 2 x 2 texels, one scan line per chunk.
Bytes hand_bdi() {
  Bytes b = common_header("!BDIF06R2!", 2, 3, 2, 2);
  b.put(std::uint32_t{1});  // scan lines per chunk
  b.put(std::uint8_t{0});   // full
  for (int t = 0; t < 4; ++t) b.put(std::uint8_t{1});
  b.put(std::uint32_t{0});  // rotations
  for (int y = 0; y < 2; ++y) {
    b.put(std::uint32_t{2 * 2 * 3 * 3 * 2});
    for (int x = 0; x < 2; ++x) {
      for (int v = 0; v < 2; ++v) {
        for (int l = 0; l < 3; ++l) {
          for (int c = 0; c < 3; ++c) b.put(Imath::half(hand_value(c, l, v, x, y)).bits());
        }
      }
    }
  }
  return b;
}

// A DFMF file of the same table, one component, the texels in U's rows (the other orientation than
// UBO2014's own files): channel c of (l, v, x, y) is (x + 2 y + 1) * (c + 1) * (l + 3 v + 1).
Bytes hand_dfmf() {
  Bytes b = common_header("!DFMF08FCR", 2, 3, 2, 2);
  b.put(std::uint32_t{0});  // rotations
  b.put(std::uint32_t{1});  // components
  b.put(std::int32_t{0});   // RGB
  for (int i = 0; i < 12; ++i) b.put(0.0f);
  for (int c = 0; c < 3; ++c) {
    b.put(std::uint8_t{4});
    b.put(std::uint32_t{1});
    b.put(std::uint32_t{4});  // rows: texels
    b.put(std::uint32_t{6});  // columns: pairs
    b.put(1.0f);
    for (int t = 0; t < 4; ++t) b.put(static_cast<float>(t + 1) * static_cast<float>(c + 1));
    for (int p = 0; p < 6; ++p) b.put(static_cast<float>(p + 1) / 64.0f);
  }
  return b;
}

void require_input_error(const fs::path& path, const std::vector<std::string>& fragments) {
  std::vector<std::string> warnings;
  try {
    const BtfDataset dataset = load_btf(path, kQuiet, warnings);
    // A DFMF file's values are decoded on access.
    std::vector<float> rgb(dataset.pixel_count() * 3);
    for (const LightView pair : dataset.present_pairs()) dataset.linear_rgb(pair, rgb);
    FAIL("loading " << path << " did not fail");
  } catch (const InputError& e) {
    const std::string message = e.what();
    INFO(message);
    CHECK(message.find(path.string()) != std::string::npos);
    for (const auto& fragment : fragments) CHECK(message.find(fragment) != std::string::npos);
  }
}

}  // namespace ubo2014_file_tests

TEST_CASE("UBO2014 files laid out by hand decode in the format's order", "[btf][ubo2014]") {
  using namespace ubo2014_file_tests;  // here, not at file scope: one unity source
  std::vector<std::string> warnings;
  SECTION("raw: channel fastest, then light, then view; texels x fastest, row 0 at the top") {
    const BtfDataset btf = load_btf(hand_bdi().save("hand_bdi.btf"), kQuiet, warnings);
    REQUIRE(btf.lights().size() == 3);
    REQUIRE(btf.views().size() == 2);
    CHECK(btf.lights()[2].theta == Approx(0.9f));
    CHECK(btf.lights()[2].phi == Approx(2.0f));
    CHECK(btf.views()[1].theta == Approx(0.4f));
    for (std::uint32_t l = 0; l < 3; ++l) {
      for (std::uint32_t v = 0; v < 2; ++v) {
        const auto rgb = image_of(btf, {l, v});
        for (int y = 0; y < 2; ++y) {
          for (int x = 0; x < 2; ++x) {
            for (int c = 0; c < 3; ++c) {
              CHECK(rgb[(y * 2 + x) * 3 + c] ==
                    static_cast<float>(Imath::half(hand_value(c, int(l), int(v), x, y))));
            }
          }
        }
      }
    }
  }
  SECTION("DFMF: the pairs' rows light fastest, the texels' x fastest") {
    const BtfDataset btf = load_btf(hand_dfmf().save("hand_dfmf.btf"), kQuiet, warnings);
    for (std::uint32_t l = 0; l < 3; ++l) {
      for (std::uint32_t v = 0; v < 2; ++v) {
        const auto rgb = image_of(btf, {l, v});
        for (int t = 0; t < 4; ++t) {
          for (int c = 0; c < 3; ++c) {
            CHECK(rgb[t * 3 + c] == Approx(static_cast<float>((t + 1) * (c + 1) * (l + 3 * v + 1)) / 64.0f));
          }
        }
      }
    }
  }
  CHECK(warnings.empty());
}

TEST_CASE("Bad UBO2014 files get one clear error naming the file and the field", "[btf][ubo2014]") {
  using namespace ubo2014_file_tests;  // here, not at file scope: one unity source
  // Offsets in hand_bdi() / hand_dfmf(): meta data at 10, views at 301 (3 lights: 36 bytes a view),
  // width at 377, height at 381; BDI: chunk lines 385, compression 389, mask 390, rotations 394,
  // first chunk's size 398; DFMF: rotations 385, components 389, model 393, channel 0 at 445 (scalar
  // size), its components 446, rows 450, columns 454, values from 458.
  SECTION("a wrong signature") {
    Bytes b = hand_bdi();
    b.data[1] = 'X';
    require_input_error(b.save("signature.btf"), {"signature", "not a UBO2014"});
  }
  SECTION("a layout carbtf does not read") {
    Bytes b = hand_bdi();
    std::memcpy(b.data.data(), "!FMF12FCER", 10);
    require_input_error(b.save("fmf.btf"), {"signature", "FMF"});
  }
  SECTION("a truncated header") {
    Bytes b = hand_dfmf();
    b.data.resize(360);  // inside view 1's light table
    require_input_error(b.save("short_header.btf"), {"view 1 light 0", "truncated"});
  }
  SECTION("a truncated body") {
    for (Bytes b : {hand_bdi(), hand_dfmf()}) {
      b.data.resize(b.data.size() - 5);
      require_input_error(b.save("short_body.btf"), {"truncated"});
    }
  }
  SECTION("a meta data size that is not its fields'") {
    Bytes b = hand_bdi();
    b.patch(10, std::uint32_t{290});
    require_input_error(b.save("meta.btf"), {"meta data size"});
  }
  SECTION("direction counts that do not match the tables") {
    Bytes views = hand_bdi();
    views.patch(301 + 4 + 36 + 8, std::uint32_t{2});  // view 1 declares 2 lights
    require_input_error(views.save("lights.btf"), {"view 1 light count", "view 0 has 3"});
    Bytes rows = hand_dfmf();
    rows.patch(450, std::uint32_t{5});
    require_input_error(rows.save("rows.btf"), {"DFMF channel 0 rows and columns", "6 light/view pairs"});
    Bytes chunk = hand_bdi();
    chunk.patch(398, std::uint32_t{70});
    require_input_error(chunk.save("chunk.btf"), {"BDI chunk 0 size"});
  }
  SECTION("sizes past the format's limits") {
    Bytes wide = hand_bdi();
    wide.patch(377, std::uint32_t{1u << 20});
    require_input_error(wide.save("wide.btf"), {"width", "not in 1-16384"});
    Bytes views = hand_bdi();
    views.patch(301, std::uint32_t{5000});
    require_input_error(views.save("views.btf"), {"view directions"});
    Bytes components = hand_dfmf();
    components.patch(389, std::uint32_t{0xffffffffu});
    components.patch(446, std::uint32_t{0x7fffffffu});
    require_input_error(components.save("components.btf"), {"DFMF channel 0 component count"});
    Bytes huge = hand_dfmf();
    huge.patch(377, std::uint32_t{16384});
    huge.patch(381, std::uint32_t{16384});
    huge.patch(450, std::uint32_t{6});  // the pairs in U's rows, the texels in the columns
    huge.patch(454, std::uint32_t{16384u * 16384u});
    require_input_error(huge.save("huge.btf"), {"DFMF channel 0 factors", "truncated"});
    Bytes scalar = hand_dfmf();
    scalar.data[445] = 3;
    require_input_error(scalar.save("scalar.btf"), {"scalar size"});
    Bytes model = hand_dfmf();
    model.patch(393, std::int32_t{5});
    require_input_error(model.save("model.btf"), {"colour model", "spectral"});
    Bytes compression = hand_bdi();
    compression.data[389] = 1;
    require_input_error(compression.save("bzip.btf"), {"BDI compression", "bzip2"});
  }
  SECTION("NaN angles and values") {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    Bytes angle = hand_bdi();
    angle.patch(301 + 4 + 12 + 4, nan);  // view 0, light 0's phi
    require_input_error(angle.save("angle.btf"), {"view 0 light 0", "not a finite number"});
    Bytes grazing = hand_bdi();
    grazing.patch(301 + 4, 1.6f);  // view 0's theta, past pi/2
    require_input_error(grazing.save("grazing.btf"), {"view 0", "not in [0, pi/2)"});
    Bytes value = hand_bdi();
    value.patch(402 + 2 * 7, std::uint16_t{0x7e00});  // a half NaN in the first chunk
    require_input_error(value.save("value.btf"), {"BDI chunk 0", "not a finite number"});
    Bytes factor = hand_dfmf();
    factor.patch(458 + 4 * 2, nan);
    require_input_error(factor.save("factor.btf"), {"DFMF channel 0 U", "not a finite float"});
    Bytes overflow = hand_dfmf();
    overflow.patch(393, std::int32_t{12});  // log RGB: exp of the values below overflows
    for (int p = 0; p < 6; ++p) overflow.patch(458 + 4 * 5 + 4 * p, 1e30f);
    require_input_error(overflow.save("overflow.btf"), {"decodes to a value that is not finite"});
  }
}
