#pragma once
// The mesh readers' fuzz target, one per format (fuzz_obj.cpp, fuzz_off.cpp, fuzz_medit.cpp):
// the bytes are the file's text, `name`'s extension picks the reader. An accepted mesh must
// be valid (indices in range, finite coordinates) and must read back the same after the
// same format's writer.
#include <sstream>
#include <string>
#include <vector>

#include "formats.h"  // src/io: the writers to a stream
#include "fuzz_check.h"
#include "strictmin/io/mesh_io.h"

namespace strictmin::fuzz {

inline void check_valid(const Mesh& mesh) {
  require(mesh.F.rows() > 0, "an accepted mesh has no elements");
  require(mesh.F.cols() == 3 || mesh.F.cols() == 4, "elements with neither 3 nor 4 corners");
  require(mesh.V.cols() == 2 || mesh.V.cols() == 3, "vertices with neither 2 nor 3 coordinates");
  require(mesh.V.allFinite(), "non-finite coordinate accepted");
  require(mesh.F.minCoeff() >= 0 && mesh.F.maxCoeff() < mesh.V.rows(), "vertex index out of range accepted");
  if (mesh.has_uv()) {
    require(mesh.FUV.minCoeff() >= 0 && mesh.FUV.maxCoeff() < mesh.UV.rows(), "vt index out of range accepted");
    require(mesh.UV.allFinite(), "non-finite texture coordinate accepted");
  }
}

// Writes `mesh` in the format of `name` and reads it back: same elements, same coordinates
// (the writers print the shortest text that reads back to the same double; OBJ and OFF
// write 2D positions with z = 0).
inline void check_round_trip(const Mesh& mesh, const std::string& name, const std::string& ext) {
  std::ostringstream os;
  if (ext == "mesh") {
    io_detail::write_medit(os, mesh);
  } else {
    if (mesh.F.cols() != 3) return;  // OBJ and OFF hold triangles (a tet mesh comes only from .mesh)
    io_detail::SurfaceRef surface{mesh.V, mesh.F};
    if (mesh.has_uv()) {
      surface.UV = &mesh.UV;
      surface.FUV = &mesh.FUV;
    }
    if (ext == "obj")
      io_detail::write_obj(os, surface);
    else
      io_detail::write_off(os, surface);
  }
  Mesh back;
  try {
    back = read_mesh_from_string(os.str(), name);
  } catch (const InputError& e) {
    broken(std::string("the written mesh does not read back: ") + e.what());
  }
  require(back.F == mesh.F, "elements differ after a round trip");
  require(back.V.rows() == mesh.V.rows() && back.V.cols() >= mesh.V.cols(), "vertex count differs after a round trip");
  require(back.V.leftCols(mesh.V.cols()) == mesh.V, "coordinates differ after a round trip");
  if (back.V.cols() > mesh.V.cols()) require(back.V.rightCols(1).isZero(0.0), "z of a 2D mesh is not 0 after a round trip");
  require(back.has_uv() == (mesh.has_uv() && ext == "obj"), "texture coordinates lost after a round trip");
  if (back.has_uv()) require(back.UV == mesh.UV && back.FUV == mesh.FUV, "texture coordinates differ after a round trip");
}

inline int fuzz_mesh(const uint8_t* data, size_t size, const std::string& ext) {
  const std::string name = "fuzz." + ext;
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> warnings;
  Mesh mesh;
  try {
    mesh = read_mesh_from_string(text, name, &warnings);
  } catch (const InputError& e) {
    check_message(e, name, text);
    return 0;
  }
  check_valid(mesh);
  check_round_trip(mesh, name, ext);
  return 0;
}

}  // namespace strictmin::fuzz
