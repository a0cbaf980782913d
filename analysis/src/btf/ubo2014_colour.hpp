// Internal to the UBO2014 reader and writer: the DFMF colour models, from the decorrelated channels to
// linear RGB (as btflib's undecorrelate) and, for the models carbtf writes, back.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>

#include "carbtf/analysis/btf/ubo2014_format.hpp"

namespace carbtf::ubo2014 {

struct ColourTransform {
  ColourModel model = ColourModel::rgb;
  std::array<float, 3> mean{};    // pca: added after the matrix
  std::array<float, 9> matrix{};  // pca: row-major; rgb (as a row) = channels (as a row) x matrix + mean
};

// Whether carbtf can decode `model`; the reason where not.
inline std::optional<std::string> unsupported_model(std::int32_t model) {
  switch (static_cast<ColourModel>(model)) {
    case ColourModel::rgb:
    case ColourModel::yuv:
    case ColourModel::pca:
    case ColourModel::ycocg:
    case ColourModel::ylog_uv:
    case ColourModel::ylog_ulog_vlog:
    case ColourModel::ylog_u_div_y_v_div_y:
    case ColourModel::rgb_log:
      return std::nullopt;
    case ColourModel::lab:
      return "colour model 2 (LAB) is not read by carbtf";
    case ColourModel::spectral:
    case ColourModel::spectral_linear:
      return "colour model " + std::to_string(model) + " is spectral; carbtf reads RGB";
  }
  return "colour model " + std::to_string(model) + " is not one of the UBO2014 models";
}

// BT.601 YUV to RGB, as btflib.
inline std::array<float, 3> yuv_to_rgb(float y, float u, float v) {
  return {y + 1.13983f * v, y - 0.39465f * u - 0.5806f * v, y + 2.03211f * u};
}

inline std::array<float, 3> to_rgb(const ColourTransform& t, std::array<float, 3> c) {
  const float e = kLogOffset;
  switch (t.model) {
    case ColourModel::rgb:
      return c;
    case ColourModel::yuv:
      return yuv_to_rgb(c[0], c[1], c[2]);
    case ColourModel::pca: {
      std::array<float, 3> rgb = t.mean;
      for (int j = 0; j < 3; ++j) {
        for (int i = 0; i < 3; ++i) rgb[j] += c[i] * t.matrix[i * 3 + j];
      }
      return rgb;
    }
    case ColourModel::ycocg:
      return {c[0] + c[1] - c[2], c[0] + c[2], c[0] - c[1] - c[2]};
    case ColourModel::ylog_uv:
      return yuv_to_rgb(std::exp(c[0]) - e, c[1], c[2]);
    case ColourModel::ylog_ulog_vlog: {
      auto signed_exp = [&](float x) { return std::copysign(std::exp(std::abs(x) + std::log(e)), x); };
      return yuv_to_rgb(std::exp(c[0]) - e, signed_exp(c[1]), signed_exp(c[2]));
    }
    case ColourModel::ylog_u_div_y_v_div_y: {
      const float y = std::exp(c[0]) - e;
      return yuv_to_rgb(y, c[1] * (y + e), c[2] * (y + e));
    }
    case ColourModel::rgb_log:
      return {std::exp(c[0]) - e, std::exp(c[1]) - e, std::exp(c[2]) - e};
    default:
      return c;  // refused when the header is read
  }
}

}  // namespace carbtf::ubo2014
