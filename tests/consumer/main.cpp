// Reads a planar mesh, holds its left end, moves its right end up by half its length, solves
// L-infinity and prints the version and the largest field deviation.
#include <cstdio>
#include <string>
#include <vector>

#include "strictmin/io/mesh_io.h"
#include "strictmin/problem/problem.h"
#include "strictmin/solvers/linf.h"
#include "strictmin/version.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: consumer MESH\n");
    return 1;
  }
  const strictmin::Mesh mesh = strictmin::to_planar(strictmin::read_mesh(argv[1]));
  strictmin::Problem problem = strictmin::make_problem(mesh);
  const double x0 = mesh.V.col(0).minCoeff(), x1 = mesh.V.col(0).maxCoeff();
  std::vector<strictmin::Handle> handles;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    Eigen::VectorXd p = mesh.V.row(v).transpose();
    if (mesh.V(v, 0) == x1) p(1) += 0.5 * (x1 - x0);
    if (mesh.V(v, 0) == x0 || mesh.V(v, 0) == x1) handles.push_back({v, p});
  }
  problem.fix(handles);
  const strictmin::Result result = strictmin::solve_linf(problem);
  std::printf("strictmin %s (headers %s)\n", std::string(strictmin::version()).c_str(), STRICTMIN_VERSION);
  std::printf("status %s\n", strictmin::status_name(result.status).c_str());
  std::printf("max %.9g\n", result.distortion.maxCoeff());
  return result.ok() ? 0 : 2;
}
