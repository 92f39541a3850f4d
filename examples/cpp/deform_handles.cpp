// Deform a planar mesh by handles with the least possible worst-case distortion.
//
// A 40 by 10 strip (or the planar mesh given as the first argument) is held at both ends
// and the vertex nearest its centre is pulled up by a twentieth of its length (the paper's
// Figure 2 on a strip). L2 would concentrate the distortion around the pulled vertex; the
// L-infinity method puts the map's largest field deviation ||J - I|| as low as any map can,
// and certifies it with a lower bound.
//
//   deform_handles                 # the built-in strip
//   deform_handles mesh.obj out.obj
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "strictmin/io/mesh_io.h"
#include "strictmin/mesh/generators.h"
#include "strictmin/mesh/handle.h"
#include "strictmin/tasks/deform.h"

int main(int argc, char** argv) try {
  using namespace strictmin;
  // #V by 2 or 3 positions, #F by 3 triangles (or #F by 4 tets read from a .mesh file).
  const Mesh mesh = argc > 1 ? read_mesh(argv[1]) : make_grid(40, 10, 4.0, 1.0);
  const std::string output = argc > 2 ? argv[2] : "deformed.obj";

  // Handles: the vertices within 2% of either end stay where they are; the vertex nearest
  // the centre of the bounding box moves up.
  const Eigen::VectorXd x = mesh.V.col(0);
  const double x0 = x.minCoeff(), x1 = x.maxCoeff(), band = 0.02 * (x1 - x0);
  const Eigen::RowVectorXd centre = 0.5 * (mesh.V.colwise().minCoeff() + mesh.V.colwise().maxCoeff());
  Eigen::Index middle = 0;
  (mesh.V.rowwise() - centre).rowwise().squaredNorm().minCoeff(&middle);
  // Handles have the map's dimension, decided as the strictmin tool does: planar triangles
  // (2D coordinates, or 3D ones with a constant z as most OBJ files) move in the plane; tets
  // and 3D surfaces in 3D.
  const int dim = mesh.element_type() == ElementType::Tetrahedron || !mesh.is_planar() ? 3 : 2;
  std::vector<Handle> handles;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    Eigen::VectorXd p = mesh.V.row(v).leftCols(dim).transpose();
    if (v == middle) {
      p(1) += 0.05 * (x1 - x0);
      handles.push_back({v, p});
    } else if (x(v) <= x0 + band || x(v) >= x1 - band) {
      handles.push_back({v, p});
    }
  }

  // L2 (least squares) first, for comparison, then L-infinity.
  DeformOptions options;
  options.solver.method = Method::L2;
  const DeformOutcome l2 = deform(mesh, handles, options);
  options.solver.method = Method::Linf;  // Method::Relax or Method::Direct: the strict minimizer
  const DeformOutcome out = deform(mesh, handles, options);

  std::printf("%d elements, %zu handles\n", mesh.num_elements(), handles.size());
  std::printf("L2:          max distortion %.6f (element %d)\n", l2.measured.stats.max,
              l2.measured.stats.max_element);
  std::printf("L-infinity:  max distortion %.6f (element %d), certified lower bound %.6f, status %s\n",
              out.measured.stats.max, out.measured.stats.max_element, out.result.lower_bound,
              status_name(out.result.status).c_str());
  write_mesh(output, out.deformed);  // the input mesh with the new positions
  std::printf("wrote %s\n", output.c_str());
  return out.result.ok() ? 0 : 2;  // as the strictmin tool: 2 for any status but solved
} catch (const std::exception& e) {  // strictmin::InputError for input the task can't take
  std::fprintf(stderr, "deform_handles: %s\n", e.what());
  return 1;
}
