// carbtf's engine, all of it: include this, or the one layer header a file needs.
//   carbtf/engine/status.hpp      Status and ErrorCode: no exception crosses the engine's API
//   carbtf/engine/vulkan/...      the Vulkan context (own or adopted), buffers, texture arrays, timers
//   carbtf/engine/material/...    the material model and its file, range tiles, direction interpolation
//   carbtf/engine/synthesis/...   requests and GPU synthesis of subspace images, GPU noise
//   carbtf/engine/render/...      meshes, the material binding for any pass, scene pruning, resident
//                                 subspace images filled as a scene needs them, carbtf's pass
// Each header states ownership, lifetime and thread safety (docs/design.md 7).
#pragma once

#include "carbtf/engine/status.hpp"

#include "carbtf/engine/vulkan/buffer.hpp"
#include "carbtf/engine/vulkan/context.hpp"
#include "carbtf/engine/vulkan/gpu_timer.hpp"
#include "carbtf/engine/vulkan/texture_array.hpp"
#include "carbtf/engine/vulkan/unique_handle.hpp"
#include "carbtf/engine/vulkan/vulkan_functions.hpp"

#include "carbtf/engine/material/car_stability.hpp"
#include "carbtf/engine/material/direction_interpolation.hpp"
#include "carbtf/engine/material/material.hpp"
#include "carbtf/engine/material/material_directions.hpp"
#include "carbtf/engine/material/material_file.hpp"
#include "carbtf/engine/material/range_tiles.hpp"

#include "carbtf/engine/synthesis/noise_block.hpp"
#include "carbtf/engine/synthesis/noise_generator.hpp"
#include "carbtf/engine/synthesis/subspace_synthesizer.hpp"
#include "carbtf/engine/synthesis/synthesis_block.hpp"
#include "carbtf/engine/synthesis/synthesis_request.hpp"

#include "carbtf/engine/render/material_binding.hpp"
#include "carbtf/engine/render/mesh.hpp"
#include "carbtf/engine/render/mesh_renderer.hpp"
#include "carbtf/engine/render/render_scene.hpp"
#include "carbtf/engine/render/resident_images.hpp"
#include "carbtf/engine/render/scene_pruning.hpp"
