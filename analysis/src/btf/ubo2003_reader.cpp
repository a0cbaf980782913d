// The UBO2003 layout, as a folder (flat or with per-view folders).
#include <algorithm>
#include <map>

#include "carbtf/analysis/btf/btf_reader.hpp"
#include "carbtf/analysis/btf/ubo2003_names.hpp"
#include "carbtf/analysis/image_io.hpp"
#include "carbtf/analysis/input_error.hpp"
#include "image_sources.hpp"
#include "ubo2003_entries.hpp"

namespace carbtf {

namespace fs = std::filesystem;

namespace detail {

LightView ubo2003_pair(const std::string& display_name, const std::string& file_name,
                       const std::string& folder_name, std::map<std::uint32_t, std::string>& seen) {
  const auto name = parse_ubo2003_name(file_name);
  if (!name) {
    const bool image_like = is_supported_image_extension(file_name);
    throw InputError(display_name, image_like
                                       ? "name is not of the UBO2003 form 'NNNNN tlTTT plPPP tvTTT pvPPP.jpg'"
                                       : "not an image file (expected UBO2003 images named "
                                         "'NNNNN tlTTT plPPP tvTTT pvPPP.jpg')");
  }
  if (!is_supported_image_extension(file_name)) {
    throw InputError(display_name, "not an image file: unknown extension '" + name->extension + "'");
  }
  if (name->theta_light >= 90 || name->theta_view >= 90) {
    throw InputError(display_name, "direction below the horizon (theta " +
                                       std::to_string(std::max(name->theta_light, name->theta_view)) +
                                       " >= 90 degrees)");
  }
  const auto light = ubo2003_index(name->theta_light, name->phi_light);
  const auto view = ubo2003_index(name->theta_view, name->phi_view);
  if (!light || !view) {
    throw InputError(display_name,
                     "direction not in the UBO2003 set of 81 (use a manifest .csv for other sets)");
  }
  const std::uint32_t expected = *light * 81 + *view;
  if (name->index != expected) {
    throw InputError(display_name,
                     "index " + std::to_string(name->index) +
                         " does not match its directions (light*81+view = " + std::to_string(expected) + ")");
  }
  if (!folder_name.empty()) {
    int theta = 0, phi = 0;
    if (!parse_ubo2003_view_folder(folder_name, theta, phi)) {
      throw InputError(display_name,
                       "sits in folder '" + folder_name + "', which is not a view folder tvTTT_pvPPP");
    }
    if (ubo2003_index(theta, phi) != view) {
      throw InputError(display_name, "its view direction does not match its folder '" + folder_name + "'");
    }
  }
  const auto [previous, inserted] = seen.emplace(expected, display_name);
  if (!inserted) throw InputError(display_name, "duplicate direction pair, also in " + previous->second);
  return {*light, *view};
}

}  // namespace detail

BtfDataset read_ubo2003_folder(const fs::path& folder, const BtfLoadOptions& options,
                               std::vector<std::string>& warnings) {
  std::error_code ec;
  if (!fs::exists(folder, ec)) throw InputError(folder, "no such file or folder");
  if (!fs::is_directory(folder, ec)) throw InputError(folder, "not a folder");

  struct Found {
    fs::path path;
    std::string folder_name;
  };
  std::vector<Found> files;
  auto list = [&](const fs::path& dir) {
    std::vector<fs::directory_entry> entries;
    for (const auto& entry : fs::directory_iterator(dir, ec)) entries.push_back(entry);
    if (ec) throw InputError(dir, "cannot list folder: " + ec.message());
    std::sort(entries.begin(), entries.end());
    return entries;
  };
  for (const auto& entry : list(folder)) {
    const std::string name = entry.path().filename().string();
    if (name.starts_with(".")) continue;  // hidden files: .DS_Store and friends
    if (entry.is_directory()) {
      for (const auto& inner : list(entry.path())) {
        const std::string inner_name = inner.path().filename().string();
        if (inner_name.starts_with(".")) continue;
        if (inner.is_directory()) throw InputError(inner.path(), "unexpected folder inside a view folder");
        files.push_back({inner.path(), name});
      }
    } else {
      files.push_back({entry.path(), ""});
    }
  }
  if (files.empty()) throw InputError(folder, "no images in this folder");

  std::map<std::uint32_t, std::string> seen;
  std::vector<detail::ImageSource> sources;
  for (const Found& f : files) {
    const LightView pair =
        detail::ubo2003_pair(f.path.string(), f.path.filename().string(), f.folder_name, seen);
    sources.push_back({f.path.string(), [path = f.path] { return read_file_bytes(path); }, pair});
  }
  return detail::decode_sources(sources, ubo2003_directions(), ubo2003_directions(),
                                "UBO2003 folder " + folder.string(), options, warnings);
}

}  // namespace carbtf
