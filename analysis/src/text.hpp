// Internal: small text helpers shared by the readers.
#pragma once

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

namespace carbtf::detail {

inline std::string to_lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

inline std::string lower_extension(const std::filesystem::path& path) {
  return to_lower(path.extension().string());
}

}  // namespace carbtf::detail
