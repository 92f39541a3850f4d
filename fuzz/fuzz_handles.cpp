// libFuzzer target: the handle-file parser (parse_handles; JSON when the text starts with
// '{', else 'vertex x y [z]' lines), for a 2D and a 3D mesh of 64 vertices. Accepted handles
// must be in range, of the mesh's dimension, finite and on distinct vertices.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <set>
#include <string>

#include "fuzz_check.h"
#include "strictmin/io/handles_io.h"

namespace {

constexpr int kVertices = 64;

void fuzz_handles(const std::string& text, int dim) {
  const std::string name = "fuzz.handles";
  std::vector<strictmin::Handle> handles;
  try {
    handles = strictmin::parse_handles(text, name, kVertices, dim);
  } catch (const strictmin::InputError& e) {
    strictmin::fuzz::check_message(e, name, text);
    return;
  }
  using strictmin::fuzz::require;
  require(!handles.empty(), "no handles accepted without an error");
  std::set<int> vertices;
  for (const auto& h : handles) {
    require(h.vertex >= 0 && h.vertex < kVertices, "handle vertex out of range accepted");
    require(h.position.size() == dim, "handle of the wrong dimension accepted");
    require(h.position.allFinite(), "non-finite handle accepted");
    require(vertices.insert(h.vertex).second, "the same vertex twice in the handles");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  fuzz_handles(text, 2);
  fuzz_handles(text, 3);
  return 0;
}
