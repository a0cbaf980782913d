// `carbtf info PATH`: what a BTF dataset holds.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <set>

#include "carbtf/analysis/btf/btf_reader.hpp"
#include "cli/cli_support.hpp"
#include "commands/commands.hpp"

namespace carbtf::cli {

namespace {

std::string describe_directions(const std::vector<Direction>& directions) {
  std::set<long> thetas;
  for (const Direction& d : directions) thetas.insert(std::lround(d.theta_degrees()));
  std::string list;
  for (long t : thetas) list += (list.empty() ? "" : ", ") + std::to_string(t);
  return std::to_string(directions.size()) + " (theta " + list + " degrees)";
}

void run_info(const std::string& path) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::string> warnings;
  const BtfDataset dataset = load_btf(path, {}, warnings);
  const std::size_t pairs = dataset.lights().size() * dataset.views().size();
  const std::size_t missing = dataset.missing_pairs().size();
  std::printf("source:       %s\n", dataset.source.c_str());
  std::printf("lights:       %s\n", describe_directions(dataset.lights()).c_str());
  std::printf("views:        %s\n", describe_directions(dataset.views()).c_str());
  std::printf("image size:   %u x %u\n", dataset.width(), dataset.height());
  std::printf("colour space: %s\n", color_encoding_name(dataset.encoding()));
  std::printf("images:       %zu of %zu light/view pairs (%zu missing)\n", pairs - missing, pairs, missing);
  if (!dataset.mask.empty()) {
    const auto inside = std::count_if(dataset.mask.begin(), dataset.mask.end(), [](std::uint8_t m) { return m != 0; });
    std::printf("mask:         %zd of %zu pixels\n", static_cast<std::ptrdiff_t>(inside), dataset.mask.size());
  }
  std::printf("in memory:    %.1f MiB (loaded in %.2f s)\n", dataset.storage_bytes() / 1048576.0, seconds_since(start));
  for (const std::string& w : warnings) std::printf("warning:      %s\n", w.c_str());
}

}  // namespace

void register_info_command(CLI::App& app) {
  auto path = std::make_shared<std::string>();
  auto* command = app.add_subcommand("info", "Summarise a BTF dataset: directions, image size, colour space, "
                                             "missing pairs");
  command->add_option("path", *path, "A UBO2003 folder or .zip, a manifest .csv, or a photometric-stereo folder")
      ->required();
  command->callback([path] { run_info(*path); });
}

}  // namespace carbtf::cli
