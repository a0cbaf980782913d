// Internal to the binary readers: a file read field by field, where every read is checked against the
// file's length first, so that a size a hostile header declares is refused before anything is
// allocated for it, and every error names the file, the field and the offset.
#pragma once

#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <type_traits>

#include "carbtf/analysis/input_error.hpp"

namespace carbtf::detail {

static_assert(std::endian::native == std::endian::little, "the binary readers assume a little-endian host");

class BoundedFile {
 public:
  explicit BoundedFile(const std::filesystem::path& path) : path_(path) {
    // Checked before opening: opening a FIFO would wait for a writer.
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path, "is not a regular file");
    size_ = std::filesystem::file_size(path, ec);
    stream_.open(path, std::ios::binary);
    if (!stream_ || ec) throw InputError(path, "cannot be opened for reading");
  }

  const std::filesystem::path& path() const { return path_; }
  std::uint64_t size() const { return size_; }
  std::uint64_t position() const { return position_; }
  std::uint64_t remaining() const { return size_ - position_; }

  [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
    throw InputError(path_, field + ": " + problem);
  }

  // Throws unless `bytes` more bytes are in the file (`bytes` may be the product of declared counts).
  void require(std::uint64_t bytes, const std::string& field) const {
    if (bytes > remaining()) {
      fail(field, "needs " + std::to_string(bytes) + " bytes at offset " + std::to_string(position_) +
                      " but the file ends after " + std::to_string(remaining()) +
                      " more (truncated or corrupt)");
    }
  }

  void read(void* out, std::uint64_t bytes, const std::string& field) {
    require(bytes, field);
    if (bytes == 0) return;
    if (!stream_.read(static_cast<char*>(out), static_cast<std::streamsize>(bytes)))
      fail(field, "read error");
    position_ += bytes;
  }

  template <class T>
  T value(const std::string& field) {
    static_assert(std::is_trivially_copyable_v<T>);
    T v;
    read(&v, sizeof v, field);
    return v;
  }

  void skip(std::uint64_t bytes, const std::string& field) {
    require(bytes, field);
    stream_.seekg(static_cast<std::streamoff>(bytes), std::ios::cur);
    if (!stream_) fail(field, "seek error");
    position_ += bytes;
  }

 private:
  std::filesystem::path path_;
  std::ifstream stream_;
  std::uint64_t size_ = 0;
  std::uint64_t position_ = 0;
};

}  // namespace carbtf::detail
