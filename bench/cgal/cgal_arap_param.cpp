// The CGAL peer for the parametrization benchmark (not part of the library): reads a disk
// OBJ, runs CGAL's Surface_mesh_parameterization::ARAP_parameterizer_3 (Liu et al. 2008,
// free boundary, LSCM start, its default lambda and 50 iterations) and writes the input's
// vertices and faces with the map as vt / f v/vt, so that `strictmin eval IN OUT --measure
// arap` measures it exactly like our own maps. Prints the solve time in seconds on stdout.
//
//   cgal_arap_param IN.obj OUT.obj
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/ARAP_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>

using Kernel = CGAL::Simple_cartesian<double>;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace SMP = CGAL::Surface_mesh_parameterization;

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: cgal_arap_param IN.obj OUT.obj\n";
    return 1;
  }
  Mesh mesh;
  if (!CGAL::IO::read_polygon_mesh(argv[1], mesh) || mesh.is_empty()) {
    std::cerr << argv[1] << ": cannot read a surface mesh\n";
    return 1;
  }
  const auto border = CGAL::Polygon_mesh_processing::longest_border(mesh).first;
  if (border == Mesh::null_halfedge()) {
    std::cerr << argv[1] << ": no boundary (not a disk)\n";
    return 1;
  }
  auto uv = mesh.add_property_map<Mesh::Vertex_index, Kernel::Point_2>("v:uv").first;
  const auto t0 = std::chrono::steady_clock::now();
  const SMP::Error_code err = SMP::parameterize(mesh, SMP::ARAP_parameterizer_3<Mesh>(), border, uv);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (err != SMP::OK) {
    std::cerr << argv[1] << ": CGAL ARAP failed: " << SMP::get_error_message(err) << "\n";
    return 2;
  }
  std::ofstream out(argv[2]);
  out.precision(17);
  for (auto v : mesh.vertices()) out << "v " << mesh.point(v) << "\n";
  for (auto v : mesh.vertices()) out << "vt " << uv[v].x() << " " << uv[v].y() << "\n";
  for (auto f : mesh.faces()) {
    out << "f";
    for (auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) out << " " << v + 1 << "/" << v + 1;
    out << "\n";
  }
  if (!out) {
    std::cerr << argv[2] << ": cannot write\n";
    return 1;
  }
  std::printf("%.6f\n", seconds);
  return 0;
}
