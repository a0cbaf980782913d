// `carbtf info PATH`: what a BTF dataset or a material file holds.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>

#include "carbtf/analysis/btf/btf_reader.hpp"
#include "cli/cli_support.hpp"
#include "commands/commands.hpp"
#include "report/material_summary.hpp"

namespace carbtf::cli {

namespace {

std::string describe_directions(const std::vector<Direction>& directions) {
  std::set<long> thetas;
  for (const Direction& d : directions) thetas.insert(std::lround(d.theta_degrees()));
  std::string list;
  for (long t : thetas) list += (list.empty() ? "" : ", ") + std::to_string(t);
  return std::to_string(directions.size()) + " (theta " + list + " degrees)";
}

// By name, or by signature for a regular file: opening a FIFO to peek would wait for a writer.
bool is_material_file(const std::string& path) {
  if (std::filesystem::path(path).extension() == ".cbtf") return true;
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) return false;
  std::ifstream file(path, std::ios::binary);
  char magic[4] = {};
  return file.read(magic, 4) && std::equal(magic, magic + 4, "CBTF");
}

void run_info(const std::string& path) {
  if (is_material_file(path)) {
    print_material_summary(path);
    return;
  }
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
    const auto inside =
        std::count_if(dataset.mask.begin(), dataset.mask.end(), [](std::uint8_t m) { return m != 0; });
    std::printf("mask:         %zd of %zu pixels\n", static_cast<std::ptrdiff_t>(inside),
                dataset.mask.size());
  }
  std::printf("in memory:    %.1f MiB (loaded in %.2f s)\n", dataset.storage_bytes() / 1048576.0,
              seconds_since(start));
  for (const std::string& w : warnings) std::printf("warning:      %s\n", w.c_str());
}

}  // namespace

void register_info_command(CLI::App& app) {
  auto path = std::make_shared<std::string>();
  auto* command =
      app.add_subcommand("info",
                         "Summarise a BTF dataset (directions, image size, colour space, missing pairs) "
                         "or a .cbtf material (model summary and size per chunk)");
  command
      ->add_option("path", *path,
                   "A UBO2003 folder or .zip, a manifest .csv, a photometric-stereo folder, a Bonn UBO2014 "
                   ".btf file, or a .cbtf material")
      ->required();
  command->callback([path] { run_info(*path); });
}

}  // namespace carbtf::cli
