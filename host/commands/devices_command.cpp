// `carbtf devices`: what Vulkan devices there are, which one carbtf would use, and why not the others.
#include <cstdio>
#include <vector>

#include "cli/cli_support.hpp"
#include "commands/commands.hpp"

namespace carbtf::cli {

void register_devices_command(CLI::App& app) {
  auto* command = app.add_subcommand("devices", "List Vulkan devices and the one carbtf picks by default");
  command->callback([] {
    std::vector<DeviceInfo> devices;
    check(enumerate_devices(devices), "cannot list Vulkan devices");
    std::uint32_t chosen = 0;
    const Status selected = select_device(devices, "", chosen);
    std::printf("%-3s %-40s %-15s %-8s %s\n", "#", "name", "type", "Vulkan", "notes");
    for (const DeviceInfo& d : devices) {
      char version[32];
      std::snprintf(version, sizeof version, "%u.%u.%u", VK_API_VERSION_MAJOR(d.api_version),
                    VK_API_VERSION_MINOR(d.api_version), VK_API_VERSION_PATCH(d.api_version));
      std::string notes;
      if (!d.suitable) {
        notes = "unsuitable: " + d.unsuitable_reason;
      } else {
        notes = (selected.ok() && d.index == chosen ? "default; " : "") + std::string("storage range ") +
                std::to_string(d.max_storage_buffer_range >> 20) + " MiB, subgroup " +
                std::to_string(d.subgroup_size) +
                (d.timestamp_valid_bits ? ", timestamps" : ", no timestamps") +
                (d.shader_float64 ? ", float64" : "");
      }
      std::printf("%-3u %-40s %-15s %-8s %s\n", d.index, d.name.c_str(), device_type_name(d.type), version,
                  notes.c_str());
    }
    if (!selected.ok()) throw CommandError(selected.message());
  });
}

}  // namespace carbtf::cli
