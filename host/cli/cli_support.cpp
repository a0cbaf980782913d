#include "cli/cli_support.hpp"

#include <algorithm>
#include <iostream>

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
          "CAR scheme on the Vulkan device: serial (one invocation per field, for CPU devices), wavefront (one "
          "workgroup per field, for GPUs), or automatic by device type")
      ->check(CLI::IsMember({car_scheme_name(CarScheme::automatic), car_scheme_name(CarScheme::serial),
                             car_scheme_name(CarScheme::wavefront)}))
      ->default_str(car_scheme_name(scheme));
}

const CLI::Validator& non_negative() {
  static const CLI::Validator validator(
      [](std::string& value) { return value.find('-') == std::string::npos ? std::string() : "must not be negative"; },
      "NON-NEGATIVE");
  return validator;
}

std::unique_ptr<Context> make_context(const DeviceOptions& options) {
  ContextCreateInfo info;
  // "gpu" names the default choice, so that commands with a CPU path can offer --device cpu|gpu.
  info.device_selector = options.device == "gpu" ? std::string() : options.device;
  info.enable_validation = options.validation;
  if (options.validation) {
    info.on_message = [](MessageSeverity severity, const char* text) {
      std::cerr << "carbtf: vulkan " << (severity == MessageSeverity::error ? "error" : "warning") << ": " << text
                << "\n";
    };
  }
  std::unique_ptr<Context> context;
  check(Context::create(info, context), "cannot start Vulkan");
  return context;
}

void check_validation(const Context& context) {
  const ValidationReport report = context.validation_report();
  if (!report.clean()) {
    throw CommandError("the Vulkan validation layer reported " + std::to_string(report.errors) + " errors and " +
                       std::to_string(report.warnings) + " warnings");
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

}  // namespace carbtf::cli
