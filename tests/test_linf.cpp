// The L-infinity solver (solve_linf) and its interior-point parts (solvers/socp/):
// - second-order cone algebra: NT scaling identities, arrow solves, steps to the boundary;
// - optimality: the certified lower bound meets k (relative gap 1e-8), L-inf beats L2 on
//   the paper's Figure 2 square, affine handles give k = ||A - I||_F on every element;
// - fixed bounds: met, infeasible (reported with the amount), constant elements;
// - tets, a real surface with slivers (camelhead), random rotation targets, equalities;
// - minimize_l2_among_optimal keeps k and lowers the L2 energy.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <random>

#include "strictmin/io/input_error.h"
#include "strictmin/io/mesh_io.h"
#include "strictmin/mesh/generators.h"
#include "strictmin/solvers/conformal.h"
#include "strictmin/solvers/l2.h"
#include "strictmin/solvers/linf.h"
#include "strictmin/tasks/examples.h"
#include "solvers/socp/ordering.h"
#include "solvers/socp/soc.h"
#include "solvers/cholmod_view.h"
#include "solvers/socp/split_cholesky.h"
#include "solvers/socp/supernodal_factor.h"
#include "solvers/socp/supernodal_solve.h"
#include "test_meshes.h"

using namespace strictmin;

namespace {

double relative_gap(const Result& r) {
  const double k = r.distortion.maxCoeff();
  return (k - r.lower_bound) / std::max(1.0, std::abs(k));
}

// Certified bound, gap and sanity of a solved L-infinity result (every element free).
void expect_solved(const Result& r, double gap = 1e-8) {
  ASSERT_EQ(r.status, SolveStatus::Solved) << r.message;
  ASSERT_TRUE(r.positions.allFinite());
  ASSERT_TRUE(r.distortion.allFinite());
  const double k = r.distortion.maxCoeff();
  EXPECT_LE(r.lower_bound, k + 1e-12);
  EXPECT_LE(relative_gap(r), gap) << "k = " << k << ", lower bound = " << r.lower_bound;
  ASSERT_FALSE(r.history.empty());
  EXPECT_EQ(r.history.back().iteration, r.history.size() - 1);
}

Eigen::Matrix2d rotation2(double a) {
  Eigen::Matrix2d R;
  R << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  return R;
}

std::vector<int> grid_boundary(int nx, int ny) {
  std::vector<int> b;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i)
      if (i == 0 || j == 0 || i == nx || j == ny) b.push_back(j * (nx + 1) + i);
  return b;
}


// --- cone algebra ------------------------------------------------------------------------

TEST(SocAlgebra, NesterovToddScalingIdentities) {
  std::mt19937 rng(3);
  std::normal_distribution<double> N(0.0, 1.0);
  for (int d : {1, 2, 5, 10}) {
    for (int trial = 0; trial < 20; ++trial) {
      Eigen::VectorXd s(d), z(d), u(d);
      for (int i = 0; i < d; ++i) s[i] = N(rng), z[i] = N(rng), u[i] = N(rng);
      s[0] = s.tail(d - 1).norm() + std::exp(N(rng));
      z[0] = z.tail(d - 1).norm() + 1e-3 * std::exp(N(rng));
      double beta = 0;
      Eigen::VectorXd w(d), lz(d), ls(d), a(d), b(d), c(d);
      ASSERT_TRUE(socp::nt_scaling(s.data(), z.data(), d, beta, w.data()));
      socp::apply_w(beta, w.data(), d, z.data(), lz.data());
      socp::apply_winv(beta, w.data(), d, s.data(), ls.data());
      EXPECT_LT((lz - ls).norm(), 1e-10 * ls.norm()) << "W z = W^-1 s, d = " << d;
      EXPECT_TRUE(socp::soc_interior(lz.data(), d));
      socp::apply_w(beta, w.data(), d, u.data(), a.data());
      socp::apply_winv(beta, w.data(), d, a.data(), b.data());
      EXPECT_LT((b - u).norm(), 1e-10 * u.norm());
      socp::apply_winv(beta, w.data(), d, u.data(), a.data());
      socp::apply_winv(beta, w.data(), d, a.data(), b.data());
      socp::apply_winv2(beta, w.data(), d, u.data(), c.data());
      EXPECT_LT((b - c).norm(), 1e-10 * b.norm()) << "W^-2 = (W^-1)^2";
      // Arrow solve inverts the Jordan product.
      socp::jordan_product(lz.data(), u.data(), d, a.data());
      socp::arrow_solve(lz.data(), a.data(), d, b.data());
      EXPECT_LT((b - u).norm(), 1e-9 * u.norm());
      // The longest step lands on the boundary.
      const double alpha = socp::max_step(s.data(), u.data(), d);
      if (std::isfinite(alpha)) {
        const Eigen::VectorXd e = s + alpha * u;
        EXPECT_NEAR(e[0] - e.tail(d - 1).norm(), 0.0, 1e-9 * (1 + e.norm()));
        const Eigen::VectorXd inside = s + 0.999 * alpha * u;
        EXPECT_TRUE(socp::soc_interior(inside.data(), d));
      } else {
        const Eigen::VectorXd far = s + 1e6 * u;
        EXPECT_GE(far[0], far.tail(d - 1).norm() * (1 - 1e-12));
      }
    }
  }
}

