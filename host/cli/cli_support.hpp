// Shared plumbing of the carbtf commands: one-line errors, device options, context creation.
#pragma once

#include <CLI/CLI.hpp>

#include <chrono>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "carbtf/analysis/btf/btf_dataset.hpp"
#include "carbtf/engine/material/direction_interpolation.hpp"
#include "carbtf/engine/synthesis/subspace_synthesizer.hpp"
#include "carbtf/engine/vulkan/context.hpp"
#include "cli/command_error.hpp"

namespace carbtf::cli {

// Options every GPU command takes.
struct DeviceOptions {
  std::string device;       // selector; empty: CARBTF_DEVICE, then the best device
  bool validation = false;  // enable the Vulkan validation layer and fail on its messages
};
void add_device_options(CLI::App& command, DeviceOptions& options);

// --scheme automatic|serial|wavefront: how CAR recursions run on the Vulkan device.
void add_car_scheme_option(CLI::App& command, CarScheme& scheme);

// --direction-taps 9|5: the (light, view) pairs the render pass reads per light
// (MaterialBindingInfo::pair_coupling: 9 the paper's product, 5 the staircase).
void add_direction_taps_option(CLI::App& command, PairCoupling& coupling);
// --parallax (MaterialBindingInfo::parallax_scale) and --parallax-steps (::parallax_steps).
void add_parallax_options(CLI::App& command, float& scale, std::uint32_t& steps);
// "9" or "5": the --direction-taps value of a coupling.
const char* direction_taps_name(PairCoupling coupling);

// For unsigned options: CLI11 would otherwise wrap "-3" around to a huge value.
const CLI::Validator& non_negative();

// Adds the checks every command shares to the options of `app` and its subcommands: each number is
// finite, within float range for real options, and not wrapped or saturated for integer ones ("nan",
// "inf", "1e39" and "18446744073709551617" are refused with one line naming the option), and --out
// and --report are not empty. Call after every command is registered.
void check_every_option(CLI::App& app);

// Throws CommandError("<what>: N of M values are not finite ...") unless every value is finite: the
// last guard before a synthesized or rendered image is written.
void require_finite(std::span<const float> values, const std::string& what);

// Refuses, before any work, an output file path that exists and is not a regular file (a folder, a
// device, a FIFO, a socket, a link to nothing): nothing is ever written in place of such a thing.
void check_output_file_path(const std::string& path, const std::string& option);

// Refuses, before any work, an output image path that cannot be written: empty, an existing folder, or
// an extension with no encoder, or anything check_output_file_path() refuses. `option` names the flag.
void check_image_output_path(const std::string& path, const std::string& option);

// Creates the context or throws CommandError with the engine's message.
std::unique_ptr<Context> make_context(const DeviceOptions& options);
// Throws when validation was on and reported anything.
void check_validation(const Context& context);
// Throws CommandError("<what>: <status message>") unless `status` is ok.
void check(const Status& status, const std::string& what);

double seconds_since(std::chrono::steady_clock::time_point start);

// `file` with `suffix` after its stem: ("out/frame.png", "_measured") gives "out/frame_measured.png".
std::filesystem::path with_stem_suffix(const std::filesystem::path& file, const std::string& suffix);

// The measured BTF a material was analysed from, loaded to compare the model with it: loads `path`
// (printing its load warnings) and checks that its light and view directions are the material's; else
// an error naming `option`, the path and both direction counts.
BtfDataset load_measurement_of(const Material& material, const std::string& path, const std::string& option);

// "WIDTHxHEIGHT" (digits only, each 1 to 16384) into width and height, or CommandError naming `option`.
void parse_frame_size(const std::string& text, const std::string& option, std::uint32_t& width,
                      std::uint32_t& height);

// How many values of `a` and `b` (images of equal sizes) differ in their bits; `values` counts them all.
std::size_t differing_values(const std::vector<std::vector<float>>& a,
                             const std::vector<std::vector<float>>& b, std::size_t& values);

// CommandError naming `material_path` unless every index in `subspaces` is one of the material's.
void require_subspaces(const Material& material, const std::vector<std::uint32_t>& subspaces,
                       const std::string& material_path);

// The `fraction` quantile of benchmark samples, interpolating linearly between order statistics
// (0.5: the median, the mean of the two middle samples for an even count); 0 for no samples.
double percentile(std::vector<double> samples, double fraction);
inline double median(std::vector<double> samples) {
  return percentile(std::move(samples), 0.5);
}

}  // namespace carbtf::cli
