// Files written whole or not at all, and never in place of what is not a regular file.
#include <catch2/catch.hpp>

#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "carbtf/engine/file_output.hpp"
#include "scratch_folder.hpp"

namespace fs = std::filesystem;
using namespace carbtf;

namespace {

std::string read_text(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

std::size_t entries_in(const fs::path& folder) {
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(folder), fs::directory_iterator()));
}

// The file-size limit lowered for one scope, with SIGXFSZ ignored so that a write past it fails with
// EFBIG instead of ending the process: a write that fails, without a full disk.
struct FileSizeLimit {
  rlimit saved{};
  void (*saved_handler)(int) = nullptr;
  explicit FileSizeLimit(rlim_t bytes) {
    REQUIRE(getrlimit(RLIMIT_FSIZE, &saved) == 0);
    saved_handler = std::signal(SIGXFSZ, SIG_IGN);
    rlimit lowered = saved;
    lowered.rlim_cur = bytes;
    REQUIRE(setrlimit(RLIMIT_FSIZE, &lowered) == 0);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &saved);
    std::signal(SIGXFSZ, saved_handler);
  }
};

}  // namespace

TEST_CASE("write_file_whole writes a new file and replaces a regular one, keeping its mode",
          "[material_file][file_output]") {
  const fs::path folder = test::scratch_folder("file_output_regular");
  const fs::path path = folder / "a.txt";
  REQUIRE(check_output_file(path.string()).ok());
  REQUIRE(write_file_whole(path.string(), std::string_view("first")).ok());
  CHECK(read_text(path) == "first");
  fs::permissions(path, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  REQUIRE(write_file_whole(path.string(), std::string_view("second, longer")).ok());
  CHECK(read_text(path) == "second, longer");
  CHECK(fs::status(path).permissions() ==
        (fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read));
  CHECK(entries_in(folder) == 1);  // no temporary left beside it

  SECTION("a file of the user's named like a temporary is not touched") {
    write_text(folder / "a.txt.partial", "the user's");
    REQUIRE(write_file_whole(path.string(), std::string_view("third")).ok());
    CHECK(read_text(folder / "a.txt.partial") == "the user's");
    CHECK(read_text(path) == "third");
  }
  SECTION("through a symbolic link the target is written and the link kept") {
    fs::create_symlink(path, folder / "link.txt");
    REQUIRE(write_file_whole((folder / "link.txt").string(), std::string_view("via link")).ok());
    CHECK(fs::is_symlink(fs::symlink_status(folder / "link.txt")));
    CHECK(read_text(path) == "via link");
  }
  fs::remove_all(folder);
}

TEST_CASE("write_file_whole refuses folders, FIFOs, devices and dangling links and replaces none",
          "[material_file][file_output]") {
  const fs::path folder = test::scratch_folder("file_output_special");
  const auto refused = [](const fs::path& path, const std::string& expected) {
    const Status checked = check_output_file(path.string());
    const Status written = write_file_whole(path.string(), std::string_view("x"));
    INFO(path << ": " << written.message());
    CHECK_FALSE(checked.ok());
    CHECK_FALSE(written.ok());
    CHECK(written.code() == ErrorCode::file_error);
    CHECK_THAT(written.message(), Catch::StartsWith(path.string() + ": ") && Catch::Contains(expected));
  };
  fs::create_directories(folder / "sub");
  refused(folder / "sub", "is a folder");
  CHECK(fs::is_directory(folder / "sub"));

  REQUIRE(mkfifo((folder / "fifo").c_str(), 0600) == 0);
  refused(folder / "fifo", "FIFO");
  CHECK(fs::is_fifo(folder / "fifo"));

  fs::create_symlink(folder / "nothing", folder / "dangling");
  refused(folder / "dangling", "symbolic link to nothing");
  CHECK_FALSE(fs::exists(folder / "nothing"));

  refused("/dev/null", "character device");
  if (geteuid() == 0) {
    // As root (as the README's commands run) a rename would replace the device node itself.
    REQUIRE(mknod((folder / "full").c_str(), S_IFCHR | 0600, makedev(1, 7)) == 0);
    refused(folder / "full", "character device");
    CHECK(fs::is_character_file(folder / "full"));
  } else {
    WARN("not root: the device node made for this test is skipped (/dev/null was checked)");
  }
  CHECK(entries_in(folder) == (geteuid() == 0 ? 4u : 3u));  // sub, fifo, dangling (and full): nothing added
  fs::remove_all(folder);
}

TEST_CASE("a write that fails leaves the old file and no temporary", "[material_file][file_output]") {
  const fs::path folder = test::scratch_folder("file_output_failing");
  const fs::path path = folder / "m.cbtf";
  write_text(path, "the old material");
  const std::vector<std::uint8_t> large(1 << 20, 0x5a);
  Status s;
  {
    const FileSizeLimit limit(64 * 1024);
    s = write_file_whole(path.string(), large);
  }
  INFO(s.message());
  CHECK_FALSE(s.ok());
  CHECK(s.code() == ErrorCode::file_error);
  CHECK_THAT(s.message(), Catch::Contains(path.string()) && Catch::Contains("nothing was written"));
  CHECK(read_text(path) == "the old material");
  CHECK(entries_in(folder) == 1);

  SECTION("a folder that does not exist is an error naming the path") {
    const Status missing = write_file_whole((folder / "no" / "x").string(), std::string_view("x"));
    CHECK_FALSE(missing.ok());
    CHECK_THAT(missing.message(),
               Catch::Contains((folder / "no" / "x").string()) && Catch::Contains("cannot create"));
  }
  fs::remove_all(folder);
}