// --- optimality --------------------------------------------------------------------------

TEST(Linf, Figure2SquareBeatsL2WithCertifiedGap) {
  const Problem p = test_support::figure2(20, 0.2);
  const Result l2 = solve_l2(p);
  ASSERT_TRUE(l2.ok());
  int calls = 0;
  LinfOptions o;
  o.progress = [&](const IterationRecord&) { ++calls; };
  const Result r = solve_linf(p, o);
  expect_solved(r);
  EXPECT_LT(r.distortion.maxCoeff(), l2.distortion.maxCoeff() - 1e-3);
  EXPECT_EQ(calls, static_cast<int>(r.history.size()));
  EXPECT_LE(r.iterations, 40);
  std::printf("figure 2 (20x20): k = %.10f (L2 max %.6f), bound %.10f, %d iterations\n", r.distortion.maxCoeff(),
              l2.distortion.maxCoeff(), r.lower_bound, r.iterations);
}

TEST(Linf, AffineHandlesGiveTheAffineMapAndItsDistortion) {
  // Every element must have J = A (the mean of J over the square is A, Jensen), so
  // k = ||A - I||_F on every element, certified.
  const int cells = 8;
  const Mesh mesh = make_grid(cells, cells);
  Problem p = make_problem(mesh);
  Eigen::Matrix2d A;
  A << 1.3, 0.4, -0.2, 0.8;
  const Eigen::Vector2d b(0.1, -0.3);
  std::vector<Handle> handles;
  for (int v : grid_boundary(cells, cells)) handles.push_back({v, A * mesh.V.row(v).transpose() + b});
  p.fix(handles);
  const Result r = solve_linf(p);
  expect_solved(r);
  const double expected = (A - Eigen::Matrix2d::Identity()).norm();
  EXPECT_NEAR(r.distortion.maxCoeff(), expected, 1e-7 * expected);
  EXPECT_NEAR(r.distortion.minCoeff(), expected, 1e-6 * expected);
  EXPECT_GE(r.lower_bound, expected * (1 - 1e-7));
  for (int v = 0; v < mesh.num_vertices(); ++v)
    EXPECT_LT((r.positions.row(v).transpose() - (A * mesh.V.row(v).transpose() + b)).norm(), 1e-6);
}

TEST(Linf, AffineHandlesOnTets) {
  const Mesh mesh = make_tet_box(3, 3, 3);
  Problem p = make_problem(mesh);
  Eigen::Matrix3d A;
  A << 1.1, 0.2, 0.0, -0.1, 0.9, 0.3, 0.05, 0.0, 1.2;
  std::vector<Handle> handles;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const Eigen::Vector3d q = mesh.V.row(v).transpose();
    if (q.minCoeff() < 1e-12 || q.maxCoeff() > 1 - 1e-12) handles.push_back({v, A * q});
  }
  p.fix(handles);
  const Result r = solve_linf(p);
  expect_solved(r);
  const double expected = (A - Eigen::Matrix3d::Identity()).norm();
  EXPECT_NEAR(r.distortion.maxCoeff(), expected, 1e-7 * expected);
  EXPECT_NEAR(r.distortion.minCoeff(), expected, 1e-6 * expected);
}

TEST(Linf, TetBoxWithHandles) {
  const int n = 4;
  const Mesh mesh = make_tet_box(n, n, n);
  Problem p = make_problem(mesh);
  std::vector<Handle> handles;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const int k = v / ((n + 1) * (n + 1));
    if (k == 0) handles.push_back({v, mesh.V.row(v).transpose()});
    if (k == n) handles.push_back({v, mesh.V.row(v).transpose() + Eigen::Vector3d(0.4, 0.1, 0.2)});
  }
  p.fix(handles);
  const Result l2 = solve_l2(p);
  const Result r = solve_linf(p);
  expect_solved(r);
  EXPECT_LE(r.distortion.maxCoeff(), l2.distortion.maxCoeff() + 1e-9);
  std::printf("tet box %d^3 (%d tets): k = %.8f, %d iterations\n", n, p.num_elements(), r.distortion.maxCoeff(),
              r.iterations);
}

