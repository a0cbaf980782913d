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

// `environment` is put before the command: variables, or a wrapper such as "timeout 30".
inline Run run(const std::string& arguments, const std::string& environment = "") {
  const std::string command = environment + " \"" CARBTF_CLI_PATH "\" " + arguments + " 2>&1";
  Run result;
  FILE* pipe = popen(command.c_str(), "r");
  REQUIRE(pipe != nullptr);
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe)) result.output += buffer.data();
  const int raw = pclose(pipe);
  result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
  return result;
}

inline std::size_t line_count(const std::string& text) {
  std::size_t lines = 0;
  for (char c : text) lines += c == '\n';
  return lines;
}

}  // namespace carbtf::test
