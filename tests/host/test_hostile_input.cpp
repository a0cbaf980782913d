// Hostile input at the command line, one reproducer per defect a probe found: each ends with one clear
// line and a non-zero exit, or a correct result, within a bounded time; nothing is written where it
// should not be, and nothing is deleted that the command did not create.
#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include "carbtf/analysis/image_io.hpp"
#include "carbtf/engine/material/material_file.hpp"
#include "cli_run.hpp"
#include "material_bytes.hpp"
#include "scratch_folder.hpp"
#include "test_materials.hpp"

namespace fs = std::filesystem;
using namespace carbtf;
using test::check_refused;
using test::line_count;
using test::run;
using test::Run;

namespace {

// A valid material file whose bytes are then patched: every `marker` float becomes `value`.
fs::path patched_material(const fs::path& path, Material material,
                          const std::vector<std::pair<float, float>>& patches) {
  std::vector<std::uint8_t> bytes;
  REQUIRE(encode_material(material, bytes, {.deflate = false}).ok());
  for (const auto& [marker, value] : patches) REQUIRE(test::replace_float(bytes, marker, value) >= 1);
  test::fix_crcs(bytes);
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  return path;
}

std::string write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path.string();
}

}  // namespace

TEST_CASE("a material whose recursion would diverge is refused by every command", "[cli][hostile]") {
  const fs::path folder = test::scratch_folder("hostile_material");
  Material material = test::bumpy_material();
  material.subspaces[1].bands[2].gamma[0] = 0.0123f;  // the marker
  const fs::path unstable = patched_material(folder / "unstable.cbtf", material, {{0.0123f, 1.5f}});
  for (const std::string& command :
       {"info " + unstable.string(),
        "synth " + unstable.string() + " --size 32 --out " + (folder / "s").string(),
        "render " + unstable.string() + " --size 32x32 --out " + (folder / "f.png").string()}) {
    INFO("carbtf " << command);
    check_refused(run(command), unstable.string() + ": subspace 1 level 0 band 2 is an unstable recursion");
  }
  CHECK_FALSE(fs::exists(folder / "s"));
  CHECK_FALSE(fs::exists(folder / "f.png"));

  // A huge sigma and two equal view directions, both with valid CRCs.
  Material loud = test::bumpy_material();
  loud.subspaces[0].bands[0].sigma = 0.0123f;
  check_refused(run("info " + patched_material(folder / "loud.cbtf", loud, {{0.0123f, 3.4e38f}}).string()),
                "beyond +-1000000");
  Material twins = test::bumpy_material();
  twins.views[1] = {0.4321f, 1.2345f};
  const fs::path same = patched_material(folder / "same.cbtf", twins,
                                         {{0.4321f, twins.views[0].theta}, {1.2345f, twins.views[0].phi}});
  check_refused(run("info " + same.string()),
                same.string() + ": view directions: directions 0 and 1 are the same");
  fs::remove_all(folder);
}

TEST_CASE("NaN, infinite and wrapped arguments are refused with one line", "[cli][hostile]") {
  const fs::path folder = test::scratch_folder("hostile_arguments");
  const std::string material = (folder / "m.cbtf").string();
  REQUIRE(write_material_file(material, test::bumpy_material()).ok());
  const std::string png = " --out " + (folder / "f.png").string();
  for (const auto& [arguments, expected] : std::vector<std::pair<std::string, std::string>>{
           {"synth " + material + " --light nan,0 --view 0,0 --out " + (folder / "s").string(),
            "--light: nan is not a finite number"},
           {"synth " + material + " --seed 18446744073709551617 --out " + (folder / "s").string(),
            "--seed: 18446744073709551617 does not fit"},
           {"synth " + material + " --out \"\"", "--out: the path is empty"},
           {"render " + material + " --light 45,0,nan" + png, "--light: nan is not a finite number"},
           {"render " + material + " --light 45,0,1e39" + png, "1e39 is not a finite number"},
           {"render " + material + " --camera nan,0" + png, "--camera: nan"},
           {"render " + material + " --point-light 0,inf,1" + png, "inf is not a finite number"},
           {"render " + material + " --size 4294967297x1" + png, "WIDTHxHEIGHT"},
           {"render " + material + " --size -1x5" + png, "WIDTHxHEIGHT"},
           {"render " + material + " --out " + folder.string(), "is a folder"},
           {"render " + material + " --out " + (folder / "f.xyz").string(), "unknown image type"},
           {"analyze " + folder.string() + " --threads 1000 --out " + (folder / "x.cbtf").string(),
            "--threads"}}) {
    INFO("carbtf " << arguments);
    check_refused(run(arguments), expected);
  }
  CHECK_FALSE(fs::exists(folder / "s"));
  CHECK_FALSE(fs::exists(folder / "f.png"));
  fs::remove_all(folder);
}

