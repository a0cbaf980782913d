#include "carbtf/analysis/btf/ubo2003_names.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "../text.hpp"
#include "carbtf/analysis/btf/directions.hpp"

namespace carbtf {

namespace {

// Reads exactly `digits` decimal digits at `text[at]`, advancing `at`.
bool read_digits(std::string_view text, std::size_t& at, std::size_t digits, int& value) {
  if (at + digits > text.size()) return false;
  value = 0;
  for (std::size_t i = 0; i < digits; ++i) {
    const char c = text[at + i];
    if (c < '0' || c > '9') return false;
    value = value * 10 + (c - '0');
  }
  at += digits;
  return true;
}

bool read_literal(std::string_view text, std::size_t& at, std::string_view literal) {
  if (text.substr(at, literal.size()) != literal) return false;
  at += literal.size();
  return true;
}

int rounded_degrees(double degrees) {
  return static_cast<int>(std::lround(degrees)) % 360;
}

}  // namespace

std::optional<Ubo2003Name> parse_ubo2003_name(std::string_view file_name) {
  Ubo2003Name name;
  std::size_t at = 0;
  int index = 0;
  if (!read_digits(file_name, at, 5, index)) return std::nullopt;
  name.index = static_cast<std::uint32_t>(index);
  if (!read_literal(file_name, at, " tl") || !read_digits(file_name, at, 3, name.theta_light))
    return std::nullopt;
  if (!read_literal(file_name, at, " pl") || !read_digits(file_name, at, 3, name.phi_light))
    return std::nullopt;
  if (!read_literal(file_name, at, " tv") || !read_digits(file_name, at, 3, name.theta_view))
    return std::nullopt;
  if (!read_literal(file_name, at, " pv") || !read_digits(file_name, at, 3, name.phi_view))
    return std::nullopt;
  const std::string extension = detail::to_lower(std::string(file_name.substr(at)));
  if (extension.size() < 2 || extension[0] != '.') return std::nullopt;
  name.extension = extension;
  return name;
}

bool parse_ubo2003_view_folder(std::string_view folder_name, int& theta, int& phi) {
  std::size_t at = 0;
  return read_literal(folder_name, at, "tv") && read_digits(folder_name, at, 3, theta) &&
         read_literal(folder_name, at, "_pv") && read_digits(folder_name, at, 3, phi) &&
         at == folder_name.size();
}

std::string ubo2003_file_name(std::uint32_t light_index, std::uint32_t view_index,
                              std::string_view extension) {
  const auto& d = ubo2003_directions();
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%05u tl%03d pl%03d tv%03d pv%03d", light_index * 81 + view_index,
                rounded_degrees(d[light_index].theta_degrees()),
                rounded_degrees(d[light_index].phi_degrees()), rounded_degrees(d[view_index].theta_degrees()),
                rounded_degrees(d[view_index].phi_degrees()));
  return std::string(buffer) + std::string(extension);
}

std::string ubo2003_view_folder(std::uint32_t view_index) {
  const auto& d = ubo2003_directions();
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "tv%03d_pv%03d", rounded_degrees(d[view_index].theta_degrees()),
                rounded_degrees(d[view_index].phi_degrees()));
  return buffer;
}

}  // namespace carbtf
