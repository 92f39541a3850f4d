#pragma once
// Reading and writing meshes. Formats by file extension (case-insensitive):
//   .obj  Wavefront: v (2 or 3 coordinates), vt, f with i, i/t, i/t/n, i//n corners,
//         negative (relative) indices; only triangles.
//   .off  OFF (also COFF/NOFF headers with extra columns ignored); only triangles.
//   .mesh MEDIT ASCII: Vertices, Tetrahedra (Triangles alongside are the boundary and are
//         ignored when tets are present; a file with only Triangles is a triangle mesh).
//   .ply  (write only) ASCII PLY with a per-face float property `quality`.
// Every read validates (mesh/validate.h). Every write goes to a temporary file in the
// target's directory and is renamed into place: a failed run never leaves a half-written
// file.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "strictmin/mesh/mesh.h"

namespace strictmin {

struct MeshReadOptions {
  // false: skip the zero-area/volume and orientation checks (the image of a map may flip).
  bool check_geometry = true;
};

// Throws InputError naming the file, the line and the reason.
Mesh read_mesh(const std::string& path, std::vector<std::string>* warnings = nullptr,
               const MeshReadOptions& options = {});

// Parse from text already in memory (name is used in messages, its extension picks the format).
Mesh read_mesh_from_string(const std::string& text, const std::string& name,
                           std::vector<std::string>* warnings = nullptr, const MeshReadOptions& options = {});

struct MeshWriteOptions {
  // Per-element value written as PLY `quality` (and as a comment-free extra in no other
  // format). Size #F when given.
  const Eigen::VectorXd* element_quality = nullptr;
};

// Writes `mesh` (V may be 2D: written with z = 0 where the format needs 3 coordinates).
// OBJ with mesh.has_uv() writes vt lines and f v/vt corners. For a tet mesh, .obj/.off/.ply
// write its boundary triangles, .mesh writes vertices, boundary triangles and tets.
// Throws InputError, before any file is made, for a mesh a reader would refuse (indices out
// of range; a coordinate or UV that is not finite: the file, the vertex or texture coordinate
// and the value are named), and when the file cannot be written.
void write_mesh(const std::string& path, const Mesh& mesh, const MeshWriteOptions& options = {});

// Boundary faces of a tet mesh (#B by 3, oriented outward for positively oriented tets).
Eigen::MatrixXi tet_boundary_faces(const Eigen::MatrixXi& tets);
// The same, and for each boundary face the (0-based) tet it belongs to (#B). Faces come
// in tet order, then in the order (1,2,3), (0,3,2), (0,1,3), (0,2,1) within a tet.
Eigen::MatrixXi tet_boundary_faces(const Eigen::MatrixXi& tets, Eigen::VectorXi* face_tet);

}  // namespace strictmin
