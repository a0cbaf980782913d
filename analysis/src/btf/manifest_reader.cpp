// A manifest: a CSV listing any capture's images with their directions in degrees,
//   path,theta_i,phi_i,theta_v,phi_v
// one image per line; an optional header line starting with "path"; '#' starts a comment line;
// paths are relative to the manifest's folder and may be double-quoted.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <numbers>

#include "carbtf/analysis/btf/btf_reader.hpp"
#include "carbtf/analysis/image_io.hpp"
#include "carbtf/analysis/input_error.hpp"
#include "image_sources.hpp"

namespace carbtf {

namespace {

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == '"') {
      if (quoted && i + 1 < line.size() && line[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else {
        quoted = !quoted;
      }
    } else if (c == ',' && !quoted) {
      fields.emplace_back();
    } else if (c != '\r') {
      fields.back() += c;
    }
  }
  for (std::string& f : fields) {
    const auto first = f.find_first_not_of(" \t"), last = f.find_last_not_of(" \t");
    f = first == std::string::npos ? std::string() : f.substr(first, last - first + 1);
  }
  return fields;
}

// Finds `d` in `set` (within 1e-3 degrees) or appends it; returns its index.
std::uint32_t index_of(std::vector<Direction>& set, const Direction& d) {
  for (std::uint32_t i = 0; i < set.size(); ++i) {
    if (angle_between(set[i], d) < 1e-3 * std::numbers::pi / 180) return i;
  }
  set.push_back(d);
  return static_cast<std::uint32_t>(set.size() - 1);
}

}  // namespace

BtfDataset read_manifest(const std::filesystem::path& manifest, const BtfLoadOptions& options,
                         std::vector<std::string>& warnings) {
  std::ifstream file(manifest);
  if (!file) throw InputError(manifest, "cannot open the manifest");
  struct Row {
    std::filesystem::path path;
    Direction light, view;
    std::size_t line;
  };
  std::vector<Row> rows;
  std::string text;
  for (std::size_t line = 1; std::getline(file, text); ++line) {
    const auto start = text.find_first_not_of(" \t\r");
    if (start == std::string::npos || text[start] == '#') continue;
    const std::vector<std::string> fields = split_csv_line(text);
    const std::string where = manifest.string() + ":" + std::to_string(line);
    if (rows.empty() && fields[0] == "path") continue;  // header
    if (fields.size() != 5) {
      throw InputError(where, "expected 5 fields path,theta_i,phi_i,theta_v,phi_v but found " +
                                  std::to_string(fields.size()));
    }
    double angles[4];
    for (int k = 0; k < 4; ++k) {
      const std::string& f = fields[k + 1];
      const auto [end, error] = std::from_chars(f.data(), f.data() + f.size(), angles[k]);
      if (error != std::errc() || end != f.data() + f.size() || !std::isfinite(angles[k])) {
        throw InputError(where, "'" + f + "' is not a number (angles are in degrees)");
      }
    }
    if (angles[0] < 0 || angles[2] < 0) throw InputError(where, "theta must not be negative");
    if (angles[0] >= 90 || angles[2] >= 90) {
      throw InputError(where, "direction below the horizon (theta " +
                                  std::to_string(std::max(angles[0], angles[2])) + " >= 90 degrees)");
    }
    if (fields[0].empty()) throw InputError(where, "empty image path");
    if (rows.size() == kMaxDatasetDirections * kMaxDatasetDirections) {
      throw InputError(where, "more than " + std::to_string(rows.size()) + " images, the most a table of " +
                                  std::to_string(kMaxDatasetDirections) + " x " +
                                  std::to_string(kMaxDatasetDirections) + " directions holds");
    }
    rows.push_back({manifest.parent_path() / fields[0], Direction::from_degrees(angles[0], angles[1]),
                    Direction::from_degrees(angles[2], angles[3]), line});
  }
  if (rows.empty()) throw InputError(manifest, "the manifest lists no images");

  std::vector<Direction> lights, views;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> seen;
  std::vector<detail::ImageSource> sources;
  for (const Row& row : rows) {
    const LightView pair{index_of(lights, row.light), index_of(views, row.view)};
    // Stopped at the first direction past the limit: counting 10,000 of them costs 10^8 comparisons.
    check_direction_table(manifest.string(), lights.size(), views.size(), lights.size() * views.size());
    const auto [previous, inserted] = seen.emplace(std::make_pair(pair.light, pair.view), row.line);
    if (!inserted) {
      throw InputError(manifest.string() + ":" + std::to_string(row.line),
                       "duplicate direction pair, also on line " + std::to_string(previous->second));
    }
    sources.push_back({row.path.string(), [path = row.path] { return read_file_bytes(path); }, pair});
  }
  return detail::decode_sources(sources, std::move(lights), std::move(views), "manifest " + manifest.string(),
                                options, warnings);
}

}  // namespace carbtf
