// Quasiconformal and isometric L-infinity / strict maps (solvers/conformal.h, paper Section 7).
#include <gtest/gtest.h>

#include <cmath>
#include <Eigen/LU>
#include <cstdio>
#include <random>

#include "strictmin/io/input_error.h"
#include "strictmin/mesh/generators.h"
#include "strictmin/solvers/conformal.h"
#include "strictmin/solvers/l2.h"
#include "test_meshes.h"

namespace strictmin {
namespace {

// The rectangle [0, width] x [0, 1] on a cells_x by cells_y grid with its interior vertices
// jittered (seed 5) so that the triangulation is irregular; every boundary vertex fixed at
// its image under (x, y) -> (stretch x / width, y). The extremal map is that affine map.
Problem affine_patch(double width, double stretch, Eigen::MatrixXd& start) {
  const int cx = 16, cy = 10;
  Mesh mesh = make_grid(cx, cy, width, 1.0);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.25, 0.25);
  const double hx = width / cx, hy = 1.0 / cy;
  std::vector<char> boundary(mesh.V.rows(), 0);
  for (int v = 0; v < mesh.V.rows(); ++v) {
    const double x = mesh.V(v, 0), y = mesh.V(v, 1);
    boundary[v] = x < 1e-12 || y < 1e-12 || x > width - 1e-12 || y > 1 - 1e-12;
    if (!boundary[v]) mesh.V.row(v) += Eigen::RowVector2d(u(rng) * hx, u(rng) * hy);
  }
  Problem p = make_problem(mesh);
  std::vector<Handle> handles;
  start.resize(mesh.V.rows(), 2);
  for (int v = 0; v < mesh.V.rows(); ++v) {
    const Eigen::RowVector2d image(stretch * mesh.V(v, 0) / width, mesh.V(v, 1));
    // The start: the affine map with the interior pushed off it (no flips).
    start.row(v) = boundary[v] ? image : Eigen::RowVector2d(image + 0.2 * Eigen::RowVector2d(u(rng) * hx, u(rng) * hy));
    if (boundary[v]) handles.push_back({v, Eigen::VectorXd(image.transpose())});
  }
  p.fix(handles);
  return p;
}

int flipped(const Problem& p, const Eigen::MatrixXd& X) {
  int n = 0;
  for (int e = 0; e < p.num_elements(); ++e) n += p.jacobian(e, X).determinant() <= 0;
  return n;
}

TEST(Conformal, AffinePatchQcReachesTheExtremalK) {
  Eigen::MatrixXd start;
  const Problem p = affine_patch(1.5, 3.0, start);
  ConformalOptions o;
  o.measure = Measure::Quasiconformal;
  o.bisection_tolerance = 1e-9;
  ConformalStats st;
  double last = INFINITY;
  o.progress = [&](const IterationRecord& r) {
    EXPECT_LE(r.max_distortion, last * (1 + 1e-12));  // monotone over frame iterations
    last = r.max_distortion;
  };
  const Result r = solve_conformal_linf(p, start, o, &st);
  EXPECT_EQ(r.status, SolveStatus::Solved) << r.message;
  const double K = 2.0;  // max(b/a, a/b) = 3 / 1.5
  EXPECT_NEAR(r.distortion.maxCoeff(), K, 1e-6);
  EXPECT_NEAR(r.distortion.minCoeff(), K, 1e-6);
  EXPECT_EQ(flipped(p, r.positions), 0);
  EXPECT_GT(st.bisection_steps, 0);
  EXPECT_GT(st.frame_iterations, 0);
  std::printf("qc affine: K %.12f..%.12f, %d bisection steps, %d frame iterations, %d ipm iterations\n",
              r.distortion.minCoeff(), r.distortion.maxCoeff(), st.bisection_steps, st.frame_iterations,
              st.ipm_iterations);
}

TEST(Conformal, AffinePatchIsoReachesTheExtremalS) {
  Eigen::MatrixXd start;
  const Problem p = affine_patch(1.5, 3.0, start);
  ConformalOptions o;
  o.measure = Measure::Isometric;
  o.bisection_tolerance = 1e-9;
  ConformalStats st;
  const Result r = solve_conformal_linf(p, start, o, &st);
  EXPECT_EQ(r.status, SolveStatus::Solved) << r.message;
  const double S = 2.0;  // max(b/a, a/b, 1): sigma1 = 2, sigma2 = 1
  EXPECT_NEAR(r.distortion.maxCoeff(), S, 1e-6);
  EXPECT_EQ(flipped(p, r.positions), 0);
  std::printf("iso affine: S %.12f..%.12f, %d bisection steps, %d frame iterations, %d ipm iterations\n",
              r.distortion.minCoeff(), r.distortion.maxCoeff(), st.bisection_steps, st.frame_iterations,
              st.ipm_iterations);
}

}  // namespace
}  // namespace strictmin