TEST(Linf, RandomRotationTargetsIterationCountsStayFlat) {
  std::vector<int> iterations;
  for (int size : {8, 16, 32}) {
    const Mesh mesh = make_grid(4 * size, size, 4.0, 1.0);
    Problem p = make_problem(mesh);
    std::mt19937 rng(size);
    std::uniform_real_distribution<double> angle(-0.6, 0.6);
    for (int e = 0; e < p.num_elements(); ++e) p.set_target(e, rotation2(angle(rng)));
    std::vector<Handle> handles;
    for (int v = 0; v < mesh.num_vertices(); ++v) {
      const int i = v % (4 * size + 1);
      if (i == 0) handles.push_back({v, mesh.V.row(v).transpose()});
      if (i == 4 * size) handles.push_back({v, mesh.V.row(v).transpose() + Eigen::Vector2d(0.5, 1.0)});
    }
    p.fix(handles);
    const Result r = solve_linf(p);
    expect_solved(r);
    iterations.push_back(r.iterations);
    std::printf("bar %dx%d (%d triangles), random rotations: k = %.8f, %d iterations, %.3f s\n", 4 * size, size,
                p.num_elements(), r.distortion.maxCoeff(), r.iterations, r.time_s);
  }
  for (int it : iterations) EXPECT_LE(it, 40);
}

TEST(Linf, ProgressAndHistory) {
  const Problem p = test_support::figure2(6, 0.1);
  std::vector<IterationRecord> seen;
  LinfOptions o;
  o.progress = [&](const IterationRecord& r) { seen.push_back(r); };
  const Result r = solve_linf(p, o);
  expect_solved(r);
  ASSERT_EQ(seen.size(), r.history.size());
  for (size_t i = 0; i < seen.size(); ++i) {
    EXPECT_EQ(seen[i].iteration, static_cast<int>(i));
    EXPECT_LE(seen[i].lower_bound, r.distortion.maxCoeff() + 1e-12) << "every bound is certified";
    if (i > 0) {
      EXPECT_GE(seen[i].time_s, seen[i - 1].time_s);
    }
  }
  EXPECT_NEAR(r.history.back().max_distortion, r.distortion.maxCoeff(), 1e-12);
}

// --- fixed bounds and constant elements -------------------------------------------------

TEST(Linf, FixedBoundsAreMetAndLowerTheRest) {
  // One step of the strict-minimizer algorithm: bound the elements at the maximum, minimize
  // the rest.
  const Problem p = test_support::figure2(10, 0.15);
  const Result r1 = solve_linf(p);
  expect_solved(r1);
  const double k1 = r1.distortion.maxCoeff();
  LinfOptions o;
  o.element_bounds = Eigen::VectorXd::Constant(p.num_elements(), -1.0);
  int bounded = 0;
  for (int e = 0; e < p.num_elements(); ++e)
    if (r1.distortion[e] >= k1 - 1e-6) {
      o.element_bounds[e] = k1;
      ++bounded;
    }
  ASSERT_GT(bounded, 0);
  ASSERT_LT(bounded, p.num_elements());
  Problem p2 = p;
  p2.positions = r1.positions;  // start from the previous map (meets the bounds)
  const Result r2 = solve_linf(p2, o);
  ASSERT_EQ(r2.status, SolveStatus::Solved) << r2.message;
  double k2 = 0;
  for (int e = 0; e < p.num_elements(); ++e) {
    if (o.element_bounds[e] >= 0)
      EXPECT_LE(r2.distortion[e], k1 + 1e-7);
    else
      k2 = std::max(k2, r2.distortion[e]);
  }
  EXPECT_LE(k2, k1 + 1e-9);
  EXPECT_LE(r2.lower_bound, k2 + 1e-12);
  EXPECT_LE(k2 - r2.lower_bound, 1e-6 * std::max(1.0, k2));
  std::printf("bounded %d elements at k1 = %.8f: k2 = %.8f (bound %.8f), %d iterations\n", bounded, k1, k2,
              r2.lower_bound, r2.iterations);
}

// The dual multipliers of the certificate: non-negative, summing to 1 over the free
// elements, small where an element is well below k (complementary slackness), and the
// weak-duality inequality sum lambda_T D_T(x) + sum_bounded lambda_T (D_T(x) - k_T) >= bound
// holds for any map x, here random perturbations of the optimum and the L2 map.
TEST(Linf, MultipliersCertifyTheBoundForEveryMap) {
  const Problem p = test_support::figure2(10, 0.15);
  const Result r1 = solve_linf(p);
  LinfOptions o;
  o.element_bounds = Eigen::VectorXd::Constant(p.num_elements(), -1.0);
  const double k1 = r1.distortion.maxCoeff();
  for (int e = 0; e < p.num_elements(); ++e)
    if (r1.distortion[e] >= k1 - 1e-6) o.element_bounds[e] = k1 * 1.02;
  for (const LinfOptions& options : {LinfOptions{}, o}) {
    const Result r = solve_linf(p, options);
    ASSERT_EQ(r.status, SolveStatus::Solved) << r.message;
    ASSERT_EQ(r.multipliers.size(), p.num_elements());
    const auto bounded = [&](int e) { return options.element_bounds.size() > 0 && options.element_bounds[e] >= 0; };
    double sum_free = 0, k = 0;
    for (int e = 0; e < p.num_elements(); ++e) {
      EXPECT_GE(r.multipliers[e], 0.0) << e;
      if (!bounded(e)) {
        sum_free += r.multipliers[e];
        k = std::max(k, r.distortion[e]);
      }
    }
    EXPECT_NEAR(sum_free, 1.0, 1e-12);
    EXPECT_LE(k - r.lower_bound, 1e-8 * std::max(1.0, k));
    for (int e = 0; e < p.num_elements(); ++e) {
      if (!bounded(e) && r.distortion[e] < k - 1e-2) {
        EXPECT_LT(r.multipliers[e], 1e-4) << e;
      }
    }
    std::mt19937 rng(5);
    std::normal_distribution<double> noise(0.0, 0.05);
    const Eigen::VectorXd x0 = p.free_dofs(r.positions);
    std::vector<Eigen::VectorXd> maps{x0, p.free_dofs(solve_l2(p).positions)};
    for (int trial = 0; trial < 20; ++trial) {
      Eigen::VectorXd x = x0;
      for (Eigen::Index i = 0; i < x.size(); ++i) x[i] += noise(rng);
      maps.push_back(x);
    }
    for (const Eigen::VectorXd& x : maps) {
      const Eigen::MatrixXd X = p.with_free_dofs(x);
      double lhs = 0;
      for (int e = 0; e < p.num_elements(); ++e) {
        const double d = (p.jacobian(e, X) - p.target(e)).norm();
        lhs += r.multipliers[e] * (bounded(e) ? d - options.element_bounds[e] : d);
      }
      EXPECT_GE(lhs, r.lower_bound - 1e-12);
    }
  }
}

