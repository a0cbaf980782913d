// carbtf: compress a measured BTF into a probabilistic model and synthesize it on the GPU.
#include <CLI/CLI.hpp>

#include <csignal>

#include <cstdlib>
#include <iostream>
#include <string>

#include "cli/cli_support.hpp"
#include "commands/commands.hpp"

namespace {

// Errors end up on one line: a decoder's message can hold line breaks of its own.
std::string one_line(std::string message) {
  while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.pop_back();
  for (std::size_t at; (at = message.find('\n')) != std::string::npos;) message.replace(at, 1, "; ");
  return message;
}

}  // namespace

int main(int argc, char** argv) {
  // Past a file-size limit (ulimit -f) a write then fails with EFBIG, which the command reports and
  // cleans up after, instead of the process being killed halfway through a file.
  std::signal(SIGXFSZ, SIG_IGN);
  CLI::App app{
      "carbtf: extreme BTF compression (Haindl & Filip) with Vulkan synthesis.\n"
      "Environment: CARBTF_DEVICE picks the Vulkan device (index or part of its name)."};
  app.name("carbtf");
  carbtf::cli::register_all_commands(app);
  try {
    app.parse(argc, argv);
    if (app.get_subcommands().empty()) {
      std::string commands;
      for (const CLI::App* command : app.get_subcommands({}))
        commands += (commands.empty() ? "" : ", ") + command->get_name();
      std::cerr << "carbtf: error: no command given; commands are " << commands << " (see carbtf --help)\n";
      return 2;
    }
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // One line: what was wrong, and where to look.
    std::cerr << "carbtf: error: " << one_line(e.what()) << " (see carbtf --help)\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "carbtf: error: " << one_line(e.what()) << "\n";
    return 1;
  }
  return 0;
}
