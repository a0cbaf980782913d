// Bad input from outside (a file, a folder, an archive): one message naming the input and the problem.
// analysis/ throws it; the CLI prints it as one line and exits non-zero.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

namespace carbtf {

class InputError : public std::runtime_error {
 public:
  InputError(const std::string& input, const std::string& problem) : std::runtime_error(input + ": " + problem) {}
  InputError(const std::filesystem::path& input, const std::string& problem) : InputError(input.string(), problem) {}
};

}  // namespace carbtf
