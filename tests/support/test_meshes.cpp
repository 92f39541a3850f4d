#include "test_meshes.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <map>
#include <random>
#include <vector>

#include "strictmin/mesh/generators.h"
#include "strictmin/solvers/l2.h"

namespace strictmin::test_support {

Problem random_target_bar() {
  const Mesh mesh = make_grid(16, 4, 4.0, 1.0);
  Problem p = make_problem(mesh);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> angle(-0.4, 0.4);
  for (int e = 0; e < p.num_elements(); ++e) p.set_target(e, Eigen::Rotation2Dd(angle(rng)).toRotationMatrix());
  const Eigen::Matrix2d turn = Eigen::Rotation2Dd(0.5).toRotationMatrix();
  std::vector<Handle> h;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const Eigen::Vector2d x = mesh.V.row(v).transpose();
    if (x.x() == 0.0) h.push_back({v, x});
    if (x.x() == 4.0) h.push_back({v, Eigen::Vector2d(3.6, 0.8) + turn * (x - Eigen::Vector2d(4.0, 0.5))});
  }
  p.fix(h);
  return p;
}

Problem disk_with_three_pins(const Mesh& mesh) {
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

}  // namespace strictmin::test_support
