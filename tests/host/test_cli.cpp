// The carbtf command line as a user meets it: exit status, one-line errors, files written.
#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "carbtf/analysis/image_io.hpp"
#include "carbtf/engine/material/material_file.hpp"

#include <sstream>
#include <string>
#include "cli_run.hpp"
#include "scratch_folder.hpp"

namespace fs = std::filesystem;
using namespace carbtf;

namespace {

using test::line_count;
using test::run;
using test::Run;
using test::scratch_folder;

}  // namespace

TEST_CASE("carbtf noise writes the field it was asked for", "[cli]") {
  const fs::path folder = scratch_folder("noise");
  const Run png = run("noise --size 64 --seed 3 --validation --out " + (folder / "sub" / "n.png").string());
  INFO(png.output);
  REQUIRE(png.status == 0);
  CHECK(fs::file_size(folder / "sub" / "n.png") > 0);
  CHECK_THAT(png.output, Catch::Contains("64x64"));
  const Run exr = run("noise --size 32 --reference --out " + (folder / "n.exr").string());
  INFO(exr.output);
  REQUIRE(exr.status == 0);
  CHECK(fs::file_size(folder / "n.exr") > 32 * 32 * 2);
  fs::remove_all(folder);
}

TEST_CASE("bad arguments give one error line and a non-zero exit", "[cli]") {
  const fs::path folder = scratch_folder("errors");
  struct Case {
    std::string arguments;
    std::string expected;
  };
  for (const Case& c :
       {Case{"noise --size 0", "--size"}, Case{"noise --size abc", "--size"},
        Case{"noise --seed -3", "--seed"}, Case{"frobnicate", "frobnicate"},
        Case{"render m.cbtf --direction-taps 7", "--direction-taps: 7 not in {9,5}"},
        Case{"render m.cbtf --parallax-steps 257", "--parallax-steps: Value 257 not in range 0 to 256"},
        Case{"bench frame --lights 5", "--lights"},
        Case{"noise --out " + (folder / "n.xyz").string(), "unsupported image extension"},
        Case{"noise --size 16 --device no-such-gpu --out " + (folder / "n.png").string(), "no-such-gpu"},
        Case{"noise --size 16 --out /proc/carbtf/n.png", "/proc/carbtf"}}) {
    const Run r = run(c.arguments);
    INFO("carbtf " << c.arguments << "\n" << r.output);
    CHECK(r.status != 0);
    CHECK(r.status < 128);  // an error exit, not a crash
    CHECK(line_count(r.output) == 1);
    CHECK_THAT(r.output, Catch::StartsWith("carbtf: error: ") && Catch::Contains(c.expected));
  }
  CHECK_FALSE(fs::exists(folder / "n.xyz"));
  CHECK_FALSE(fs::exists(folder / "n.png"));
  fs::remove_all(folder);
}

TEST_CASE("with no Vulkan driver the error names the package to install", "[cli]") {
  // Point the loader at a driver manifest that does not exist: as on a machine with no driver.
  const std::string no_driver =
      "VK_DRIVER_FILES=/nonexistent/icd.json VK_ICD_FILENAMES=/nonexistent/icd.json";
  for (const std::string arguments : {"devices", "noise --size 16 --out /tmp/carbtf_never_written.png"}) {
    const Run r = run(arguments, no_driver);
    INFO("carbtf " << arguments << "\n" << r.output);
    CHECK(r.status == 1);
    CHECK_THAT(r.output, Catch::Contains("no Vulkan driver") && Catch::Contains("mesa-vulkan-drivers"));
  }
  CHECK_FALSE(fs::exists("/tmp/carbtf_never_written.png"));
}

TEST_CASE("carbtf devices lists the default device", "[cli]") {
  const Run r = run("devices");
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("default"));
}

