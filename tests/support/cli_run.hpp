// Running the carbtf command line from a test as a user would: exit status and everything it printed.
#pragma once

#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace carbtf::test {

struct Run {
  int status = -1;
  std::string output;  // stdout and stderr together
};

// A shell command line, its stderr joined to its stdout.
inline Run run_shell(const std::string& command_line) {
  const std::string command = command_line + " 2>&1";
  Run result;
  FILE* pipe = popen(command.c_str(), "r");
  REQUIRE(pipe != nullptr);
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe)) result.output += buffer.data();
  const int raw = pclose(pipe);
  result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
  return result;
}

#ifdef CARBTF_CLI_PATH
// carbtf with `arguments`; `environment` is put before it: variables, or a wrapper such as "timeout 30".
inline Run run(const std::string& arguments, const std::string& environment = "") {
  return run_shell(environment + " \"" CARBTF_CLI_PATH "\" " + arguments);
}
#endif

inline std::size_t line_count(const std::string& text) {
  std::size_t lines = 0;
  for (char c : text) lines += c == '\n';
  return lines;
}

// One line, starting "carbtf: error: ", holding `expected`, and an error exit (non-zero, not a crash).
inline void check_refused(const Run& r, const std::string& expected) {
  INFO(r.output);
  CHECK(r.status != 0);
  CHECK(r.status < 128);
  CHECK(line_count(r.output) == 1);
  CHECK_THAT(r.output, Catch::StartsWith("carbtf: error: ") && Catch::Contains(expected));
}

}  // namespace carbtf::test
