// Kept so that hosts that include it still build: the mip level maths is Vulkan-free and lives with the
// material's (carbtf/engine/material/mip_levels.hpp), below the Vulkan layer that blits the levels.
#pragma once

#include "carbtf/engine/material/mip_levels.hpp"
