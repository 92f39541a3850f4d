#pragma once
// Internal: one reader and one writer per mesh format; mesh_io.cpp picks by extension.
// Readers only parse (indices are range-checked with the line number); validation is done
// once by the caller. Not a public header.
#include <Eigen/Core>
#include <functional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "strictmin/mesh/mesh.h"

namespace strictmin::io_detail {

Mesh read_obj(std::string_view text, const std::string& name, std::vector<std::string>* warnings);
Mesh read_off(std::string_view text, const std::string& name);
Mesh read_medit(std::string_view text, const std::string& name);

// A triangle surface to write: V (#V by 2 or 3), F (#F by 3), optional UV/FUV (OBJ only)
// and optional per-face quality (PLY only).
struct SurfaceRef {
  const Eigen::MatrixXd& V;
  const Eigen::MatrixXi& F;
  const Eigen::MatrixXd* UV = nullptr;
  const Eigen::MatrixXi* FUV = nullptr;
  const Eigen::VectorXd* quality = nullptr;
};

class ChunkWriter;  // text_parse.h

// The vertex and face lines that OFF and PLY share: "x y z" per vertex (z = 0 for 2D
// positions) and "3 a b c" per face, each with its newline; `after_face` (may be null) appends
// what follows a face's indices on its line (PLY's quality).
void append_vertex_and_face_lines(ChunkWriter& out, const SurfaceRef& s,
                                  const std::function<void(std::string&, Eigen::Index)>& after_face);

void write_obj(std::ostream& os, const SurfaceRef& surface);
void write_off(std::ostream& os, const SurfaceRef& surface);
void write_ply(std::ostream& os, const SurfaceRef& surface);
// Writes vertices, then boundary triangles and tets for a tet mesh, or triangles.
void write_medit(std::ostream& os, const Mesh& mesh);

}  // namespace strictmin::io_detail