TEST_CASE("carbtf demo runs the whole pipeline and writes a report", "[cli][slow]") {
  const fs::path folder = scratch_folder("demo");
  const fs::path report = folder / "report";
  const Run r = run("demo --size 48 --texture-size 64 --validation --out " + report.string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  for (const char* stage : {"[1/6] sample", "[2/6] analysis", "[3/6] synthesis", "[4/6] fidelity",
                            "[5/6] render", "[6/6] report"}) {
    CHECK_THAT(r.output, Catch::Contains(stage));
  }
  CHECK_THAT(r.output, Catch::Contains("report: " + (report / "index.html").string()));
  CHECK_THAT(r.output, Catch::Contains("fidelity: s mean ") &&
                           Catch::Contains("the model beats the Gaussian reference on "));
  // The GPU synthesis equals the CPU reference: "bit-identical to the CPU on N of N values".
  CHECK_THAT(r.output, Catch::Contains("bit-identical to the CPU on 245760 of 245760 values"));
  for (const char* file :
       {"index.html", "leather.cbtf", "sphere.png", "synthesized_00.png", "analysis/index_table.png",
        "analysis/eigenvalues.png", "fidelity_grid.png", "fidelity.csv"}) {
    CHECK(fs::exists(report / file));
  }
  const RgbImage sphere =
      decode_rgb_image((report / "sphere.png").string(), read_file_bytes(report / "sphere.png"));
  REQUIRE(sphere.srgb8.size() == 960u * 640u * 3u);
  // The sphere covers the centre, the clear colour the corner.
  CHECK(sphere.srgb8[(320u * 960u + 480u) * 3u] != sphere.srgb8[0]);
  fs::remove_all(folder);
}

TEST_CASE("every command answers --help", "[cli][slow]") {
  for (const std::string command :
       {"", "noise", "devices", "demo", "sample", "info", "analyze", "normals", "synth", "conform", "render",
        "fidelity", "bench noise", "bench data", "bench analyze", "bench synth", "bench frame"}) {
    const Run r = run(command + " --help");
    INFO("carbtf " << command << " --help\n" << r.output);
    CHECK(r.status == 0);
    CHECK_THAT(r.output, Catch::Contains("Usage"));
  }
}

TEST_CASE("carbtf sample writes a UBO2003 zip and ground truth that carbtf info reads", "[cli]") {
  const fs::path folder = scratch_folder("sample");
  const Run sample = run("sample fabric --size 16 --zip --seed 2 --out " + (folder / "fabric").string());
  INFO(sample.output);
  REQUIRE(sample.status == 0);
  for (const char* file : {"btf.zip", "material.json", "ground_truth/range.exr", "ground_truth/normals.png",
                           "ground_truth/albedo.png"}) {
    CHECK(fs::exists(folder / "fabric" / file));
  }
  const Run info = run("info " + (folder / "fabric" / "btf.zip").string());
  INFO(info.output);
  REQUIRE(info.status == 0);
  CHECK_THAT(info.output, Catch::Contains("6561 of 6561") && Catch::Contains("16 x 16") &&
                              Catch::Contains("theta 0, 15, 30, 45, 60, 75"));
  fs::remove_all(folder);
}

TEST_CASE("carbtf sample and info reject bad input with one line", "[cli]") {
  const fs::path folder = scratch_folder("sample_errors");
  for (const auto& [arguments, expected] : std::vector<std::pair<std::string, std::string>>{
           {"sample velvet --out " + (folder / "v").string(), "velvet"},
           {"sample leather --format gif --out " + (folder / "v").string(), "--format"},
           {"info " + (folder / "missing").string(), "no such file or folder"}}) {
    const Run r = run(arguments);
    INFO("carbtf " << arguments << "\n" << r.output);
    CHECK(r.status != 0);
    CHECK(line_count(r.output) == 1);
    CHECK_THAT(r.output, Catch::StartsWith("carbtf: error: ") && Catch::Contains(expected));
  }
  CHECK_FALSE(fs::exists(folder / "v"));
  fs::remove_all(folder);
}

namespace {

// Catch runs a test case's body once per section; the sample and its analysis are made once per
// process and removed when it exits.
struct AnalysedLeather {
  fs::path folder = scratch_folder("analyze");
  fs::path material = folder / "materials" / "leather.cbtf";  // a folder analyze has to make
  Run sample = run("sample leather --size 32 --out " + (folder / "leather").string());
  Run analyze = run("analyze " + (folder / "leather" / "btf").string() + " --out " + material.string() +
                    " --subspaces 8 --levels 2 --report " + (folder / "report").string());
  ~AnalysedLeather() {
    std::error_code ignored;
    fs::remove_all(folder, ignored);
  }
};

}  // namespace

TEST_CASE("carbtf analyze writes a material and a report that carbtf info describes", "[cli][slow]") {
  static const AnalysedLeather analysed;
  const fs::path& folder = analysed.folder;
  const fs::path& material = analysed.material;
  const Run& analyze = analysed.analyze;
  REQUIRE(analysed.sample.status == 0);
  INFO(analyze.output);
  REQUIRE(analyze.status == 0);
  CHECK_THAT(analyze.output, Catch::Contains("segmentation") && Catch::Contains("subspace models") &&
                                 Catch::Contains("ratio 1 : "));
  REQUIRE(fs::exists(material));  // in the folder --out named, which was not there
  for (const char* file :
       {"index_table.png", "eigenvalues.png", "eigenvalues.csv", "subspace_07.png", "normals.png",
        "range_map.exr", "range_enlarged.png", "stages.csv", "analysis_log.txt"}) {
    CHECK(fs::exists(folder / "report" / file));
  }
  const Run info = run("info " + material.string());
  INFO(info.output);
  REQUIRE(info.status == 0);
  CHECK_THAT(info.output, Catch::Contains("(format 1." + std::to_string(kMaterialFormatMinor) + ")"));
  CHECK_THAT(info.output, Catch::Contains("81 lights x 81 views") && Catch::Contains("8, 2 pyramid levels") &&
                              Catch::Contains("SUBS") && Catch::Contains("RNGE") &&
                              Catch::Contains("compression ratio"));

  SECTION("a damaged material gets one error line naming the file") {
    const fs::path damaged = folder / "damaged.cbtf";
    fs::copy_file(material, damaged);
    fs::resize_file(damaged, fs::file_size(material) - 100);
    const Run r = run("info " + damaged.string());
    CHECK(r.status == 1);
    CHECK(line_count(r.output) == 1);
    CHECK_THAT(r.output, Catch::StartsWith("carbtf: error: ") && Catch::Contains(damaged.string()) &&
                             Catch::Contains("truncated"));
  }
  SECTION("carbtf synth gives the same bits on the Vulkan device and the CPU reference") {
    const std::string common =
        "synth " + material.string() + " --size 48 --seed 9 --light 30,45 --view 60,120 --out ";
    const Run gpu = run(common + (folder / "gpu").string() + " --validation");
    INFO(gpu.output);
    REQUIRE(gpu.status == 0);
    CHECK_THAT(gpu.output, Catch::Contains("of 8 subspace images") && Catch::Contains("interpolated.png"));
    const Run cpu = run(common + (folder / "cpu").string() + " --device cpu");
    INFO(cpu.output);
    REQUIRE(cpu.status == 0);
    std::size_t compared = 0;
    for (const auto& entry : fs::directory_iterator(folder / "gpu")) {
      if (entry.path().extension() != ".exr") continue;
      const fs::path twin = folder / "cpu" / entry.path().filename();
      REQUIRE(fs::exists(twin));
      // Pixels, not file bytes: OpenEXR stamps each file with its capture date.
      const RgbImage a = decode_rgb_image(entry.path().string(), read_file_bytes(entry.path()));
      const RgbImage b = decode_rgb_image(twin.string(), read_file_bytes(twin));
      CHECK(a.linear_rgb == b.linear_rgb);
      CHECK(a.linear_rgb.size() == 48u * 48u * 3u);
      ++compared;
    }
    CHECK(compared >= 2);  // at least one subspace image and the interpolated image
    CHECK(fs::exists(folder / "gpu" / "interpolated.exr"));

    const Run conform =
        run("conform " + material.string() + " --size 40 --large-size 96 --growth-sizes 32,64 --validation");
    INFO(conform.output);
    CHECK(conform.status == 0);
    CHECK_THAT(conform.output, Catch::Contains("near-unit-root") && Catch::Contains("HDR") &&
                                   Catch::Contains("interpolation") && Catch::Contains("all stages within"));

    const Run missing =
        run("synth " + material.string() + " --subspaces 8 --out " + (folder / "bad").string());
    CHECK(missing.status == 1);
    CHECK(line_count(missing.output) == 1);
    CHECK_THAT(missing.output, Catch::Contains("subspace 8 does not exist"));
  }
  SECTION("carbtf bench synth reports conformance and fidelity error against run time") {
    const fs::path out = folder / "bench";
    const Run bench = run("bench synth --material " + material.string() + " --btf " +
                          (folder / "leather" / "btf").string() +
                          " --sizes 32 --subspace-counts 3 --repeats 1 --validation --out " + out.string());
    INFO(bench.output);
    REQUIRE(bench.status == 0);
    for (const char* file :
         {"bench_synth.csv", "bench_synth.md", "bench_synth.png", "bench_synth_fidelity.png"})
      CHECK(fs::exists(out / file));
    const auto csv_bytes = read_file_bytes(out / "bench_synth.csv");
    std::string csv;
    for (const std::byte b : csv_bytes) csv.push_back(static_cast<char>(b));
    CHECK_THAT(csv, Catch::Contains("fidelity_pairs,rel_mean,rel_worst,gaussian_rel_mean"));
    // Each synthesized subspace image is scored against its representative pair; the size row
    // synthesizes 5, the subspace row 3, so both score a positive number of pairs.
    CHECK_THAT(bench.output, Catch::Contains("pairs: rel mean"));
    CHECK_THAT(bench.output, !Catch::Contains(" 0 pairs"));

    const Run mismatch =
        run("bench synth --material " + material.string() + " --btf " + (folder / "missing").string());
    CHECK(mismatch.status != 0);
    CHECK(line_count(mismatch.output) == 1);
  }
  SECTION("carbtf render draws the material on a mesh and refuses bad meshes with one line") {
    const fs::path frame = folder / "render" / "sphere.png";
    const Run r = run("render " + material.string() +
                      " --mesh sphere --size 96x64 --texture-size 32 --light 40,90 "
                      "--point-light 1,1,2,2 --validation --out " +
                      frame.string());
    INFO(r.output);
    REQUIRE(r.status == 0);
    CHECK_THAT(r.output, Catch::Contains("rendering 96x64") && Catch::Contains("wrote " + frame.string()));
    const RgbImage image = decode_rgb_image(frame.string(), read_file_bytes(frame));
    REQUIRE(image.srgb8.size() == 96u * 64u * 3u);
    // The sphere covers the centre, the clear colour the corner, and the two differ.
    const std::size_t centre = (32u * 96u + 48u) * 3u;
    CHECK(image.srgb8[centre] != image.srgb8[0]);
    // The same frame drawn otherwise: another picture of the same material.
    const auto drawn_otherwise = [&](const std::string& option, const std::string& name) {
      const fs::path other = folder / "render" / name;
      const Run r_other = run("render " + material.string() +
                              " --mesh sphere --size 96x64 --texture-size 32 --light 40,90 "
                              "--point-light 1,1,2,2 " +
                              option + " --validation --out " + other.string());
      INFO(r_other.output);
      REQUIRE(r_other.status == 0);
      const RgbImage other_image = decode_rgb_image(other.string(), read_file_bytes(other));
      REQUIRE(other_image.srgb8.size() == image.srgb8.size());
      CHECK(other_image.srgb8 != image.srgb8);
    };
    // --direction-taps 5: the staircase's pairs, another picture between the measured directions.
    drawn_otherwise("--direction-taps 5", "sphere_5.png");
    // --parallax-steps 0: offset mapping instead of the ray march, another picture of the same relief.
    drawn_otherwise("--parallax-steps 0", "sphere_offset_mapping.png");

    // Beside the measurement: the measured BTF drawn the same way on the same plane, view and light.
    const fs::path compare = folder / "render" / "plane.png";
    const Run beside =
        run("render " + material.string() + " --compare " + (folder / "leather" / "btf").string() +
            " --mesh plane --camera 35,200,2.6 --light 45,60 --size 64x48 --validation --out " +
            compare.string());
    INFO(beside.output);
    REQUIRE(beside.status == 0);
    CHECK_THAT(beside.output, Catch::Contains("rendering the measured BTF"));
    const RgbImage pair = decode_rgb_image((folder / "render" / "plane_compare.png").string(),
                                           read_file_bytes(folder / "render" / "plane_compare.png"));
    CHECK(pair.width == 128u);
    CHECK(fs::exists(folder / "render" / "plane_measured.png"));
    const Run no_dataset = run("render " + material.string() + " --compare " + (folder / "missing").string() +
                               " --out " + (folder / "bad.png").string());
    CHECK(no_dataset.status == 1);
    CHECK(line_count(no_dataset.output) == 1);

    const fs::path obj = folder / "no_uv.obj";
    {
      std::ofstream file(obj);
      file << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    }
    auto write_obj = [&](const std::string& name, const std::string& text) {
      std::ofstream(folder / name, std::ios::binary) << text;
      return (folder / name).string();
    };
    const std::string far_index = write_obj("far.obj", "v 0 0 0\nvt 0 0\nf 1/1 2/1 -9/1\n");
    const std::string not_a_number =
        write_obj("inf.obj", "v 1e999 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\n");
    const std::string empty = write_obj("empty.obj", "");
    const std::string garbage = write_obj("garbage.obj", std::string("\x7f\x45\x4c\x46\x02\x01\x00\xff", 8));
    for (const auto& [arguments, expected] : std::vector<std::pair<std::string, std::string>>{
             {"--mesh " + far_index, "does not exist"},
             {"--mesh " + not_a_number, "non-finite"},
             {"--mesh " + empty, "no faces"},
             {"--mesh " + garbage, "no faces"},
             {"--mesh " + obj.string(), "no texture coordinates"},
             {"--mesh " + (folder / "missing.obj").string(), "no such mesh file"},
             {"--mesh cube", "expected plane, sphere"},
             {"--size 12by5", "WIDTHxHEIGHT"}}) {
      const Run bad =
          run("render " + material.string() + " " + arguments + " --out " + (folder / "bad.png").string());
      INFO("carbtf render " << arguments << "\n" << bad.output);
      CHECK(bad.status == 1);
      CHECK(line_count(bad.output) == 1);
      CHECK_THAT(bad.output, Catch::StartsWith("carbtf: error: ") && Catch::Contains(expected));
    }
    CHECK_FALSE(fs::exists(folder / "bad.png"));
  }
  SECTION("carbtf bench frame reports synthesis and render times per frame") {
    const fs::path out = folder / "frames";
    const Run bench = run("bench frame --material " + material.string() +
                          " --frames 4 --width 64 --height 48 "
                          "--texture-size 32 --lights 2 --parts --validation --out " +
                          out.string());
    INFO(bench.output);
    REQUIRE(bench.status == 0);
    CHECK_THAT(bench.output, Catch::Contains("render pass, GPU timestamps | 4 |") &&
                                 Catch::Contains("synthesis, GPU timestamps (frames that synthesize)") &&
                                 Catch::Contains("sphere, 2 lights, on "));
    // --parts: the full pass and each part replaced, every one timed on the 4 frames.
    for (const char* part :
         {"none (the full pass)", "direction lookups", "pair table reads", "subspace image reads",
          "relief (normal, tone, horizons)", "parallax ray march",
          "offset mapping (1 height read) in the march's place", "9 direction taps (5 in their place)"}) {
      CHECK_THAT(bench.output, Catch::Contains(std::string("| ") + part + " | 4 |"));
    }
    const auto parts_bytes = read_file_bytes(out / "bench_frame_parts.csv");
    const std::string parts_csv(reinterpret_cast<const char*>(parts_bytes.data()), parts_bytes.size());
    CHECK(line_count(parts_csv) == 1 + 8 * 4);
    CHECK_THAT(parts_csv,
               Catch::Contains("\n\"relief (normal, tone, horizons)\",3,"));  // quoted: it holds commas
    CHECK(fs::exists(out / "bench_frame_parts.md"));
    const auto csv_bytes = read_file_bytes(out / "bench_frame.csv");
    std::string csv;
    for (const std::byte b : csv_bytes) csv.push_back(static_cast<char>(b));
    CHECK(line_count(csv) == 5);  // header + 4 frames
    CHECK(fs::exists(out / "bench_frame.md"));
    // Every subspace image is synthesized once, on the frame that first needs it.
    std::stringstream rows(csv);
    std::string row;
    std::getline(rows, row);
    std::size_t synthesized = 0, resident = 0;
    while (std::getline(rows, row)) {
      std::stringstream fields(row);
      std::string frame, added, now;
      std::getline(fields, frame, ',');
      std::getline(fields, added, ',');
      std::getline(fields, now, ',');
      synthesized += std::stoul(added);
      CHECK(std::stoul(now) == synthesized);
      resident = std::stoul(now);
    }
    CHECK(resident > 0);
  }
  SECTION("tone weights: each subspace's share of the relief tone, stored and shown by info") {
    // The analysis gives every subspace the whole tone; a material file may hold other shares (TWGT).
    Material whole;
    REQUIRE(read_material_file(material.string(), whole).ok());
    CHECK_THAT(run("info " + material.string()).output,
               Catch::Contains("taken whole by") && !Catch::Contains("TWGT"));
    Material none = whole;
    for (SubspaceModel& s : none.subspaces) s.tone_weight = 0.0f;
    const fs::path none_path = folder / "tone_none.cbtf";
    REQUIRE(write_material_file(none_path.string(), none).ok());
    const Run info_none = run("info " + none_path.string());
    CHECK_THAT(info_none.output, Catch::Contains("relief tone:  taken whole by 0 subspaces, by none " +
                                                 std::to_string(none.subspaces.size())) &&
                                     Catch::Contains("TWGT"));
  }
  SECTION("range-tile edge colours: more colours, more tiles from more patches, shown by info") {
    const fs::path three = folder / "edge_colours_3.cbtf";
    const Run analyze_three = run("analyze " + (folder / "leather" / "btf").string() +
                                  " --subspaces 8 --levels 2 --edge-colours 3 --out " + three.string());
    INFO(analyze_three.output);
    REQUIRE(analyze_three.status == 0);
    CHECK_THAT(run("info " + three.string()).output,
               Catch::Contains("81 tiles of") && Catch::Contains("from 6 patches"));
    CHECK_THAT(run("info " + material.string()).output,
               Catch::Contains("16 tiles of") && Catch::Contains("from 4 patches"));
  }
  SECTION("bad analysis arguments") {
    for (const auto& [arguments, expected] : std::vector<std::pair<std::string, std::string>>{
             {"analyze " + (folder / "leather" / "btf").string() + " --out x.cbtf --edge-colours 5",
              "--edge-colours"},
             {"analyze " + (folder / "leather" / "btf").string() + " --out x.cbtf --subspaces 21",
              "--subspaces"},
             {"analyze " + (folder / "leather" / "btf").string() + " --out x.cbtf --levels 7", "--levels"},
             {"analyze " + (folder / "leather" / "btf").string() + " --out x.cbtf --deshade 0.3",
              "--deshade"},
             {"analyze " + (folder / "leather" / "btf").string() + " --out x.cbtf --tone-planes yes",
              "--tone-planes"},
             {"analyze " + (folder / "missing").string() + " --out " + (folder / "x.cbtf").string(),
              "no such file or folder"}}) {
      const Run r = run(arguments);
      INFO("carbtf " << arguments << "\n" << r.output);
      CHECK(r.status != 0);
      CHECK(line_count(r.output) == 1);
      CHECK_THAT(r.output, Catch::StartsWith("carbtf: error: ") && Catch::Contains(expected));
    }
    CHECK_FALSE(fs::exists(folder / "x.cbtf"));
  }
}

TEST_CASE("carbtf normals estimates a sample's normals and compares them with its ground truth", "[cli]") {
  const fs::path folder = scratch_folder("normals");
  REQUIRE(run("sample fabric --size 32 --format png --out " + (folder / "fabric").string()).status == 0);
  const Run r =
      run("normals " + (folder / "fabric" / "btf").string() + " --out " + (folder / "out").string() +
          " --truth " + (folder / "fabric" / "ground_truth" / "normals.exr").string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("mean") && Catch::Contains("median"));
  for (const char* file : {"normals.png", "normals.exr", "albedo.png", "range_map.exr", "range_map.png"})
    CHECK(fs::exists(folder / "out" / file));
  fs::remove_all(folder);
}
