// Plays an outside program: creates a validated context, generates noise, checks it, exits 0 on success.
#include <carbtf/engine.hpp>  // the umbrella header, as an outside host would include it

#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

int main() {
  carbtf::ContextCreateInfo info;
  info.enable_validation = true;
  std::unique_ptr<carbtf::Context> context;
  if (carbtf::Status s = carbtf::Context::create(info, context); !s.ok()) {
    std::fprintf(stderr, "consumer: %s\n", s.message().c_str());
    return 1;
  }
  std::unique_ptr<carbtf::NoiseGenerator> generator;
  std::vector<float> values;
  if (carbtf::Status s = carbtf::NoiseGenerator::create(*context, generator); !s.ok()) return 1;
  if (carbtf::Status s = generator->generate({1, 0, 0, 0, 256, 256}, values); !s.ok()) return 1;
  double sum = 0, sum_sq = 0;
  for (float v : values) {
    if (!std::isfinite(v)) return 2;
    sum += v;
    sum_sq += double{v} * v;
  }
  const double mean = sum / values.size(), variance = sum_sq / values.size() - mean * mean;
  std::printf("consumer: %zu samples on %s, mean %.4f, variance %.4f\n", values.size(),
              context->device_info().name.c_str(), mean, variance);
  // 5 standard errors for 65536 samples.
  if (std::abs(mean) > 5 / 256.0 || std::abs(variance - 1) > 5 * std::sqrt(2.0) / 256.0) return 3;
  if (!context->validation_report().clean()) return 4;
  return 0;
}
