// File and folder names of the Bonn UBO2003 BTF layout:
//   NNNNN tlTTT plPPP tvTTT pvPPP.jpg   NNNNN = light_index * 81 + view_index, angles in integer degrees
//   tvTTT_pvPPP/                        optional per-view folder
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace carbtf {

struct Ubo2003Name {
  std::uint32_t index = 0;                                           // NNNNN
  int theta_light = 0, phi_light = 0, theta_view = 0, phi_view = 0;  // degrees
  std::string extension;                                             // lower case, with the dot: ".jpg"
};

// Parses a file name (no folder). nullopt when it is not of the UBO2003 form.
std::optional<Ubo2003Name> parse_ubo2003_name(std::string_view file_name);
// Parses a per-view folder name "tvTTT_pvPPP" into degrees.
bool parse_ubo2003_view_folder(std::string_view folder_name, int& theta, int& phi);

// Names for the UBO2003 direction indices (0..80) of a light and a view.
std::string ubo2003_file_name(std::uint32_t light_index, std::uint32_t view_index,
                              std::string_view extension);
std::string ubo2003_view_folder(std::uint32_t view_index);

}  // namespace carbtf
