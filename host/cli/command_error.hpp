// Thrown by a command to stop with one line on stderr and a non-zero exit status (main.cpp). On its
// own so that code a fuzz target builds (the OBJ loader, tests/fuzz) needs neither CLI11 nor the rest
// of the CLI's helpers.
#pragma once

#include <stdexcept>

namespace carbtf::cli {

class CommandError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace carbtf::cli
