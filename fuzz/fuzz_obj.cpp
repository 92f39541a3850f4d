// libFuzzer target: the OBJ reader (read_mesh_from_string with a .obj name), fuzz_mesh.h.
#include <cstddef>
#include <cstdint>

#include "fuzz_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return strictmin::fuzz::fuzz_mesh(data, size, "obj");
}