TEST(Linf, InfeasibleBoundsAreReportedWithTheAmount) {
  // Every element bounded by 0.05: the centre moves 0.2 while the boundary (0.5 away) stays,
  // so |J - I| >= 0.4 somewhere. Phase 1 certifies it.
  const Problem p = test_support::figure2(8, 0.2);
  LinfOptions o;
  o.element_bounds = Eigen::VectorXd::Constant(p.num_elements(), 0.05);
  const Result r = solve_linf(p, o);
  EXPECT_EQ(r.status, SolveStatus::Infeasible) << r.message;
  EXPECT_NE(r.message.find("cannot all be met"), std::string::npos) << r.message;
  EXPECT_TRUE(r.positions.allFinite());
  // A bound of zero on a single element that must deform.
  LinfOptions o2;
  o2.element_bounds = Eigen::VectorXd::Constant(p.num_elements(), -1.0);
  const Result free = solve_linf(p);
  int worst = 0;
  free.distortion.maxCoeff(&worst);
  Problem tiny = test_support::figure2(2, 0.2);  // every vertex fixed: all elements constant
  LinfOptions o3;
  o3.element_bounds = Eigen::VectorXd::Constant(tiny.num_elements(), 0.0);
  const Result r3 = solve_linf(tiny, o3);
  EXPECT_EQ(r3.status, SolveStatus::Infeasible);
  EXPECT_NE(r3.message.find("every vertex fixed"), std::string::npos) << r3.message;
}

TEST(Linf, ConstantElementsBoundK) {
  // The left quarter of a bar is entirely fixed, with a shear: its elements are constants
  // with D = 0.3 (k >= 0.3); the right end is moved a little.
  const int nx = 16, ny = 4;
  const Mesh mesh = make_grid(nx, ny, 4.0, 1.0);
  Problem p = make_problem(mesh);
  std::vector<Handle> handles;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const int i = v % (nx + 1);
    const Eigen::Vector2d q = mesh.V.row(v).transpose();
    if (i <= 4) handles.push_back({v, Eigen::Vector2d(q.x() + 0.3 * q.y(), q.y())});
    if (i == nx) handles.push_back({v, q + Eigen::Vector2d(0.05, 0.0)});
  }
  p.fix(handles);
  const Result r = solve_linf(p);
  expect_solved(r);
  EXPECT_NEAR(r.distortion.maxCoeff(), 0.3, 1e-8);
  EXPECT_NEAR(r.lower_bound, 0.3, 1e-8);
  // Every vertex fixed: nothing to solve, k is the constants' maximum.
  Problem all = make_problem(make_grid(3, 3));
  std::vector<Handle> every;
  for (int v = 0; v < all.num_vertices; ++v) every.push_back({v, all.positions.row(v).transpose() * 1.1});
  all.fix(every);
  const Result r2 = solve_linf(all);
  EXPECT_EQ(r2.status, SolveStatus::Solved) << r2.message;
  EXPECT_NEAR(r2.distortion.maxCoeff(), 0.1 * std::sqrt(2.0), 1e-12);
}

TEST(Linf, RejectsBoundsOfTheWrongSize) {
  const Problem p = test_support::figure2(4, 0.1);
  LinfOptions o;
  o.element_bounds = Eigen::VectorXd::Constant(3, 1.0);
  EXPECT_THROW(solve_linf(p, o), InputError);
}

