#include "carbtf/engine/file_output.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

namespace carbtf {

namespace {

namespace fs = std::filesystem;

Status file_error(const std::string& path, const std::string& problem) {
  return {ErrorCode::file_error, path + ": " + problem};
}

std::string system_reason(int error) {
  return std::strerror(error);
}

const char* kind_of(const struct stat& info) {
  if (S_ISDIR(info.st_mode)) return "is a folder, not a file";
  if (S_ISCHR(info.st_mode)) return "is a character device";
  if (S_ISBLK(info.st_mode)) return "is a block device";
  if (S_ISFIFO(info.st_mode)) return "is a FIFO (named pipe)";
  if (S_ISSOCK(info.st_mode)) return "is a socket";
  return "is not a regular file";
}

// Where the bytes go: `path` itself, or the regular file a symbolic link at `path` leads to, so that
// the link survives the rename; and the mode of the file there, if any.
struct Target {
  std::string path;
  bool exists = false;
  mode_t mode = 0;
};

// Fails for anything at `path` that is not a regular file or nothing.
Status resolve_target(const std::string& path, Target& target) {
  if (path.empty()) return {ErrorCode::file_error, "the output path is empty"};
  target = {path, false, 0};
  struct stat link_info {};
  if (::lstat(path.c_str(), &link_info) != 0) {
    if (errno == ENOENT) return {};
    return file_error(path, "cannot be checked (" + system_reason(errno) + ")");
  }
  struct stat info = link_info;
  if (S_ISLNK(link_info.st_mode)) {
    if (::stat(path.c_str(), &info) != 0)
      return file_error(path, "is a symbolic link to nothing; this command does not follow it");
    std::error_code error;
    target.path = fs::canonical(path, error).string();
    if (error)
      return file_error(path, "is a symbolic link that cannot be resolved (" + error.message() + ")");
  }
  if (!S_ISREG(info.st_mode)) {
    return file_error(
        path, std::string(kind_of(info)) + "; carbtf writes only regular files and does not replace it");
  }
  target.exists = true;
  target.mode = info.st_mode & 07777;
  return {};
}

Status write_all(int fd, const std::uint8_t* data, std::size_t size) {
  while (size > 0) {
    const ssize_t written = ::write(fd, data, size);
    if (written < 0) {
      if (errno == EINTR) continue;
      return {ErrorCode::file_error, system_reason(errno)};
    }
    if (written == 0) return {ErrorCode::file_error, "the system wrote nothing"};
    data += written;
    size -= static_cast<std::size_t>(written);
  }
  return {};
}

// A new, empty file in `folder` that no one else has: O_EXCL makes a name already taken (a user's own
// "x.partial" among them) fail instead of being truncated.
int create_temporary(const fs::path& target, std::string& name) {
  static std::atomic<unsigned> counter{0};
  for (int attempt = 0; attempt < 100; ++attempt) {
    std::string file_name = ".";
    file_name += target.filename().string();
    file_name += '.';
    file_name += std::to_string(::getpid());
    file_name += '-';
    file_name += std::to_string(counter++);
    file_name += ".partial";
    name = (target.parent_path() / file_name).string();
    const int fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0 || errno != EEXIST) return fd;
  }
  errno = EEXIST;
  return -1;
}

}  // namespace

Status check_output_file(const std::string& path) {
  Target target;
  return resolve_target(path, target);
}

Status write_file_whole(const std::string& path, std::span<const std::uint8_t> bytes, Flush flush) {
  Target target;
  if (Status s = resolve_target(path, target); !s.ok()) return s;
  std::string temporary;
  const int fd = create_temporary(fs::path(target.path), temporary);
  if (fd < 0) return file_error(path, "cannot create the file (" + system_reason(errno) + ")");
  Status written = write_all(fd, bytes.data(), bytes.size());
  if (written.ok() && target.exists && ::fchmod(fd, target.mode) != 0)
    written = {ErrorCode::file_error, system_reason(errno)};
  if (written.ok() && flush == Flush::each_file && ::fsync(fd) != 0)
    written = {ErrorCode::file_error, system_reason(errno)};
  if (::close(fd) != 0 && written.ok()) written = {ErrorCode::file_error, system_reason(errno)};
  if (written.ok()) {
    // The target may have changed since it was checked; a device put there meanwhile is still kept.
    if (Status again = resolve_target(path, target); !again.ok()) {
      ::unlink(temporary.c_str());
      return again;
    }
    if (::rename(temporary.c_str(), target.path.c_str()) != 0)
      written = {ErrorCode::file_error, system_reason(errno)};
  }
  if (!written.ok()) {
    ::unlink(temporary.c_str());
    return file_error(path, "cannot write the file (" + written.message() + "); nothing was written");
  }
  return {};
}

Status write_file_whole(const std::string& path, std::string_view text, Flush flush) {
  return write_file_whole(
      path, std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()),
      flush);
}

Status flush_file_system(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return file_error(path, "cannot be opened to flush it (" + system_reason(errno) + ")");
  const int result = ::syncfs(fd);
  const int error = errno;
  ::close(fd);
  if (result != 0)
    return file_error(path, "the disk reported an error writing it (" + system_reason(error) + ")");
  return {};
}

}  // namespace carbtf
