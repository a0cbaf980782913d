// libFuzzer target: the OBJ mesh loader of `carbtf render --mesh FILE.obj` (host/scene/scene_mesh).
// One-line errors (CommandError) are the expected outcome; a loaded mesh must be valid.
#include <cstdint>
#include <cstdlib>
#include <exception>

#include "carbtf/engine/render/mesh.hpp"
#include "fuzz_support.hpp"
#include "scene/scene_mesh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = carbtf::fuzz::write_input("mesh.obj", data, size);
  try {
    const carbtf::Mesh mesh = carbtf::cli::load_obj_mesh(path);
    if (!carbtf::validate_mesh(mesh).ok()) std::abort();
  } catch (const std::exception&) {
  }
  return 0;
}
