// The measured BTF drawn through the render pass, the same way as a model: so that a model and its
// measurement are compared on the same mesh, view and lights (render --compare, fidelity).
#pragma once

#include <cstdint>
#include <filesystem>
#include <utility>
#include <vector>

#include "carbtf/analysis/btf/btf_dataset.hpp"
#include "carbtf/engine/material/material.hpp"
#include "carbtf/engine/render/mesh.hpp"
#include "carbtf/engine/render/mesh_renderer.hpp"
#include "carbtf/engine/vulkan/context.hpp"

namespace carbtf::cli {

// The measured images of `pairs` (light, view indices; those the frame can use) as texture layers, a
// flat range map (the relief is in the photographs already) and no parallax, rendered once. Throws
// CommandError when the images exceed 1.5 GiB or the device's array layers. `mip_levels`: as
// SynthesisRequest::mip_levels (0: all), so that the measurement is filtered as the model is;
// `coupling` (MaterialBindingInfo::pair_coupling) so that it is interpolated as the model is.
RenderedImage render_measured(Context& context, const Material& material, const BtfDataset& dataset,
                              const std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs,
                              const Mesh& mesh, const RenderScene& scene, const RenderTargetInfo& target,
                              std::uint32_t mip_levels = 0, PairCoupling coupling = PairCoupling::product);

// render --compare: the measured BTF rendered as above into an RGBA32F target of the model frame's size,
// written beside the model's frame `out` as OUT_measured and OUT_compare (model | measured), with a line
// saying so. Checks validation after the render.
void write_measured_comparison(Context& context, const Material& material, const BtfDataset& dataset,
                               const std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs,
                               const Mesh& mesh, const RenderScene& scene,
                               const std::vector<float>& model_rgb, std::uint32_t width, std::uint32_t height,
                               const std::filesystem::path& out,
                               PairCoupling coupling = PairCoupling::product);

}  // namespace carbtf::cli
