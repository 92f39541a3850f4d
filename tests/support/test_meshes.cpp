#include "test_meshes.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <random>
#include <vector>

#include "strictmin/field/singularities.h"
#include "strictmin/io/mesh_io.h"
#include "strictmin/mesh/generators.h"
#include "strictmin/tasks/examples.h"
#include "strictmin/tasks/gparam.h"

namespace strictmin::test_support {

const Mesh* shared_closed_mesh(const std::string& name) {
  static std::map<std::string, Mesh> cache;
  const std::filesystem::path file = std::filesystem::path(STRICTMIN_SHARED_DATA) / "closed" / (name + ".obj");
  if (!std::filesystem::exists(file)) return nullptr;
  if (!cache.count(name)) cache[name] = read_mesh(file.string());
  return &cache[name];
}

Eigen::VectorXd sorted_down(Eigen::VectorXd values) {
  std::sort(values.data(), values.data() + values.size(), std::greater<>());
  return values;
}

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

Problem figure2(int cells, double shift) { return example_problem(make_square_example(cells, shift)); }

int figure2_centre(int cells) { return (cells / 2) * (cells + 1) + cells / 2; }

Problem handle_as_equalities(const Problem& p, int vertex) {
  Problem q = p;
  const int n = p.image_dim;
  q.fixed[vertex] = 0;
  q.eq_matrix.resize(n, static_cast<Eigen::Index>(n) * p.num_vertices);
  std::vector<Eigen::Triplet<double>> t;
  for (int r = 0; r < n; ++r) t.emplace_back(r, n * vertex + r, 1.0);
  q.eq_matrix.setFromTriplets(t.begin(), t.end());
  q.eq_rhs = p.positions.row(vertex).transpose();
  return q;
}

Problem bent_bar(int cells_x, int cells_y, double length, double height, double angle) {
  const Mesh bar = make_grid(cells_x, cells_y, length, height);
  std::vector<Handle> handles;
  for (int v = 0; v < bar.num_vertices(); ++v) {
    const double x = bar.V(v, 0);
    if (x > 0 && x < length) continue;
    const Eigen::Vector2d c(x, 0.5 * height);
    handles.push_back({v, Eigen::Rotation2Dd(x == 0 ? angle : -angle) * (bar.V.row(v).transpose() - c) + c});
  }
  Problem p = make_problem(bar);
  p.fix(handles);
  return p;
}

Problem seamless_problem(const Mesh& mesh) {
  GParamOptions o;
  o.solver.method = Method::L2;
  return global_parametrize(mesh, o, "test mesh").problem;
}

FieldComparison linf_against_smoothest(const Mesh& mesh, const std::function<void(GParamOptions&)>& vary) {
  GParamOptions o;
  o.solver.method = Method::Linf;
  FieldComparison out;
  out.smoothest = global_parametrize(mesh, o);
  vary(o);
  out.variant = global_parametrize(mesh, o);
  return out;
}

void expect_poincare_hopf(const Mesh& m, const GParamOutcome& g, const std::string& name) {
  std::vector<double> raw;
  const std::vector<int> q = vertex_indices(m, g.graph, g.frames, g.field.u, &raw);
  int sum = 0;
  double off = 0;
  for (size_t v = 0; v < q.size(); ++v) {
    sum += q[v];
    off = std::max(off, std::abs(raw[v] - q[v]));
  }
  EXPECT_EQ(sum, 4 * g.graph.euler_characteristic()) << name;
  EXPECT_LT(off / 4, 1e-9) << name;  // indices are multiples of 1/4 to 1e-9
}

}  // namespace strictmin::test_support
