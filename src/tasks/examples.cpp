#include "strictmin/tasks/examples.h"

#include <Eigen/Geometry>
#include <cmath>

#include "strictmin/io/input_error.h"
#include "strictmin/mesh/generators.h"

namespace strictmin {
namespace {

Handle handle_at(int v, const Eigen::VectorXd& p) { return Handle{v, p}; }

Example bar() {
  const int nx = 64, ny = 8;
  Example ex{"bar", make_grid(nx, ny, 8.0, 1.0), {}};
  // The right end is lifted by 2 and turned by 45 degrees about its midpoint: a bend.
  const Eigen::Rotation2Dd turn(M_PI / 4);
  const Eigen::Vector2d end_mid(8.0, 0.5);
  for (int j = 0; j <= ny; ++j) {
    const int left = j * (nx + 1), right = j * (nx + 1) + nx;
    ex.handles.push_back(handle_at(left, ex.mesh.V.row(left).transpose()));
    const Eigen::Vector2d p = ex.mesh.V.row(right).transpose();
    ex.handles.push_back(handle_at(right, end_mid + turn * (p - end_mid) + Eigen::Vector2d(0.0, 2.0)));
  }
  return ex;
}

Example tetbar() {
  const int nx = 16, ny = 4, nz = 4;
  Example ex{"tetbar", make_tet_box(nx, ny, nz, 4.0, 1.0, 1.0), {}};
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const Eigen::Vector3d axis(0.0, 0.5, 0.5);
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j) {
      const int left = (k * (ny + 1) + j) * (nx + 1), right = left + nx;
      ex.handles.push_back(handle_at(left, ex.mesh.V.row(left).transpose()));
      const Eigen::Vector3d p = ex.mesh.V.row(right).transpose();
      const Eigen::Vector3d moved = axis + turn * (p - axis) + Eigen::Vector3d(0.0, 1.0, 0.0);
      ex.handles.push_back(handle_at(right, Eigen::Vector3d(p.x(), moved.y(), moved.z())));
    }
  return ex;
}

}  // namespace

Example make_square_example(int cells, double shift) {
  if (cells < 2) throw InputError("the square example needs at least 2 cells (got " + std::to_string(cells) + ")");
  Example ex{"square", make_grid(cells, cells), {}};
  const int n = cells + 1;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      if (i == 0 || j == 0 || i == n - 1 || j == n - 1)
        ex.handles.push_back(handle_at(j * n + i, ex.mesh.V.row(j * n + i).transpose()));
  const int centre = (cells / 2) * n + cells / 2;
  ex.handles.push_back(handle_at(centre, ex.mesh.V.row(centre).transpose() + Eigen::Vector2d(shift, 0.0)));
  return ex;
}

Problem example_problem(const Example& example) {
  Problem p = make_problem(example.mesh);
  p.fix(example.handles);
  return p;
}

std::vector<std::string> example_names() { return {"square", "bar", "tetbar"}; }

Example make_example(const std::string& name) {
  if (name == "square") return make_square_example(20, 0.15);
  if (name == "bar") return bar();
  if (name == "tetbar") return tetbar();
  throw InputError("unknown example '" + name + "' (known: square, bar, tetbar)");
}

}  // namespace strictmin
