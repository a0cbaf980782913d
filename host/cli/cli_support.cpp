#include "cli/cli_support.hpp"

#include "carbtf/analysis/btf/btf_reader.hpp"
#include "carbtf/analysis/image_io.hpp"
#include "carbtf/engine/file_output.hpp"
#include "carbtf/engine/render/material_binding.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <limits>

namespace carbtf::cli {

void add_device_options(CLI::App& command, DeviceOptions& options) {
  command.add_option("--device", options.device,
                     "Vulkan device: index or part of the name, as `carbtf devices` lists them, or gpu "
                     "(default: $CARBTF_DEVICE, else the best device)");
  command.add_flag("--validation", options.validation,
                   "Enable the Vulkan validation layer; any message it reports fails the command");
}

void add_car_scheme_option(CLI::App& command, CarScheme& scheme) {
  command
      .add_option_function<std::string>(
          "--scheme",
          [&scheme](const std::string& name) {
            for (CarScheme s : {CarScheme::automatic, CarScheme::serial, CarScheme::wavefront}) {
              if (name == car_scheme_name(s)) scheme = s;
            }
          },
          "CAR scheme on the Vulkan device: serial (one invocation per field, for CPU devices), wavefront "
          "(one "
          "workgroup per field, for GPUs), or automatic by device type")
      ->check(CLI::IsMember({car_scheme_name(CarScheme::automatic), car_scheme_name(CarScheme::serial),
                             car_scheme_name(CarScheme::wavefront)}))
      ->default_str(car_scheme_name(scheme));
}

const char* direction_taps_name(PairCoupling coupling) {
  return coupling == PairCoupling::staircase ? "5" : "9";
}

void add_parallax_options(CLI::App& command, float& scale, std::uint32_t& steps) {
  command.add_option("--parallax", scale, "Parallax scale (1: the range map's own heights; 0: none)")
      ->check(CLI::Range(0.0f, 16.0f))
      ->capture_default_str();
  command
      .add_option(
          "--parallax-steps", steps,
          "Most steps of the parallax ray march down each pixel's view ray, half a texel each, to the "
          "first point of the relief, so that ridges hide what lies behind them (16 reach a relief 4.6 "
          "texels deep at 60 degrees from the top, longer steps beyond); 0: offset mapping, one height read "
          "per pixel, cheaper, with facets turned from the view left in sight")
      ->check(CLI::Range(0u, kMaxParallaxSteps))
      ->capture_default_str();
}

void add_direction_taps_option(CLI::App& command, PairCoupling& coupling) {
  command
      .add_option_function<std::string>(
          "--direction-taps",
          [&coupling](const std::string& taps) {
            coupling = taps == direction_taps_name(PairCoupling::staircase) ? PairCoupling::staircase
                                                                            : PairCoupling::product;
          },
          "(Light, view) pairs the render pass reads per light: 9, every light weight times every view "
          "weight (the paper's), or 5, a staircase of the same weights, exact at the measured pairs, "
          "whose render pass reads fewer images and whose picture between the measured directions differs "
          "(docs/design.md 4.5; `carbtf bench frame --parts` measures the difference)")
      ->check(CLI::IsMember(
          {direction_taps_name(PairCoupling::product), direction_taps_name(PairCoupling::staircase)}))
      ->default_str(direction_taps_name(coupling));
}

const CLI::Validator& non_negative() {
  static const CLI::Validator validator(
      [](std::string& value) {
        return value.find('-') == std::string::npos ? std::string() : "must not be negative";
      },
      "NON-NEGATIVE");
  return validator;
}

namespace {

// The check for one token of a numeric option; an empty string accepts it. Text that is no number is
// left to CLI11's own conversion, which names the option and the expected type.
std::string representable_number(const std::string& token, bool real) {
  if (token.empty()) return {};
  errno = 0;
  char* end = nullptr;
  if (real) {
    const double value = std::strtod(token.c_str(), &end);
    if (end != token.c_str() + token.size()) return {};
    // Underflow to 0 is harmless; overflow past float would become infinity on the device.
    if (!std::isfinite(value) || std::fabs(value) > std::numeric_limits<float>::max()) {
      return token + " is not a finite number within +-3.4e38";
    }
    return {};
  }
  const bool negative = token.find('-') != std::string::npos;
  if (negative) {
    std::strtoll(token.c_str(), &end, 0);
  } else {
    std::strtoull(token.c_str(), &end, 0);
  }
  if (end == token.c_str() + token.size() && errno == ERANGE) return token + " does not fit a 64-bit integer";
  return {};
}

}  // namespace

void check_every_option(CLI::App& app) {
  for (CLI::Option* option : app.get_options()) {
    if (option->check_name("--out") || option->check_name("--report")) {
      // An empty path would write into the current folder under names like "/subspace_00.png"; a device,
      // FIFO or socket there is never written to or replaced (a folder or a file: each command says which
      // it takes).
      option->check(CLI::Validator(
          [](std::string& path) {
            if (path.empty()) return std::string("the path is empty");
            std::error_code error;
            if (std::filesystem::is_directory(path, error)) return std::string();
            const Status s = check_output_file(path);
            return s.ok() ? std::string() : s.message();
          },
          ""));
      continue;
    }
    const std::string type = option->get_type_name();
    const bool real = type.find("FLOAT") != std::string::npos;
    const bool integer = type.find("INT") != std::string::npos;
    if (!real && !integer) continue;
    option->check(
        CLI::Validator([real](std::string& token) { return representable_number(token, real); }, ""));
  }
  for (CLI::App* command : app.get_subcommands({})) check_every_option(*command);
}

void require_finite(std::span<const float> values, const std::string& what) {
  const auto bad = static_cast<std::size_t>(
      std::count_if(values.begin(), values.end(), [](float v) { return !std::isfinite(v); }));
  if (bad == 0) return;
  throw CommandError(
      what + ": " + std::to_string(bad) + " of " + std::to_string(values.size()) +
      " values are not finite (NaN or infinity); nothing was written. This is a defect of carbtf or of "
      "the material: please report it with the material file");
}

void check_output_file_path(const std::string& path, const std::string& option) {
  if (path.empty()) throw CommandError(option + ": the output path is empty");
  if (std::filesystem::is_directory(path))
    throw CommandError(option + " " + path + ": is a folder; this option takes a file name");
  check(check_output_file(path), option);
}

void check_image_output_path(const std::string& path, const std::string& option) {
  if (path.empty()) throw CommandError(option + ": the output path is empty");
  if (std::filesystem::is_directory(path)) {
    throw CommandError(option + " " + path + ": is a folder; give an image file name such as " +
                       (std::filesystem::path(path) / "frame.png").string());
  }
  if (!is_supported_image_extension(path)) {
    throw CommandError(option + " " + path +
                       ": unknown image type; use .png, .jpg, .bmp (8-bit sRGB) or .exr, .tif, .pfm (float)");
  }
  check(check_output_file(path), option);
}

std::unique_ptr<Context> make_context(const DeviceOptions& options) {
  ContextCreateInfo info;
  // "gpu" names the default choice, so that commands with a CPU path can offer --device cpu|gpu.
  info.device_selector = options.device == "gpu" ? std::string() : options.device;
  info.enable_validation = options.validation;
  if (options.validation) {
    info.on_message = [](MessageSeverity severity, const char* text) {
      std::cerr << "carbtf: vulkan " << (severity == MessageSeverity::error ? "error" : "warning") << ": "
                << text << "\n";
    };
  }
  std::unique_ptr<Context> context;
  check(Context::create(info, context), "cannot start Vulkan");
  return context;
}

void check_validation(const Context& context) {
  const ValidationReport report = context.validation_report();
  if (!report.clean()) {
    throw CommandError("the Vulkan validation layer reported " + std::to_string(report.errors) +
                       " errors and " + std::to_string(report.warnings) + " warnings");
  }
}

void check(const Status& status, const std::string& what) {
  if (!status.ok()) throw CommandError(what + ": " + status.message());
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double percentile(std::vector<double> samples, double fraction) {
  if (samples.empty()) return 0.0;
  std::sort(samples.begin(), samples.end());
  const double position = std::clamp(fraction, 0.0, 1.0) * static_cast<double>(samples.size() - 1);
  const auto below = static_cast<std::size_t>(position);
  const std::size_t above = std::min(below + 1, samples.size() - 1);
  return samples[below] + (position - static_cast<double>(below)) * (samples[above] - samples[below]);
}

void parse_frame_size(const std::string& text, const std::string& option, std::uint32_t& width,
                      std::uint32_t& height) {
  // Digits only, at most 5 each: sscanf's %u would wrap 4294967297 to 1 and accept a sign.
  const std::size_t x = text.find_first_of("xX");
  const auto digits = [](std::string_view part) {
    return !part.empty() && part.size() <= 5 &&
           part.find_first_not_of("0123456789") == std::string_view::npos;
  };
  const std::string_view all(text);
  const bool shaped = x != std::string::npos && digits(all.substr(0, x)) && digits(all.substr(x + 1));
  const unsigned w = shaped ? static_cast<unsigned>(std::stoul(text.substr(0, x))) : 0;
  const unsigned h = shaped ? static_cast<unsigned>(std::stoul(text.substr(x + 1))) : 0;
  if (!shaped || w == 0 || h == 0 || w > 16384 || h > 16384) {
    throw CommandError(option + " " + text + ": expected WIDTHxHEIGHT, each 1 to 16384 (e.g. 1920x1080)");
  }
  width = w;
  height = h;
}

std::filesystem::path with_stem_suffix(const std::filesystem::path& file, const std::string& suffix) {
  return std::filesystem::path(file).replace_filename(file.stem().string() + suffix +
                                                      file.extension().string());
}

BtfDataset load_measurement_of(const Material& material, const std::string& path, const std::string& option) {
  std::vector<std::string> warnings;
  BtfDataset dataset = load_btf(path, {}, warnings);
  for (const std::string& w : warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  require_directions_of(dataset, material, option + " " + path);
  return dataset;
}

void require_subspaces(const Material& material, const std::vector<std::uint32_t>& subspaces,
                       const std::string& material_path) {
  for (std::uint32_t s : subspaces) {
    if (s >= material.subspaces.size()) {
      throw CommandError("--subspaces: subspace " + std::to_string(s) + " does not exist; " + material_path +
                         " has " + std::to_string(material.subspaces.size()) + " (0 to " +
                         std::to_string(material.subspaces.size() - 1) + ")");
    }
  }
}

std::size_t differing_values(const std::vector<std::vector<float>>& a,
                             const std::vector<std::vector<float>>& b, std::size_t& values) {
  std::size_t differing = 0;
  values = 0;
  for (std::size_t s = 0; s < a.size(); ++s) {
    values += a[s].size();
    for (std::size_t i = 0; i < a[s].size(); ++i)
      differing += std::memcmp(&a[s][i], &b[s][i], sizeof(float)) != 0;
  }
  return differing;
}

}  // namespace carbtf::cli
