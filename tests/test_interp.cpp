// Shape interpolation (paper Section 5.4; docs/maths.md section 6): t = 0 and 1 give
// the poses, a rigidly moved target changes the frames only by a rigid motion, rotations are
// unwrapped so a bar turned by more than 180 degrees does not fold, bad pairs are refused.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <numbers>

#include "strictmin/io/input_error.h"
#include "strictmin/io/mesh_io.h"
#include "strictmin/measures/polar.h"
#include "strictmin/mesh/generators.h"
#include "strictmin/problem/problem.h"
#include "strictmin/solvers/local_global.h"
#include "strictmin/tasks/interp.h"
#include "strictmin/tasks/rotation_unwrap.h"

using namespace strictmin;

namespace {

constexpr double kPi = std::numbers::pi;

// A 10 by 1 bar rolled onto an arc turning by `turn` radians (isometric along the centre
// line, so the target is a bent bar with mild stretch across).
Mesh bent_bar(const Mesh& bar, double turn) {
  Mesh out = bar;
  const double length = 10.0, radius = length / turn;
  for (int v = 0; v < bar.num_vertices(); ++v) {
    const double phi = bar.V(v, 0) / length * turn, r = radius - (bar.V(v, 1) - 0.5);
    out.V(v, 0) = r * std::sin(phi);
    out.V(v, 1) = radius - r * std::cos(phi);
  }
  return out;
}

// Residual of the best rigid (rotation + translation) fit of A onto B, relative to B's size.
double rigid_residual(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  const Eigen::RowVectorXd ca = A.colwise().mean(), cb = B.colwise().mean();
  const Eigen::MatrixXd a = A.rowwise() - ca, b = B.rowwise() - cb;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(a.transpose() * b, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::MatrixXd D = Eigen::MatrixXd::Identity(A.cols(), A.cols());
  D(A.cols() - 1, A.cols() - 1) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1 : 1;
  const Eigen::MatrixXd Q = svd.matrixV() * D * svd.matrixU().transpose();  // b ~ a Q^T
  return (a * Q.transpose() - b).norm() / b.norm();
}

InterpOptions options_for(Method m) {
  InterpOptions o;
  o.solver.method = m;
  o.local_global.max_iterations = 50;
  o.local_global.relative_change = 1e-6;
  return o;
}

double max_abs_difference(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) { return (A - B).cwiseAbs().maxCoeff(); }

TEST(Polar, FactorsAreARotationAndASymmetricMatrix) {
  for (int d : {2, 3}) {
    Eigen::MatrixXd J = Eigen::MatrixXd::Random(d, d) + 2 * Eigen::MatrixXd::Identity(d, d);
    const Polar p = polar_decomposition(J);
    EXPECT_LT((p.R * p.Y - J).norm(), 1e-12);
    EXPECT_LT((p.Y - p.Y.transpose()).norm(), 1e-12);
    EXPECT_NEAR(p.R.determinant(), 1.0, 1e-12);
    EXPECT_LT((p.R.transpose() * p.R - Eigen::MatrixXd::Identity(d, d)).norm(), 1e-12);
  }
  const Eigen::Vector3d w(0.3, -1.2, 2.0);
  EXPECT_LT((rotation_log(rotation_exp(w)) - w).norm(), 1e-12);
}

TEST(Unwrap, AnglesOfAChainDifferByLessThanPi) {
  // A strip of elements turning by 0.5 rad each: the principal angles wrap, the unwrapped ones don't.
  const Mesh bar = make_grid(30, 1);
  const auto nb = element_neighbours(bar.F);
  for (int e = 0; e < bar.num_elements(); ++e) EXPECT_GE(nb[e].size(), 1u);
  Eigen::VectorXd angles(bar.num_elements());
  for (int e = 0; e < angles.size(); ++e) angles(e) = std::remainder(0.2 * e, 2 * kPi);
  const Eigen::VectorXd u = unwrap_angles(nb, angles);
  for (int e = 0; e < u.size(); ++e) EXPECT_NEAR(u(e), 0.2 * e, 1e-12);
  // 3D: rotation vectors about one axis, principal angles in [0, pi].
  Eigen::MatrixXd w(angles.size(), 3);
  const Eigen::Vector3d axis = Eigen::Vector3d(1, 2, 3).normalized();
  for (int e = 0; e < w.rows(); ++e) w.row(e) = rotation_log(rotation_exp(0.2 * e * axis)).transpose();
  const Eigen::MatrixXd uw = unwrap_rotation_vectors(nb, w);
  for (int e = 0; e < w.rows(); ++e) EXPECT_LT((uw.row(e).transpose() - 0.2 * e * axis).norm(), 1e-9) << e;
}

TEST(Interp, EndpointsArePoses) {
  const Mesh bar = make_grid(20, 2, 10.0, 1.0);
  const Mesh target = bent_bar(bar, 0.75 * kPi);
  const Interpolator interp(bar, target);
  EXPECT_EQ(interp.kind(), InterpKind::Planar);
  for (Method m : {Method::L2, Method::Linf, Method::Relax}) {
    const InterpOptions o = options_for(m);
    // The centroid is pinned to the poses' centroids, so the ends match exactly, not only
    // up to a rigid motion (tolerance: the solvers' accuracy).
    EXPECT_LT(max_abs_difference(interp.at(0.0, o).mesh.V, bar.V), 1e-6) << method_name(m);
    EXPECT_LT(max_abs_difference(interp.at(1.0, o).mesh.V, target.V), 1e-6) << method_name(m);
  }
}

TEST(Interp, RigidlyMovedTargetMovesFramesRigidly) {
  const Mesh bar = make_grid(20, 2, 10.0, 1.0);
  const Mesh target = bent_bar(bar, 0.75 * kPi);
  Mesh moved = target;
  const Eigen::Matrix2d Q = rotation_2d(0.9);
  moved.V = (target.V * Q.transpose()).rowwise() + Eigen::RowVector2d(3.0, -2.0);
  for (Method m : {Method::L2, Method::Linf}) {
    const InterpOptions o = options_for(m);
    const InterpFrame a = Interpolator(bar, target).at(0.5, o), b = Interpolator(bar, moved).at(0.5, o);
    EXPECT_LT(rigid_residual(a.mesh.V, b.mesh.V), 1e-6) << method_name(m);
    EXPECT_NEAR(a.stats.max, b.stats.max, 1e-6) << method_name(m);
  }
}

TEST(Interp, BarTurnedBeyond180DegreesDoesNotFold) {
  const Mesh bar = make_grid(40, 4, 10.0, 1.0);
  const Mesh target = bent_bar(bar, 1.5 * kPi);  // the far end turns by 270 degrees
  const Interpolator interp(bar, target);
  // The far end's unwrapped angle is the real turn, not its principal value -90 degrees.
  EXPECT_GT(interp.rotation_logs().maxCoeff(), kPi);
  for (Method m : {Method::L2, Method::Linf}) {
    const InterpFrame f = interp.at(0.5, options_for(m));
    EXPECT_EQ(f.stats.flipped, 0) << method_name(m);
    EXPECT_LT(f.stats.max, 0.2) << method_name(m);
  }
}

TEST(Interp, TetBarTwist) {
  const Mesh bar = make_tet_box(8, 2, 2, 4.0, 1.0, 1.0);
  Mesh target = bar;  // twisted by 150 degrees about the x axis along the bar
  for (int v = 0; v < bar.num_vertices(); ++v) {
    const double a = bar.V(v, 0) / 4.0 * (150.0 / 180.0) * kPi, y = bar.V(v, 1) - 0.5, z = bar.V(v, 2) - 0.5;
    target.V(v, 1) = std::cos(a) * y - std::sin(a) * z;
    target.V(v, 2) = std::sin(a) * y + std::cos(a) * z;
  }
  const Interpolator interp(bar, target);
  EXPECT_EQ(interp.kind(), InterpKind::Tets);
  for (Method m : {Method::L2, Method::Linf}) {
    const InterpOptions o = options_for(m);
    EXPECT_LT(max_abs_difference(interp.at(0.0, o).mesh.V, bar.V), 1e-6) << method_name(m);
    EXPECT_LT(max_abs_difference(interp.at(1.0, o).mesh.V, target.V), 1e-6) << method_name(m);
    const InterpFrame f = interp.at(0.5, o);
    EXPECT_EQ(f.stats.flipped, 0) << method_name(m);
    EXPECT_LT(f.stats.max, 0.2) << method_name(m);
  }
}

// A long tet bar twisted about its axis: up to 270 degrees the rotations unwrap without a
// jump and the half-way frame is the half twist (no flip); at 540 degrees the elements near a
// full turn have rotations near the identity about their own small tilt, no logarithm of
// which is near their neighbours' (nearly 2 pi about the axis): the frame folded (6 flipped
// tets) and said nothing. The jumps are counted and the interpolator warns.
TEST(Interp, TwistsOfAFullTurnOrMoreAreCountedAsJumps) {
  const double length = 30.0;
  const Mesh bar = make_tet_box(60, 2, 2, length, 1.0, 1.0);
  const auto twisted = [&](double degrees) {
    Mesh target = bar;
    for (int v = 0; v < bar.num_vertices(); ++v) {
      const double a = bar.V(v, 0) / length * degrees / 180.0 * kPi, y = bar.V(v, 1) - 0.5, z = bar.V(v, 2) - 0.5;
      target.V(v, 1) = std::cos(a) * y - std::sin(a) * z;
      target.V(v, 2) = std::sin(a) * y + std::cos(a) * z;
    }
    return target;
  };
  const Interpolator quarter_turns(bar, twisted(270));
  EXPECT_EQ(quarter_turns.rotation_jumps(), 0);
  EXPECT_TRUE(quarter_turns.warning().empty());
  const InterpFrame half = quarter_turns.at(0.5, options_for(Method::L2));
  EXPECT_EQ(half.stats.flipped, 0);
  EXPECT_LT(half.stats.max, 0.05);
  const Interpolator turn_and_a_half(bar, twisted(540));
  EXPECT_GT(turn_and_a_half.rotation_jumps(), 0);
  EXPECT_NE(turn_and_a_half.warning().find("blended rotations jump"), std::string::npos) << turn_and_a_half.warning();
}

// direct's levels on an interpolation: every level is the whole problem (the shapes Y_T(t) are
// per element of it; a level restricted to its moving region renumbered the elements and took
// other elements' shapes: the tet bar's third level was declared infeasible). Solved, with
// the maximum of linf's local-global and never above it.
TEST(Interp, DirectLevelsKeepEachElementsShape) {
  const Mesh bar = make_tet_box(8, 2, 2, 4.0, 1.0, 1.0);
  Mesh target = bar;
  for (int v = 0; v < bar.num_vertices(); ++v) {
    const double a = bar.V(v, 0) / 4.0 * (150.0 / 180.0) * kPi, y = bar.V(v, 1) - 0.5, z = bar.V(v, 2) - 0.5;
    target.V(v, 1) = std::cos(a) * y - std::sin(a) * z;
    target.V(v, 2) = std::sin(a) * y + std::cos(a) * z;
  }
  const Interpolator interp(bar, target);
  InterpOptions o = options_for(Method::Direct);
  o.solver.direct.k_min = 0;
  const InterpFrame direct = interp.at(0.5, o);
  ASSERT_EQ(direct.result.status, SolveStatus::Solved) << direct.result.message;
  EXPECT_GE(direct.result.iterations, 2);
  const InterpFrame linf = interp.at(0.5, options_for(Method::Linf));
  EXPECT_LE(direct.stats.max, linf.stats.max * (1 + 1e-4));
  EXPECT_EQ(direct.stats.flipped, 0);
  // Levels whose local-global loops reach their cap: the run is not solved, whatever the
  // last field-deviation step's gap says (its rotations are held: no bound on the level).
  InterpOptions capped = o;
  capped.local_global.max_iterations = 2;
  const InterpFrame short_loops = interp.at(0.5, capped);
  EXPECT_EQ(short_loops.result.status, SolveStatus::MaxIterations) << short_loops.result.message;
  EXPECT_NE(short_loops.result.message.find("has no certified gap"), std::string::npos) << short_loops.result.message;
  // Shapes that do not fit the problem are refused, not read out of range.
  LocalGlobalOptions bad;
  bad.shapes = Eigen::MatrixXd::Identity(3, 3);
  const Problem p = make_problem(bar);
  EXPECT_THROW(local_global(p, p.positions, SolverOptions{}, bad), InputError);
}

TEST(Interp, SurfaceInSpace) {
  // A flat strip rolled around a cylinder (a 3D surface pose), and back.
  const Mesh strip = make_grid(16, 4, 4.0, 1.0);
  Mesh flat = strip, rolled = strip;
  flat.V.conservativeResize(Eigen::NoChange, 3);
  flat.V.col(2).setZero();
  flat.V.col(2) += 0.05 * flat.V.col(0).cwiseProduct(flat.V.col(1));  // not planar: a surface
  rolled.V = Eigen::MatrixXd(strip.num_vertices(), 3);
  for (int v = 0; v < strip.num_vertices(); ++v) {
    const double a = strip.V(v, 0) / 4.0 * 1.2 * kPi;
    rolled.V.row(v) << std::sin(a), strip.V(v, 1), 1.0 - std::cos(a);
  }
  const Interpolator interp(flat, rolled);
  EXPECT_EQ(interp.kind(), InterpKind::Surface);
  for (Method m : {Method::L2, Method::Linf}) {
    const InterpOptions o = options_for(m);
    EXPECT_LT(max_abs_difference(interp.at(0.0, o).mesh.V, flat.V), 1e-6) << method_name(m);
    EXPECT_LT(max_abs_difference(interp.at(1.0, o).mesh.V, rolled.V), 1e-6) << method_name(m);
    EXPECT_LT(interp.at(0.5, o).stats.max, 0.3) << method_name(m);
  }
  // The strict minimizers on a surface (3x2 Jacobians): relax sweeps move vertices in 3D,
  // direct solves levels; neither is above linf's maximum (ties to 1e-4), and both reproduce
  // the poses at the ends.
  const double linf_max = interp.at(0.5, options_for(Method::Linf)).stats.max;
  for (Method m : {Method::Relax, Method::Direct}) {
    const InterpOptions o = options_for(m);
    EXPECT_LT(max_abs_difference(interp.at(0.0, o).mesh.V, flat.V), 1e-6) << method_name(m);
    const InterpFrame f = interp.at(0.5, o);
    EXPECT_TRUE(f.result.usable()) << method_name(m) << ": " << f.result.message;
    EXPECT_LE(f.stats.max, linf_max * (1 + 1e-4)) << method_name(m) << ": " << f.result.message;
    std::printf("surface interp t = 0.5: %s max %.9f (linf %.9f), L2 %.6f\n", method_name(m).c_str(), f.stats.max,
                linf_max, f.stats.l2);
  }
}

TEST(Interp, PinnedVertexMovesLinearly) {
  const Mesh bar = make_grid(20, 2, 10.0, 1.0);
  const Mesh target = bent_bar(bar, 0.5 * kPi);
  InterpOptions o = options_for(Method::L2);
  o.pin_vertex = 7;
  const InterpFrame f = Interpolator(bar, target).at(0.3, o);
  EXPECT_LT((f.mesh.V.row(7) - (0.7 * bar.V.row(7) + 0.3 * target.V.row(7))).norm(), 1e-12);
}

// -1 pins the centroid; other negative vertices were taken for it silently.
TEST(Interp, RefusesANegativePinnedVertexOtherThanMinusOne) {
  const Mesh bar = make_grid(20, 2, 10.0, 1.0);
  InterpOptions o = options_for(Method::L2);
  o.pin_vertex = -5;
  EXPECT_THROW(Interpolator(bar, bent_bar(bar, 0.5 * kPi)).at(0.3, o), InputError);
}

TEST(Interp, RefusesDifferentConnectivity) {
  const Mesh bar = make_grid(4, 2);
  Mesh other = make_grid(5, 2);
  EXPECT_THROW(Interpolator(bar, other), InputError);
  Mesh swapped = bar;
  std::swap(swapped.F(3, 0), swapped.F(3, 1));
  try {
    Interpolator(bar, swapped, "a.obj", "b.obj");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("element 3"), std::string::npos) << e.what();
  }
  EXPECT_THROW(Interpolator(make_tet_box(1, 1, 1), bar), InputError);
  const Interpolator ok(bar, bar);
  EXPECT_THROW(ok.at(1.5, options_for(Method::L2)), InputError);
  EXPECT_THROW(ok.at(0.5, options_for(Method::Exact)), InputError);
}

TEST(Interp, SharedTetBarPair) {
  const std::string dir = std::string(STRICTMIN_SHARED_DATA) + "/interp/";
  if (!std::filesystem::exists(dir + "tetbar_rest.mesh")) GTEST_SKIP() << "no " << dir;
  const Mesh rest = read_mesh(dir + "tetbar_rest.mesh"), init = read_mesh(dir + "tetbar_init.mesh");
  const Interpolator interp(rest, init);
  for (Method m : {Method::L2, Method::Linf}) {
    const InterpOptions o = options_for(m);
    EXPECT_LT(rigid_residual(interp.at(1.0, o).mesh.V, init.V), 1e-6) << method_name(m);
    EXPECT_EQ(interp.at(0.5, o).stats.flipped, 0) << method_name(m);
  }
}

}  // namespace