TEST_CASE("hostile OBJ meshes: zero normals are recomputed, bad numbers refused, long polygons are linear",
          "[cli][hostile]") {
  const fs::path folder = test::scratch_folder("hostile_obj");
  const std::string material = (folder / "m.cbtf").string();
  REQUIRE(write_material_file(material, test::bumpy_material()).ok());
  const std::string quad = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n";
  const std::string render =
      "render " + material + " --camera 0,0,3 --size 32x32 --texture-size 32 --validation --out ";

  SECTION("zero normals are recomputed from the faces, and the frame is lit") {
    const std::string obj = write_text(folder / "zero.obj", quad + "vn 0 0 0\nf 1/1/1 2/2/1 3/3/1 4/4/1\n");
    const Run r = run(render + (folder / "zero.png").string() + " --mesh " + obj);
    INFO(r.output);
    REQUIRE(r.status == 0);
    CHECK_THAT(r.output, Catch::Contains("recomputed from the faces"));
    const RgbImage image =
        decode_rgb_image((folder / "zero.png").string(), read_file_bytes(folder / "zero.png"));
    const std::size_t centre = (16u * 32u + 16u) * 3u;
    CHECK(int{image.srgb8[centre]} + image.srgb8[centre + 1] + image.srgb8[centre + 2] > 0);
  }
  SECTION("NaN and infinite coordinates and overflowing indices are refused") {
    for (const auto& [text, expected] : std::vector<std::pair<std::string, std::string>>{
             {quad + "vn nan 0 1\nf 1/1/1 2/2/1 3/3/1\n", "'nan' is a non-finite or malformed coordinate"},
             {"v nan 0 0\n" + quad + "f 2/1 3/2 4/3\n", ":1: 'nan' is a non-finite or malformed coordinate"},
             {quad + "f 1/1 2/2 99999999999999999999/3\n", "face index '99999999999999999999'"}}) {
      check_refused(
          run(render + (folder / "bad.png").string() + " --mesh " + write_text(folder / "bad.obj", text)),
          expected);
    }
    CHECK_FALSE(fs::exists(folder / "bad.png"));
  }
  SECTION("one face of 200,000 corners renders in bounded time") {
    // ostringstream: GCC 12 warns falsely (-Wrestrict) on long chains of string concatenation.
    std::ostringstream text;
    constexpr int corners = 200000;
    for (int i = 0; i < corners; ++i) {
      const double a = 2.0 * std::numbers::pi * i / corners;
      text << "v " << std::cos(a) << ' ' << std::sin(a) << " 0\nvt " << 0.5 + 0.5 * std::cos(a) << ' '
           << 0.5 + 0.5 * std::sin(a) << '\n';
    }
    text << 'f';
    for (int i = 1; i <= corners; ++i) text << ' ' << i << '/' << i;
    text << '\n';
    const Run r = run(
        render + (folder / "disc.png").string() + " --mesh " + write_text(folder / "disc.obj", text.str()),
        "timeout 120");
    INFO(r.output);
    CHECK(r.status == 0);
  }
  fs::remove_all(folder);
}

TEST_CASE("a FIFO or a folder given as a material is refused at once", "[cli][hostile]") {
  const fs::path folder = test::scratch_folder("hostile_fifo");
  const fs::path fifo = folder / "x.cbtf";
  REQUIRE(mkfifo(fifo.c_str(), 0600) == 0);
  // timeout: a reader that opened the FIFO would wait for a writer forever.
  check_refused(run("info " + fifo.string(), "timeout 30"), fifo.string() + ": is not a regular file");
  check_refused(run("synth " + fifo.string() + " --out " + (folder / "s").string(), "timeout 30"),
                "is not a regular file");
  check_refused(run("synth " + folder.string() + " --out " + (folder / "s").string()),
                folder.string() + ": is a folder, not a material file");
  fs::remove_all(folder);
}

TEST_CASE("a UBO2014 .btf that is a FIFO or truncated is refused with one line", "[cli][hostile]") {
  const fs::path folder = test::scratch_folder("hostile_btf");
  const fs::path fifo = folder / "fifo.btf";
  REQUIRE(mkfifo(fifo.c_str(), 0600) == 0);
  check_refused(run("info " + fifo.string(), "timeout 30"), fifo.string() + ": is not a regular file");
  const fs::path truncated = folder / "truncated.btf";
  std::ofstream(truncated, std::ios::binary) << "!DFMF08FCR" << std::string(20, '\x01');
  check_refused(run("analyze " + truncated.string() + " --out " + (folder / "m.cbtf").string()),
                truncated.string() + ": meta data");
  CHECK(!fs::exists(folder / "m.cbtf"));
  fs::remove_all(folder);
}

TEST_CASE("bench analyze removes only what it created in its --out folder", "[cli][hostile][slow]") {
  const fs::path folder = test::scratch_folder("hostile_bench");
  const fs::path out = folder / "mine";
  fs::create_directories(out);
  write_text(out / "sentinel.txt", "the user's own file");
  const Run bench = run("bench analyze --materials leather --sizes 16 --out " + out.string());
  INFO(bench.output);
  REQUIRE(bench.status == 0);
  CHECK(fs::exists(out / "sentinel.txt"));
  CHECK(std::distance(fs::directory_iterator(out), fs::directory_iterator()) == 1);  // its scratch is gone

  // A folder of the user's where the bench would write its scratch: refused, and left alone.
  fs::create_directories(out / "leather_16");
  write_text(out / "leather_16" / "keep.txt", "x");
  check_refused(run("bench analyze --materials leather --sizes 16 --out " + out.string()), "already exists");
  CHECK(fs::exists(out / "leather_16" / "keep.txt"));

  // A fresh --out folder the bench created is removed with its scratch.
  const Run fresh = run("bench analyze --materials leather --sizes 16 --out " + (folder / "fresh").string());
  CHECK(fresh.status == 0);
  CHECK_FALSE(fs::exists(folder / "fresh"));
  fs::remove_all(folder);
}
