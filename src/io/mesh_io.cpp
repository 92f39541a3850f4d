// Mesh files: format by extension, read whole then parse, validate; atomic writes.
#include "strictmin/io/mesh_io.h"

#include <algorithm>
#include <array>
#include <filesystem>

#include "formats.h"
#include "strictmin/io/atomic_file.h"
#include "strictmin/io/input_error.h"
#include "strictmin/mesh/validate.h"
#include "text_parse.h"

namespace strictmin {
namespace {

std::string extension_of(const std::string& name) {
  return io_detail::lowercase(std::filesystem::path(name).extension().string());
}

[[noreturn]] void unknown_format(const std::string& name, const std::string& ext, const char* choices) {
  if (ext.empty())
    throw InputError(located(name, 0, std::string("no file extension, cannot tell the mesh format (use ") + choices + ")"));
  throw InputError(located(name, 0, "unknown mesh format '" + ext + "' (use " + choices + ")"));
}

// Outward faces of a positively oriented tet (v0..v3), by local corner.
constexpr int kTetFaces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

}  // namespace

Mesh read_mesh_from_string(const std::string& text, const std::string& name, std::vector<std::string>* warnings,
                           const MeshReadOptions& options) {
  if (io_detail::has_utf8_bom(text))  // as read_mesh's file (read_text_file)
    return read_mesh_from_string(text.substr(3), name, warnings, options);
  const std::string ext = extension_of(name);
  Mesh mesh;
  if (ext == ".obj")
    mesh = io_detail::read_obj(text, name, warnings);
  else if (ext == ".off")
    mesh = io_detail::read_off(text, name);
  else if (ext == ".mesh")
    mesh = io_detail::read_medit(text, name);
  else if (ext == ".ply")
    throw InputError(located(name, 0, "reading .ply is not supported (use .obj, .off or .mesh)"));
  else
    unknown_format(name, ext, ".obj, .off or .mesh");
  validate_mesh(mesh, name, warnings, options.check_geometry);
  return mesh;
}

Mesh read_mesh(const std::string& path, std::vector<std::string>* warnings, const MeshReadOptions& options) {
  const std::string ext = extension_of(path);
  if (ext != ".obj" && ext != ".off" && ext != ".mesh") {
    if (ext == ".ply") throw InputError(located(path, 0, "reading .ply is not supported (use .obj, .off or .mesh)"));
    unknown_format(path, ext, ".obj, .off or .mesh");
  }
  return read_mesh_from_string(io_detail::read_text_file(path), path, warnings, options);
}

void write_mesh(const std::string& path, const Mesh& mesh, const MeshWriteOptions& options) {
  const std::string ext = extension_of(path);
  if (ext != ".obj" && ext != ".off" && ext != ".mesh" && ext != ".ply") unknown_format(path, ext, ".obj, .off, .mesh or .ply");
  if (mesh.F.cols() != 3 && mesh.F.cols() != 4)
    throw InputError("cannot write " + path + ": elements have " + std::to_string(mesh.F.cols()) +
                     " corners (need 3 or 4)");
  // What a reader would refuse, before any file is made: indices out of range, and coordinates
  // or UVs that are not finite ("nan" and "inf" are no numbers in OBJ, OFF, PLY or MEDIT).
  check_mesh_structure(mesh, "cannot write " + path, /*require_finite=*/true);
  if (options.element_quality && options.element_quality->size() != mesh.F.rows())
    throw InputError("cannot write " + path + ": element_quality has " +
                     std::to_string(options.element_quality->size()) + " values, the mesh has " +
                     std::to_string(mesh.F.rows()) + " elements");

  if (ext == ".mesh") {
    write_file_atomically(path, [&](std::ostream& os) { io_detail::write_medit(os, mesh); });
    return;
  }
  // OBJ, OFF and PLY hold triangles: a tet mesh is written as its boundary surface, each
  // face carrying the quality of its tet.
  const bool tets = mesh.element_type() == ElementType::Tetrahedron;
  Eigen::MatrixXi boundary;
  Eigen::VectorXd boundary_quality;
  const Eigen::VectorXd* quality = options.element_quality;
  if (tets) {
    Eigen::VectorXi owner;
    boundary = tet_boundary_faces(mesh.F, &owner);
    if (quality) {
      boundary_quality.resize(owner.size());
      for (Eigen::Index f = 0; f < owner.size(); ++f) boundary_quality(f) = (*quality)(owner(f));
      quality = &boundary_quality;
    }
  }
  io_detail::SurfaceRef surface{mesh.V, tets ? boundary : mesh.F};
  if (!tets && mesh.has_uv()) {
    surface.UV = &mesh.UV;
    surface.FUV = &mesh.FUV;
  }
  surface.quality = quality;
  write_file_atomically(path, [&](std::ostream& os) {
    if (ext == ".obj")
      io_detail::write_obj(os, surface);
    else if (ext == ".off")
      io_detail::write_off(os, surface);
    else
      io_detail::write_ply(os, surface);
  });
}

Eigen::MatrixXi tet_boundary_faces(const Eigen::MatrixXi& tets) { return tet_boundary_faces(tets, nullptr); }

Eigen::MatrixXi tet_boundary_faces(const Eigen::MatrixXi& tets, Eigen::VectorXi* face_tet) {
  // Sort the 4 faces of every tet by their sorted corners; a face seen once is boundary.
  struct Key {
    std::array<int, 3> corners;
    int id;  // tet * 4 + local face
  };
  const Eigen::Index n = tets.rows();
  std::vector<Key> keys(static_cast<size_t>(n) * 4);
  for (Eigen::Index t = 0; t < n; ++t)
    for (int l = 0; l < 4; ++l) {
      std::array<int, 3> c = {tets(t, kTetFaces[l][0]), tets(t, kTetFaces[l][1]), tets(t, kTetFaces[l][2])};
      std::sort(c.begin(), c.end());
      keys[t * 4 + l] = {c, static_cast<int>(t * 4 + l)};
    }
  std::sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) { return a.corners < b.corners; });
  std::vector<int> boundary;
  for (size_t i = 0; i < keys.size();) {
    size_t j = i + 1;
    while (j < keys.size() && keys[j].corners == keys[i].corners) ++j;
    if (j - i == 1) boundary.push_back(keys[i].id);
    i = j;
  }
  std::sort(boundary.begin(), boundary.end());
  Eigen::MatrixXi faces(static_cast<Eigen::Index>(boundary.size()), 3);
  if (face_tet) face_tet->resize(static_cast<Eigen::Index>(boundary.size()));
  for (size_t b = 0; b < boundary.size(); ++b) {
    const int t = boundary[b] / 4, l = boundary[b] % 4;
    for (int k = 0; k < 3; ++k) faces(static_cast<Eigen::Index>(b), k) = tets(t, kTetFaces[l][k]);
    if (face_tet) (*face_tet)(static_cast<Eigen::Index>(b)) = t;
  }
  return faces;
}

}  // namespace strictmin
