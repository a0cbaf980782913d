// Engine outputs as RGB pictures for files and reports.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "carbtf/engine/material/direction_interpolation.hpp"
#include "carbtf/engine/render/mesh_renderer.hpp"

namespace carbtf::cli {

// Model channels to display RGB: grey is repeated, a third channel of zeros pads two, extra are dropped.
std::vector<float> channels_to_rgb(const std::vector<float>& values, std::uint32_t channels,
                                   std::size_t pixels);

// An RGBA32F frame (MeshRenderer with VK_FORMAT_R32G32B32A32_SFLOAT) as RGB floats.
std::vector<float> rendered_rgb(const RenderedImage& frame);

// Two RGB images of width x height side by side: `left` | `right`, 2 * width wide.
std::vector<float> side_by_side(const std::vector<float>& left, const std::vector<float>& right,
                                std::uint32_t width, std::uint32_t height);

// `values` (`channels` per pixel, as channels_to_rgb) written as FOLDER/STEM.png (sRGB) and .exr (linear).
void write_png_and_exr(const std::filesystem::path& folder, const std::string& stem,
                       const std::vector<float>& values, std::uint32_t channels, std::uint32_t width,
                       std::uint32_t height);

// " (light 3, view 7) 0.25 (light 4, view 7) 0.75": the pairs of an interpolation with non-zero weight.
std::string describe_weights(const PairWeights& weights);

// "07" for 7: file names that sort.
std::string two_digits(std::size_t value);

}  // namespace carbtf::cli
