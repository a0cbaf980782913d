// Bad input from outside (a file, a folder, an archive): one message naming the input and the problem.
// analysis/ throws it; the CLI prints it as one line and exits non-zero.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

namespace carbtf {

class InputError : public std::runtime_error {
 public:
  InputError(const std::string& input, const std::string& problem)
      : std::runtime_error(printable(input) + ": " + problem) {}
  InputError(const std::filesystem::path& input, const std::string& problem)
      : InputError(input.string(), problem) {}

 private:
  // A name from a hostile file may hold control bytes: a NUL would end the message there, and others
  // would reach the terminal. Each becomes '?', so the message stays one readable line.
  static std::string printable(std::string name) {
    for (char& c : name) {
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    }
    return name;
  }
};

}  // namespace carbtf