// Bounds beyond 1e100 overflowed the interior-point method's squared slacks (1e150 stalled
// at iteration 10, 1e300 at iteration 1): they are refused with the element named, while a
// bound of 1e100 is a loose bound and leaves the free elements' optimum where it was.
TEST(Linf, HugeAndNonFiniteBoundsAreRefusedLooseOnesAreInactive) {
  const Problem p = test_support::figure2(10, 0.15);
  const Result free = solve_linf(p);
  expect_solved(free);
  LinfOptions o;
  o.element_bounds = Eigen::VectorXd::Constant(p.num_elements(), -1.0);
  for (int e = 0; e < p.num_elements(); e += 3) o.element_bounds[e] = 1e100;
  const Result loose = solve_linf(p, o);
  ASSERT_EQ(loose.status, SolveStatus::Solved) << loose.message;
  double k = 0;  // the bounded elements may end above k: their bound is 1e100
  for (int e = 0; e < p.num_elements(); ++e)
    if (o.element_bounds[e] < 0) k = std::max(k, loose.distortion[e]);
  EXPECT_NEAR(k, free.distortion.maxCoeff(), 1e-7);
  EXPECT_NEAR(loose.lower_bound, free.lower_bound, 1e-7);
  for (double bad : {1e150, 1e300, double(INFINITY), double(NAN)}) {
    o.element_bounds[6] = bad;
    try {
      solve_linf(p, o);
      ADD_FAILURE() << bad << " accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("element 6's bound"), std::string::npos) << e.what();
    }
    ConformalOptions c;
    c.element_bounds = o.element_bounds;
    EXPECT_THROW(solve_conformal_linf(p, p.positions, c), InputError) << bad;
  }
}

TEST(Linf, UndeterminedMapIsANumericalError) {
  const Problem p = make_problem(make_grid(4, 4));  // nothing fixed
  const Result r = solve_linf(p);
  EXPECT_EQ(r.status, SolveStatus::NumericalError);
  EXPECT_NE(r.message.find("not determined"), std::string::npos) << r.message;
}

// --- equalities and the L2 choice among minimizers -----------------------------------------

TEST(Linf, EqualityConstraintsActLikeHandles) {
  // Fixing the centre by two equality rows gives the same optimum as fixing it by a handle.
  const int cells = 10;
  const Problem with_handle = test_support::figure2(cells, 0.2);
  const int centre = test_support::figure2_centre(cells);
  const Problem with_eq = test_support::handle_as_equalities(with_handle, centre);
  const Result a = solve_linf(with_handle);
  const Result b = solve_linf(with_eq);
  expect_solved(a);
  expect_solved(b, 1e-7);
  EXPECT_NEAR(a.distortion.maxCoeff(), b.distortion.maxCoeff(), 1e-7);
  EXPECT_LT((b.positions.row(centre) - with_handle.positions.row(centre)).norm(), 1e-8);
}

TEST(Linf, MinimizeL2AmongOptimalKeepsKAndLowersTheEnergy) {
  const Problem p = test_support::figure2(12, 0.2);
  const Result r1 = solve_linf(p);
  expect_solved(r1);
  LinfOptions o;
  o.minimize_l2_among_optimal = true;
  const Result r2 = solve_linf(p, o);
  ASSERT_EQ(r2.status, SolveStatus::Solved) << r2.message;
  const double k1 = r1.distortion.maxCoeff();
  EXPECT_LE(r2.distortion.maxCoeff(), k1 + o.l2_slack * std::max(1.0, k1) + 1e-9);
  auto energy = [&](const Result& r) { return (p.weights.array() * r.distortion.array().square()).sum(); };
  EXPECT_LE(energy(r2), energy(r1) + 1e-12);
  EXPECT_EQ(r2.lower_bound, r2.lower_bound);  // kept from the L-infinity solve
  // The message describes the map returned, not only the L-infinity solve before it.
  char maximum[32];
  std::snprintf(maximum, sizeof maximum, "(its maximum %g)", r2.distortion.maxCoeff());
  EXPECT_NE(r2.message.find("then the least L2 map among those within 1e-06"), std::string::npos) << r2.message;
  EXPECT_NE(r2.message.find(maximum), std::string::npos) << r2.message;
  std::printf("L2 among optimal: energy %.8f -> %.8f, k %.10f -> %.10f, %d -> %d iterations\n", energy(r1), energy(r2),
              k1, r2.distortion.maxCoeff(), r1.iterations, r2.iterations);
}

// --- a real surface ------------------------------------------------------------------------

