// Little-endian byte encoding for the material file. ByteReader never reads past its span: a read that
// would overrun sets the failed flag and yields zeros, so a parser checks once per record instead of
// per field, and hostile sizes cannot cause out-of-bounds access.
#pragma once

#include <bit>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

namespace carbtf::detail {

class ByteWriter {
 public:
  explicit ByteWriter(std::vector<std::uint8_t>& out) : out_(out) {}
  void u8(std::uint8_t v) { out_.push_back(v); }
  void i8(std::int8_t v) { out_.push_back(static_cast<std::uint8_t>(v)); }
  void u16(std::uint16_t v) {
    for (int i = 0; i < 2; ++i) out_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  void u32(std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  void f32(float v) { u32(std::bit_cast<std::uint32_t>(v)); }
  // push_back, not insert: GCC 12 warns falsely (-Warray-bounds) on inserting a small span.
  void bytes(std::span<const std::uint8_t> b) {
    for (std::uint8_t v : b) out_.push_back(v);
  }
  void text(const std::string& s) {
    u32(static_cast<std::uint32_t>(s.size()));
    for (char c : s) out_.push_back(static_cast<std::uint8_t>(c));
  }
  std::size_t size() const { return out_.size(); }
  // Overwrites a u32 written earlier (chunk sizes are known only after the payload).
  void patch_u32(std::size_t at, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out_[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
  }

 private:
  std::vector<std::uint8_t>& out_;
};

class ByteReader {
 public:
  explicit ByteReader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}

  bool failed() const { return failed_; }
  std::size_t remaining() const { return bytes_.size() - position_; }
  bool at_end() const { return position_ == bytes_.size(); }

  std::uint8_t u8() { return static_cast<std::uint8_t>(little_endian(1)); }
  std::int8_t i8() { return static_cast<std::int8_t>(u8()); }
  std::uint16_t u16() { return static_cast<std::uint16_t>(little_endian(2)); }
  std::uint32_t u32() { return static_cast<std::uint32_t>(little_endian(4)); }
  float f32() { return std::bit_cast<float>(u32()); }

  // A span of `count` bytes, or an empty span (and failure) if fewer remain.
  std::span<const std::uint8_t> bytes(std::size_t count) {
    if (!take(count)) return {};
    return bytes_.subspan(position_ - count, count);
  }
  // A length-prefixed string of at most `max_length` bytes.
  std::string text(std::size_t max_length) {
    const std::uint32_t length = u32();
    if (length > max_length) {
      failed_ = true;
      return {};
    }
    const auto b = bytes(length);
    return std::string(b.begin(), b.end());
  }
  // True if `count` elements of `element_bytes` each could still be read: checked before allocating.
  bool can_read(std::size_t count, std::size_t element_bytes) const {
    return !failed_ && element_bytes != 0 && count <= remaining() / element_bytes;
  }

 private:
  bool take(std::size_t count) {
    if (failed_ || count > remaining()) {
      failed_ = true;
      return false;
    }
    position_ += count;
    return true;
  }
  std::uint64_t little_endian(std::size_t count) {
    if (!take(count)) return 0;
    std::uint64_t v = 0;
    for (std::size_t i = 0; i < count; ++i) v |= std::uint64_t{bytes_[position_ - count + i]} << (8 * i);
    return v;
  }

  std::span<const std::uint8_t> bytes_;
  std::size_t position_ = 0;
  bool failed_ = false;
};

}  // namespace carbtf::detail
