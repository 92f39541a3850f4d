#include "strictmin/tasks/examples.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>

#include "strictmin/io/input_error.h"
#include "strictmin/mesh/generators.h"
#include "strictmin/solvers/l2.h"

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

Problem three_pin_disk_problem(const Mesh& mesh) {
  Problem p = make_problem(mesh);
  std::map<std::pair<int, int>, int> edges;
  for (int f = 0; f < mesh.num_elements(); ++f)
    for (int j = 0; j < 3; ++j) {
      const int a = mesh.F(f, j), c = mesh.F(f, (j + 1) % 3);
      ++edges[{std::min(a, c), std::max(a, c)}];
    }
  std::vector<int> boundary;
  for (const auto& [e, count] : edges)
    if (count == 1) boundary.push_back(e.first);
  std::sort(boundary.begin(), boundary.end());
  boundary.erase(std::unique(boundary.begin(), boundary.end()), boundary.end());
  if (boundary.size() < 3) return p;
  Problem pinned = p;
  pinned.fix({{boundary[0], Eigen::Vector2d::Zero()}});
  const Result l2 = solve_l2(pinned);
  std::vector<Handle> handles;
  for (size_t i : {size_t{0}, boundary.size() / 3, 2 * boundary.size() / 3})
    handles.push_back({boundary[i], l2.positions.row(boundary[i]).transpose()});
  p.fix(handles);
  return p;
}

}  // namespace strictmin
