// Bad BTF input, one test each, each checking that the error names the file and the problem: folders,
// images (corrupt, truncated, mixed, NaN, too many channels, too large, read by the wrong reader, FIFOs)
// and zips (empty, not a zip, CRC mismatches, absolute or ../ paths).
#include "btf_test_files.hpp"

using namespace carbtf;
using namespace carbtf::btf_test_files;

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
