// The CGAL peer for the parametrization benchmark (not part of the library): reads a disk
// OBJ, runs CGAL's Surface_mesh_parameterization::ARAP_parameterizer_3 (Liu et al. 2008,
// free boundary, LSCM start, its default lambda and 50 iterations) and writes the input's
// vertices and faces with the map as vt / f v/vt, so that `strictmin eval IN OUT --measure
// arap` measures it exactly like our own maps. Prints the solve time in seconds on stdout.
//
//   cgal_arap_param IN.obj OUT.obj
//
// CGAL runs 50 local-global iterations from a mean-value-coordinates start; if the result is
// not one-to-one it calls MVC_post_processor_3 (re-solves the interior by MVC inside the
// convex hull of the UV boundary), which refuses when that boundary is not a simple polygon.
// Two things about CGAL 5.5 that this program reports instead of hiding:
//  - get_error_message() is off by one from ERROR_NO_TOPOLOGICAL_BALL on (its message table
//    lacks that entry): the post-processor's ERROR_NON_CONVEX_BORDER prints as "Cannot solve
//    linear system". We print the enum's name and what it means.
//  - When only the post-processor refuses, CGAL's ARAP map itself (the Liu et al. 2008 result)
//    is still in the UV map, untouched. With --keep-unprocessed the program writes it anyway
//    and exits 3 (instead of 2), so that the benchmark can measure the ARAP map and say why
//    it was not post-processed.
// On success a line "note: ..." on stderr says whether the map is one-to-one (CGAL's own
// test, internal::is_one_to_one_mapping): CGAL returns OK after post-processing without
// checking the result again.
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/ARAP_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/internal/validity.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

using Kernel = CGAL::Simple_cartesian<double>;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace SMP = CGAL::Surface_mesh_parameterization;

namespace {

// The Error_code's name and meaning (CGAL 5.5's get_error_message() is off by one past
// ERROR_NO_TOPOLOGICAL_BALL).
std::string describe(SMP::Error_code e) {
  switch (e) {
    case SMP::OK: return "OK";
    case SMP::ERROR_EMPTY_MESH: return "ERROR_EMPTY_MESH (input mesh is empty)";
    case SMP::ERROR_NON_TRIANGULAR_MESH: return "ERROR_NON_TRIANGULAR_MESH";
    case SMP::ERROR_NO_TOPOLOGICAL_DISC: return "ERROR_NO_TOPOLOGICAL_DISC";
    case SMP::ERROR_NO_TOPOLOGICAL_BALL: return "ERROR_NO_TOPOLOGICAL_BALL";
    case SMP::ERROR_BORDER_TOO_SHORT: return "ERROR_BORDER_TOO_SHORT";
    case SMP::ERROR_NON_CONVEX_BORDER:
      return "ERROR_NON_CONVEX_BORDER (the ARAP map is not one-to-one and its UV boundary is not a simple "
             "polygon, so MVC_post_processor_3 refuses to repair it; CGAL 5.5's get_error_message() "
             "misreports this as \"Cannot solve linear system\")";
    case SMP::ERROR_CANNOT_SOLVE_LINEAR_SYSTEM: return "ERROR_CANNOT_SOLVE_LINEAR_SYSTEM";
    case SMP::ERROR_NO_1_TO_1_MAPPING: return "ERROR_NO_1_TO_1_MAPPING";
    case SMP::ERROR_WRONG_PARAMETER: return "ERROR_WRONG_PARAMETER";
  }
  return "unknown error " + std::to_string(static_cast<int>(e));
}

}  // namespace

int main(int argc, char** argv) {
  bool keep_unprocessed = false;
  std::vector<const char*> files;
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--keep-unprocessed")
      keep_unprocessed = true;
    else
      files.push_back(argv[i]);
  }
  if (files.size() != 2) {
    std::cerr << "usage: cgal_arap_param [--keep-unprocessed] IN.obj OUT.obj\n";
    return 1;
  }
  const char* const in = files[0];
  const char* const out_path = files[1];
  Mesh mesh;
  if (!CGAL::IO::read_polygon_mesh(in, mesh) || mesh.is_empty()) {
    std::cerr << in << ": cannot read a surface mesh\n";
    return 1;
  }
  const auto border = CGAL::Polygon_mesh_processing::longest_border(mesh).first;
  if (border == Mesh::null_halfedge()) {
    std::cerr << in << ": no boundary (not a disk)\n";
    return 1;
  }
  auto uv = mesh.add_property_map<Mesh::Vertex_index, Kernel::Point_2>("v:uv").first;
  const auto t0 = std::chrono::steady_clock::now();
  const SMP::Error_code err = SMP::parameterize(mesh, SMP::ARAP_parameterizer_3<Mesh>(), border, uv);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const bool unprocessed = err == SMP::ERROR_NON_CONVEX_BORDER && keep_unprocessed;
  if (err != SMP::OK) {
    std::cerr << in << ": CGAL ARAP failed: " << describe(err) << "\n";
    if (!unprocessed) return 2;
    std::cerr << "note: writing CGAL's ARAP map as it was before the refused post-processing\n";
  } else {
    const bool one_to_one = SMP::internal::is_one_to_one_mapping(mesh, border, uv);
    std::cerr << "note: CGAL returned OK; the map is " << (one_to_one ? "" : "not ")
              << "one-to-one (CGAL's is_one_to_one_mapping)\n";
  }
  std::ofstream out(out_path);
  out.precision(17);
  for (auto v : mesh.vertices()) out << "v " << mesh.point(v) << "\n";
  for (auto v : mesh.vertices()) out << "vt " << uv[v].x() << " " << uv[v].y() << "\n";
  for (auto f : mesh.faces()) {
    out << "f";
    for (auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) out << " " << v + 1 << "/" << v + 1;
    out << "\n";
  }
  if (!out) {
    std::cerr << out_path << ": cannot write\n";
    return 1;
  }
  std::printf("%.6f\n", seconds);
  return unprocessed ? 3 : 0;
}