TEST(Linf, CamelheadSurfaceWithThreeFixedVertices) {
  const std::string path = std::string(STRICTMIN_SHARED_DATA) + "/disk/camelhead.obj";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is absent";
  const Mesh mesh = read_mesh(path);
  // Per-triangle 2D frames, identity targets; three boundary vertices held where an L2 map
  // with one pinned vertex puts them.
  const Problem p = three_pin_disk_problem(mesh);
  ASSERT_EQ(p.num_free(), mesh.num_vertices() - 3);
  Problem pinned = make_problem(mesh);
  pinned.fix({{0, Eigen::Vector2d::Zero()}});
  const Result l2 = solve_l2(pinned);
  ASSERT_TRUE(l2.ok()) << l2.message;
  const Result r = solve_linf(p);
  // On this graded mesh the certified gap ends near the 1e-8 tolerance: 2.3e-8 on some
  // processors (almost-solved, docs/linf.md "Accuracy"), below it on others. Either way the
  // status must say which, and the gap stay within the almost-solved band.
  ASSERT_TRUE(r.status == SolveStatus::Solved || r.status == SolveStatus::AlmostSolved) << r.message;
  if (r.status == SolveStatus::Solved) {
    EXPECT_LE(relative_gap(r), 1e-8) << r.message;
  }
  ASSERT_TRUE(r.positions.allFinite());
  ASSERT_TRUE(r.distortion.allFinite());
  EXPECT_LE(r.lower_bound, r.distortion.maxCoeff());
  EXPECT_LE(relative_gap(r), 1e-6) << r.message;
  EXPECT_LT(r.distortion.maxCoeff(), l2.distortion.maxCoeff());
  std::printf("camelhead (%d triangles): k = %.10f, bound %.10f, %d iterations, %.2f s %s\n", p.num_elements(),
              r.distortion.maxCoeff(), r.lower_bound, r.iterations, r.time_s, r.message.c_str());
}

}  // namespace

// The normal equations of large problems are factorised in two halves split by a vertex
// separator (socp/split_cholesky.h): same solution as one dense factorisation, also with
// entries spanning many orders of magnitude (as near the interior-point optimum).
TEST(SplitCholesky, SolvesLikeADenseFactorisation) {
  const int g = 30, n = 2, V = g * g, N = n * V;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<int> offset(V + 1, 0), adj;
  std::vector<std::vector<int>> nb(V);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(N, N);
  auto couple = [&](int a, int b, double scale) {  // PSD 2n x 2n block on the pair (a, b)
    Eigen::MatrixXd M(2 * n, 2 * n);
    for (int i = 0; i < M.size(); ++i) M.data()[i] = u(rng);
    const Eigen::MatrixXd P = scale * M * M.transpose();
    const int idx[2] = {a, b};
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) A.block(n * idx[i], n * idx[j], n, n) += P.block(n * i, n * j, n, n);
    nb[a].push_back(b);
    nb[b].push_back(a);
  };
  for (int y = 0; y < g; ++y)
    for (int x = 0; x < g; ++x) {
      const int v = y * g + x;
      const double scale = std::pow(10.0, 8.0 * (u(rng) + 1.0));  // 1 .. 1e16
      if (x + 1 < g) couple(v, v + 1, scale);
      if (y + 1 < g) couple(v, v + g, 1.0);
      if (x + 1 < g && y + 1 < g) couple(v, v + g + 1, 1.0);
    }
  A.diagonal().array() += 1e-3;
  for (int v = 0; v < V; ++v) {
    std::sort(nb[v].begin(), nb[v].end());
    nb[v].erase(std::unique(nb[v].begin(), nb[v].end()), nb[v].end());
    offset[v + 1] = offset[v] + static_cast<int>(nb[v].size());
    adj.insert(adj.end(), nb[v].begin(), nb[v].end());
  }
  const std::vector<int> part = socp::vertex_bisection(offset, adj);
  ASSERT_EQ(static_cast<int>(part.size()), V);
  int sizes[3];
  const std::vector<int> order = socp::bisected_ordering(offset, adj, part, sizes);
  ASSERT_EQ(sizes[0] + sizes[1] + sizes[2], V);
  EXPECT_GT(sizes[0], V / 4);
  EXPECT_GT(sizes[1], V / 4);
  EXPECT_LT(sizes[2], 3 * g);
  // Dofs in the bisected order, the upper triangle of the permuted matrix.
  std::vector<int> dof_order;
  for (int v : order)
    for (int r = 0; r < n; ++r) dof_order.push_back(n * v + r);
  Eigen::MatrixXd Ap(N, N);
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) Ap(i, j) = A(dof_order[i], dof_order[j]);
  Eigen::SparseMatrix<double> upper = Ap.triangularView<Eigen::Upper>().toDenseMatrix().sparseView();
  upper.makeCompressed();
  socp::SplitCholesky split;
  ASSERT_TRUE(split.analyze(upper, n * sizes[0], n * sizes[1]));
  ASSERT_TRUE(split.factorize(upper.valuePtr()));
  const Eigen::VectorXd b = Eigen::VectorXd::NullaryExpr(N, [&] { return u(rng); });
  Eigen::VectorXd x;
  split.solve(b, x);
  const Eigen::VectorXd expected = Ap.llt().solve(b);
  EXPECT_LE((Ap * x - b).norm(), 1e-6 * b.norm());
  EXPECT_LE((x - expected).norm(), 1e-6 * expected.norm());
  // Two right-hand sides at once: each as solved alone, to round-off.
  const Eigen::VectorXd b1 = Eigen::VectorXd::NullaryExpr(N, [&] { return u(rng); });
  Eigen::VectorXd x1, y0, y1;
  split.solve(b1, x1);
  split.solve2(b, b1, y0, y1);
  EXPECT_LE((y0 - x).norm(), 1e-12 * x.norm());
  EXPECT_LE((y1 - x1).norm(), 1e-12 * x1.norm());
  // A matrix that couples the two parts is refused.
  Eigen::MatrixXd coupled = Ap;
  coupled(0, N - n * sizes[2] - 1) = coupled(N - n * sizes[2] - 1, 0) = 1e-3;
  Eigen::SparseMatrix<double> upper2 = coupled.triangularView<Eigen::Upper>().toDenseMatrix().sparseView();
  upper2.makeCompressed();
  socp::SplitCholesky refused;
  EXPECT_FALSE(refused.analyze(upper2, n * sizes[0], n * sizes[1]));
}

