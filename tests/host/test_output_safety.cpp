// What a command writes: never in place of a device, FIFO or folder, never half a file, and nothing
// left behind when the write fails. Run as root, as the README's commands are, a rename over
// `--out /dev/full` would replace the device itself.
#include <catch2/catch.hpp>

#include <sys/mount.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "cli_run.hpp"
#include "scratch_folder.hpp"

namespace fs = std::filesystem;
using carbtf::test::check_refused;
using carbtf::test::run;
using carbtf::test::Run;
using carbtf::test::run_shell;

namespace {

std::size_t entries_in(const fs::path& folder) {
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(folder), fs::directory_iterator()));
}

// A 16^2 leather BTF, made once per process: enough for analyze to reach the write of a 15 KiB material.
struct SmallSample {
  fs::path folder = carbtf::test::scratch_folder("output_safety_sample");
  fs::path btf = folder / "leather" / "btf";
  Run sample = run("sample leather --size 16 --out " + (folder / "leather").string());
  ~SmallSample() {
    std::error_code ignored;
    fs::remove_all(folder, ignored);
  }
};

const SmallSample& small_sample() {
  static const SmallSample sample;
  REQUIRE(sample.sample.status == 0);
  return sample;
}

}  // namespace

TEST_CASE(
    "an output path that is a FIFO, a device or a folder is refused before any work and replaces nothing",
    "[cli][hostile][output]") {
  const SmallSample& sample = small_sample();
  const fs::path folder = carbtf::test::scratch_folder("output_safety_nodes");
  const fs::path fifo = folder / "m.cbtf";
  REQUIRE(mkfifo(fifo.c_str(), 0600) == 0);
  // timeout: a writer that opened the FIFO would wait for a reader forever.
  check_refused(run("analyze " + sample.btf.string() + " --out " + fifo.string(), "timeout 60"),
                fifo.string() + ": is a FIFO");
  REQUIRE(mkfifo((folder / "n.png").c_str(), 0600) == 0);
  check_refused(run("noise --size 16 --out " + (folder / "n.png").string(), "timeout 60"), "is a FIFO");
  CHECK(fs::is_fifo(fifo));
  CHECK(fs::is_fifo(folder / "n.png"));

  fs::create_directories(folder / "dir.cbtf");
  check_refused(run("analyze " + sample.btf.string() + " --out " + (folder / "dir.cbtf").string()),
                "is a folder");
  CHECK(fs::is_directory(folder / "dir.cbtf"));

  if (geteuid() == 0) {
    // A device node of /dev/full's numbers, made for the test: root may rename over it.
    const fs::path device = folder / "full";
    REQUIRE(mknod(device.c_str(), S_IFCHR | 0600, makedev(1, 7)) == 0);
    check_refused(run("analyze " + sample.btf.string() + " --out " + device.string()),
                  device.string() + ": is a character device");
    REQUIRE(mknod((device.string() + ".png").c_str(), S_IFCHR | 0600, makedev(1, 7)) == 0);
    check_refused(run("noise --size 16 --out " + device.string() + ".png"), "is a character device");
    CHECK(fs::is_character_file(device));
    CHECK(fs::is_character_file(device.string() + ".png"));
  } else {
    WARN("not root: the device-node case is skipped");
  }
  fs::remove_all(folder);
}

TEST_CASE("a material write that fails is one error, with no partial file and no temporary left",
          "[cli][hostile][output][slow]") {
  const SmallSample& sample = small_sample();
  const fs::path folder = carbtf::test::scratch_folder("output_safety_full");
  const fs::path out = folder / "m.cbtf";

  SECTION("past the file-size limit (a write fails with EFBIG)") {
    // 4 KiB of the 15 KiB the material needs.
    const Run r = run_shell("ulimit -f 4; \"" CARBTF_CLI_PATH "\" analyze " + sample.btf.string() +
                            " --out " + out.string());
    INFO(r.output);
    CHECK(r.status == 1);
    CHECK_THAT(r.output, Catch::Contains("carbtf: error: cannot write the material: " + out.string()) &&
                             Catch::Contains("nothing was written"));
    CHECK(entries_in(folder) == 0);
  }
  SECTION("on a full file system (a tmpfs of 4 KiB)") {
    const fs::path mount_point = folder / "small";
    fs::create_directories(mount_point);
    if (geteuid() != 0 || mount("tmpfs", mount_point.c_str(), "tmpfs", 0, "size=4k") != 0) {
      WARN(
          "cannot mount a tmpfs here (needs root): the full-disk case is skipped, the file-size limit covers "
          "the write path");
      return;
    }
    const Run r = run("analyze " + sample.btf.string() + " --out " + (mount_point / "m.cbtf").string());
    const std::size_t left = entries_in(mount_point);
    umount(mount_point.c_str());
    INFO(r.output);
    CHECK(r.status == 1);
    CHECK_THAT(r.output,
               Catch::Contains("No space left on device") && Catch::Contains("nothing was written"));
    CHECK(left == 0);
  }
  fs::remove_all(folder);
}

TEST_CASE("a zip whose member CRC-32 is wrong is refused by info and analyze, naming the member",
          "[cli][hostile][output]") {
  const fs::path folder = carbtf::test::scratch_folder("output_safety_zip");
  REQUIRE(run("sample leather --size 16 --zip --out " + (folder / "s").string()).status == 0);
  std::ifstream in(folder / "s" / "btf.zip", std::ios::binary);
  std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  // The first member's CRC in its local header (offset 14) and in its central-directory entry (16).
  const std::size_t local = bytes.find(std::string("PK\x03\x04", 4));
  const std::size_t central = bytes.find(std::string("PK\x01\x02", 4));
  REQUIRE(local != std::string::npos);
  REQUIRE(central != std::string::npos);
  const std::string member =
      bytes.substr(central + 46, static_cast<unsigned char>(bytes[central + 28]) |
                                     static_cast<unsigned char>(bytes[central + 29]) << 8);
  bytes[local + 14] ^= 0x01;
  bytes[central + 16] ^= 0x01;
  const fs::path bad = folder / "crcbad.zip";
  std::ofstream(bad, std::ios::binary) << bytes;
  for (const std::string& command :
       {"info " + bad.string(), "analyze " + bad.string() + " --out " + (folder / "m.cbtf").string()}) {
    check_refused(run(command), bad.string() + ":" + member + ": CRC-32 mismatch");
  }
  CHECK_FALSE(fs::exists(folder / "m.cbtf"));
  fs::remove_all(folder);
}

TEST_CASE("a manifest of 10,000 distinct directions is refused at once, in bounded memory",
          "[cli][hostile][output]") {
  const fs::path folder = carbtf::test::scratch_folder("output_safety_manifest");
  std::ostringstream rows;
  for (int i = 0; i < 10000; ++i)
    rows << "a.png," << 0.008 * i << "," << 0.03 * i << "," << 0.008 * i << "," << 0.05 * i << "\n";
  std::ofstream(folder / "many.csv") << rows.str();
  // 1 GiB of address space at most (it built a 3.7 GB table before), and a guard against a hang.
  const Run r = run_shell("ulimit -v 1048576; timeout 60 \"" CARBTF_CLI_PATH "\" analyze " +
                          (folder / "many.csv").string() + " --out " + (folder / "m.cbtf").string());
  check_refused(r, "many.csv: has more than 1024 distinct light directions; carbtf reads at most 1024");
  CHECK_FALSE(fs::exists(folder / "m.cbtf"));
  fs::remove_all(folder);
}
