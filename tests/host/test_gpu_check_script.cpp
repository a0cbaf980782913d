// scripts/gpu_check.sh, the one run a machine with a real GPU makes, at the small sizes lavapipe runs:
// every step succeeds with the validation layer on, and the report holds each step's figures.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "cli_run.hpp"
#include "scratch_folder.hpp"

namespace carbtf {
namespace {

namespace fs = std::filesystem;

// The script with `arguments`, on the carbtf these tests were built with; `environment` goes first.
test::Run run_script(const std::string& arguments, const std::string& environment = "") {
  return test::run_shell(environment + " \"" CARBTF_GPU_CHECK_SCRIPT "\" --carbtf \"" CARBTF_CLI_PATH "\" " +
                         arguments);
}

std::string text_of(const fs::path& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

}  // namespace

TEST_CASE("scripts/gpu_check.sh runs every check at lavapipe sizes and writes one report",
          "[cli][gpu_check][slow]") {
  const fs::path folder = test::scratch_folder("gpu_check");
  const fs::path report = folder / "report" / "gpu_check.md";
  const test::Run r =
      run_script("--small --validation --out " + report.string() + " --work " + (folder / "work").string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("(0 failed steps)"));
  const std::string markdown = text_of(report);
  INFO(markdown);
  for (const char* section :
       {"## devices", "## analysis", "## conform, every extreme case", "## bench synth, serial scheme",
        "## bench synth, wavefront scheme", "## bench frame, 160x90", "## bench frame, 320x180",
        "## bench frame, 160x90, filtered by hand", "## summary"}) {
    CHECK_THAT(markdown, Catch::Contains(section));
  }
  CHECK_THAT(markdown, Catch::Contains("all stages within"));            // conform's verdict
  CHECK_THAT(markdown, Catch::Contains("wavefront"));                    // bench synth's rows
  CHECK_THAT(markdown, Catch::Contains("render pass, GPU timestamps"));  // bench frame's table
  CHECK_THAT(markdown, Catch::Contains("| direction lookups | 3 |"));    // its --parts table, first size
  CHECK_THAT(markdown, Catch::Contains("filtered by hand") && Catch::Contains("filtered by the sampler"));
  CHECK_THAT(markdown, Catch::Contains("0 failed steps"));
  CHECK_FALSE(markdown.find("FAILED") != std::string::npos);
  fs::remove_all(folder);
}

TEST_CASE("scripts/gpu_check.sh reports a failed step and exits non-zero", "[cli][gpu_check][slow]") {
  const fs::path folder = test::scratch_folder("gpu_check_failing");
  SECTION("a carbtf that is not there") {
    const test::Run r = test::run_shell(
        "\"" CARBTF_GPU_CHECK_SCRIPT "\" --carbtf /nonexistent/carbtf --out " + (folder / "r.md").string());
    CHECK(r.status == 2);
    CHECK_THAT(r.output, Catch::Contains("/nonexistent/carbtf is not an executable carbtf"));
  }
  SECTION("a device that is not there: the device steps fail, the others still run") {
    const fs::path report = folder / "r.md";
    const test::Run r =
        run_script("--small --out " + report.string() + " --work " + (folder / "work").string(),
                   "CARBTF_DEVICE=no-such-device");
    INFO(r.output);
    CHECK(r.status == 1);
    const std::string markdown = text_of(report);
    CHECK_THAT(markdown,
               Catch::Contains("## conform, every extreme case") && Catch::Contains("**FAILED (exit"));
    CHECK_THAT(markdown, Catch::Contains("## bench frame, 320x180") && Catch::Contains("## summary"));
    CHECK_THAT(markdown, !Catch::Contains(" 0 failed steps"));
  }
  fs::remove_all(folder);
}

}  // namespace carbtf