// A symmetric positive definite matrix whose CHOLMOD supernodes have many widths (3 dofs per
// vertex of a g x g grid, wide coupling) and entries over 12 orders of magnitude: its upper
// triangle.
Eigen::SparseMatrix<double> wide_supernode_matrix(int g) {
  const int n = 3, V = g * g, N = n * V;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::Triplet<double>> triplets;
  for (int y = 0; y < g; ++y)
    for (int x = 0; x < g; ++x) {
      const int v = y * g + x;
      for (int w : {v + 1, v + g, v + g + 1, v + 2 * g - 1}) {  // PSD blocks on vertex pairs
        if (w >= V || (w == v + 1 && x + 1 >= g)) continue;
        Eigen::MatrixXd M(2 * n, 2 * n);
        for (int i = 0; i < M.size(); ++i) M.data()[i] = u(rng);
        const Eigen::MatrixXd P = std::pow(10.0, 6.0 * (u(rng) + 1.0)) * M * M.transpose();
        const int idx[2] = {v, w};
        for (int a = 0; a < 2 * n; ++a)
          for (int b = 0; b < 2 * n; ++b) triplets.emplace_back(n * idx[a / n] + a % n, n * idx[b / n] + b % n, P(a, b));
      }
    }
  for (int d = 0; d < N; ++d) triplets.emplace_back(d, d, 1e-3);
  Eigen::SparseMatrix<double> A(N, N);
  A.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::SparseMatrix<double> upper = A.triangularView<Eigen::Upper>();
  upper.makeCompressed();
  return upper;
}

// Our one-column substitutions with a CHOLMOD supernodal factor (socp/supernodal_solve.h)
// give what cholmod_solve gives.
TEST(SupernodalSolve, MatchesCholmodSolve) {
  Eigen::SparseMatrix<double> upper = wide_supernode_matrix(25);
  const int N = static_cast<int>(upper.rows());
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  cholmod_common common;
  cholmod_start(&common);
  common.supernodal = CHOLMOD_SUPERNODAL;
  cholmod_sparse view = cholmod_view(upper, 1);
  cholmod_factor* L = cholmod_analyze(&view, &common);
  ASSERT_NE(L, nullptr);
  cholmod_factorize(&view, L, &common);
  ASSERT_EQ(common.status, CHOLMOD_OK);
  ASSERT_TRUE(socp::supports_supernodal_solve(*L));
  int widest = 0;
  for (size_t k = 0; k < L->nsuper; ++k)
    widest = std::max(widest, static_cast<const int*>(L->super)[k + 1] - static_cast<const int*>(L->super)[k]);
  EXPECT_GE(widest, 6) << "the test should have wide supernodes";
  Eigen::VectorXd b = Eigen::VectorXd::NullaryExpr(N, [&] { return u(rng); });
  for (int sys : {CHOLMOD_L, CHOLMOD_Lt}) {
    cholmod_dense bd{};
    bd.nrow = bd.d = bd.nzmax = N;
    bd.ncol = 1;
    bd.x = b.data();
    bd.xtype = CHOLMOD_REAL;
    bd.dtype = CHOLMOD_DOUBLE;
    cholmod_dense* expected = cholmod_solve(sys, L, &bd, &common);
    ASSERT_NE(expected, nullptr);
    Eigen::VectorXd ours = b;
    if (sys == CHOLMOD_L)
      socp::supernodal_forward(*L, ours.data());
    else
      socp::supernodal_backward(*L, ours.data());
    const Eigen::Map<Eigen::VectorXd> e(static_cast<double*>(expected->x), N);
    EXPECT_LE((ours - e).norm(), 1e-12 * e.norm()) << (sys == CHOLMOD_L ? "forward" : "backward");
    cholmod_free_dense(&expected, &common);
  }
  // Two right-hand sides interleaved: each as substituted alone.
  const Eigen::VectorXd c = Eigen::VectorXd::NullaryExpr(N, [&] { return u(rng); });
  for (int sys : {CHOLMOD_L, CHOLMOD_Lt}) {
    Eigen::VectorXd one_b = b, one_c = c, both(2 * N);
    for (int i = 0; i < N; ++i) both[2 * i] = b[i], both[2 * i + 1] = c[i];
    if (sys == CHOLMOD_L) {
      socp::supernodal_forward(*L, one_b.data());
      socp::supernodal_forward(*L, one_c.data());
      socp::supernodal_forward2(*L, both.data());
    } else {
      socp::supernodal_backward(*L, one_b.data());
      socp::supernodal_backward(*L, one_c.data());
      socp::supernodal_backward2(*L, both.data());
    }
    double diff = 0;
    for (int i = 0; i < N; ++i) diff = std::max({diff, std::abs(both[2 * i] - one_b[i]), std::abs(both[2 * i + 1] - one_c[i])});
    EXPECT_LE(diff, 1e-12 * std::max(one_b.lpNorm<Eigen::Infinity>(), one_c.lpNorm<Eigen::Infinity>()))
        << (sys == CHOLMOD_L ? "forward2" : "backward2");
  }
  cholmod_free_factor(&L, &common);
  cholmod_finish(&common);
}

// Our numeric factorisation on CHOLMOD's analysis (socp/supernodal_factor.h) gives CHOLMOD's
// factor: narrow updates by our loops, wide ones by BLAS (the grid's top separators are
// supernodes of 75 and more columns). A matrix that is not positive definite is reported.
TEST(SupernodalFactor, MatchesCholmodFactorAndDetectsIndefinite) {
  Eigen::SparseMatrix<double> upper = wide_supernode_matrix(40);
  const int N = static_cast<int>(upper.rows());
  cholmod_common common;
  cholmod_start(&common);
  common.supernodal = CHOLMOD_SUPERNODAL;
  cholmod_sparse view = cholmod_view(upper, 1);
  cholmod_factor* expected = cholmod_analyze(&view, &common);
  cholmod_factor* ours = cholmod_analyze(&view, &common);
  ASSERT_NE(expected, nullptr);
  ASSERT_NE(ours, nullptr);
  cholmod_factorize(&view, expected, &common);
  ASSERT_EQ(common.status, CHOLMOD_OK);
  int widest = 0;
  for (size_t k = 0; k < ours->nsuper; ++k)
    widest = std::max(widest, static_cast<const int*>(ours->super)[k + 1] - static_cast<const int*>(ours->super)[k]);
  EXPECT_GE(widest, 48) << "the test should reach the BLAS paths";
  // The upper triangle's entries as lower-triangle entries of the permuted matrix.
  const int* perm = static_cast<const int*>(ours->Perm);
  std::vector<int> iperm(N), rows, cols;
  for (int k = 0; k < N; ++k) iperm[perm[k]] = k;
  for (int c = 0; c < N; ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(upper, c); it; ++it) {
      const int pr = iperm[it.row()], pc = iperm[c];
      rows.push_back(std::max(pr, pc));
      cols.push_back(std::min(pr, pc));
    }
  socp::SupernodalFactor factor;
  ASSERT_TRUE(factor.setup(ours, &common, rows, cols));
  ASSERT_TRUE(factor.factorize(upper.valuePtr()));
  ASSERT_EQ(ours->xsize, expected->xsize);
  const Eigen::Map<const Eigen::VectorXd> lo(static_cast<const double*>(ours->x), ours->xsize);
  const Eigen::Map<const Eigen::VectorXd> le(static_cast<const double*>(expected->x), expected->xsize);
  // CHOLMOD leaves the strict upper triangle of each diagonal block as it finds it: compare
  // the lower part (diagonal blocks' lower triangles and the blocks below).
  double diff = 0, scale = 0;
  const int* super = static_cast<const int*>(ours->super);
  const int* pi = static_cast<const int*>(ours->pi);
  const int* px = static_cast<const int*>(ours->px);
  for (size_t k = 0; k < ours->nsuper; ++k) {
    const int cols_k = super[k + 1] - super[k], rows_k = pi[k + 1] - pi[k];
    for (int c = 0; c < cols_k; ++c)
      for (int r = c; r < rows_k; ++r) {
        const long at = px[k] + static_cast<long>(c) * rows_k + r;
        diff = std::max(diff, std::abs(lo[at] - le[at]));
        scale = std::max(scale, std::abs(le[at]));
      }
  }
  EXPECT_LE(diff, 1e-10 * scale);
  // Indefinite: one diagonal entry made negative.
  Eigen::SparseMatrix<double> bad = upper;
  bad.coeffRef(N / 2, N / 2) = -1.0;
  EXPECT_FALSE(factor.factorize(bad.valuePtr()));
  cholmod_free_factor(&expected, &common);
  cholmod_free_factor(&ours, &common);
  cholmod_finish(&common);
}

// Above 20,000 free dofs the solver splits the normal equations (socp/split_cholesky.h).
TEST(Linf, LargeSquareSolvedWithSplitFactorisation) {
  const Problem p = test_support::figure2(102, 0.2);  // 101^2 free vertices: 20,402 dofs
  ASSERT_GE(p.num_free() * 2, 20000);
  const Result r = solve_linf(p);
  expect_solved(r);
  EXPECT_NEAR(r.distortion.maxCoeff(), 0.4, 0.01);
  EXPECT_LE(r.iterations, 20);
}
