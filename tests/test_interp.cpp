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

// A long tet bar twisted about its axis. Up to 270 degrees the rotations unwrap without a
// jump and the half-way frame is the half twist. At 540 degrees the elements near a full
// turn have rotations near the identity about their own small tilt, no logarithm of which
// is near their neighbours' (nearly 2 pi about the axis): blended each on its own, the
// frames folded (6 flipped tets, "solved", no word). The jumps are counted; the rotations
// are then blended relative to their neighbours' along a tree, which follows the twist: the
// half-way frame is the bar twisted by 270 degrees, end to end, with nothing folded.
TEST(Interp, TwistsOfAFullTurnOrMoreAreFollowed) {
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
  // The angle (degrees) in the yz plane of cross-section k (x = k length / 60) of a pose of the
  // bar: its diagonal from corner (y, z) = (0, 0) to (1, 1).
  const auto section_angle = [&](const Mesh& m, int k) {
    Eigen::RowVector3d low = Eigen::RowVector3d::Zero(), high = low;
    for (int v = 0; v < bar.num_vertices(); ++v) {
      if (std::abs(bar.V(v, 0) - k * length / 60) > 1e-9) continue;
      if (bar.V(v, 1) < 1e-9 && bar.V(v, 2) < 1e-9) low = m.V.row(v);
      if (bar.V(v, 1) > 1 - 1e-9 && bar.V(v, 2) > 1 - 1e-9) high = m.V.row(v);
    }
    return std::atan2(high(2) - low(2), high(1) - low(1)) * 180.0 / kPi;
  };
  const auto turn_between = [](double from, double to) { return std::remainder(to - from, 360.0); };

  const Interpolator quarter_turns(bar, twisted(270));
  EXPECT_EQ(quarter_turns.rotation_jumps(), 0);
  EXPECT_EQ(quarter_turns.rotation_blend(), "logarithms");
  EXPECT_TRUE(quarter_turns.warning().empty());
  const InterpFrame quarter = quarter_turns.at(0.5, options_for(Method::L2));
  EXPECT_EQ(quarter.stats.flipped, 0);
  EXPECT_LT(quarter.stats.max, 0.05);

  const Interpolator turn_and_a_half(bar, twisted(540));
  EXPECT_GT(turn_and_a_half.rotation_jumps(), 0);
  EXPECT_EQ(turn_and_a_half.rotation_blend(), "tree");
  EXPECT_EQ(turn_and_a_half.rotation_disagreements(), 0);
  EXPECT_TRUE(turn_and_a_half.warning().empty()) << turn_and_a_half.warning();
  const InterpFrame half = turn_and_a_half.at(0.5, options_for(Method::L2));
  EXPECT_EQ(half.stats.flipped, 0);
  EXPECT_LT(half.stats.max, 0.05);
  // The rest bar's cross-sections sit at 45 degrees. Half way the near end has not turned
  // (within 2 degrees), and the sections turn by 270 degrees in all from end to end (within
  // 3), each by 270 / 60 from the last (within 1): the twist is followed, not undone.
  EXPECT_NEAR(turn_between(45.0, section_angle(half.mesh, 0)), 0.0, 2.0);
  double total = 0;
  for (int k = 0; k < 60; ++k) {
    const double step = turn_between(section_angle(half.mesh, k), section_angle(half.mesh, k + 1));
    EXPECT_NEAR(step, 270.0 / 60, 1.0) << "section " << k;
    total += step;
  }
  EXPECT_NEAR(total, 270.0, 3.0);

  // Blended each on its own, as before: the pairs that cannot turn together are counted and
  // warned about.
  const Interpolator logarithms(bar, twisted(540), "source", "target", RotationBlend::Logarithms);
  EXPECT_EQ(logarithms.rotation_blend(), "logarithms");
  EXPECT_GT(logarithms.rotation_disagreements(), 0);
  EXPECT_NE(logarithms.warning().find("more than 90 degrees apart"), std::string::npos) << logarithms.warning();
}

// The tree blend (rotation_unwrap.h) on rotations about one axis, which commute: the same as
// each element's own logarithm, exp(t theta_e a), however far they turn (here up to 3.4 turns),
// with the least turned element as the root. And on arbitrary rotations: I at t = 0, the
// rotations themselves at t = 1.
TEST(Interp, TreeBlendOfRotationsAboutOneAxisIsExact) {
  const int E = 41;
  std::vector<std::vector<int>> chain(E);
  for (int e = 0; e + 1 < E; ++e) {
    chain[e].push_back(e + 1);
    chain[e + 1].push_back(e);
  }
  const Eigen::Vector3d axis = Eigen::Vector3d(1, 2, -2).normalized();
  std::vector<Eigen::Matrix3d> R(E);
  std::vector<double> theta(E);
  for (int e = 0; e < E; ++e) {
    theta[e] = 0.55 * (e - 3);
    R[e] = rotation_exp(theta[e] * axis);
  }
  const TreeRotationBlend blend(chain, R);
  for (double t : {0.0, 0.3, 0.5, 0.9, 1.0}) {
    const std::vector<Eigen::Matrix3d> at = blend.at(t);
    double worst = 0;
    for (int e = 0; e < E; ++e) worst = std::max(worst, (at[e] - rotation_exp(t * theta[e] * axis)).norm());
    EXPECT_LT(worst, 1e-12) << "t = " << t;
    EXPECT_EQ(count_disagreeing_neighbours(chain, R, at, t, 1e-6), 0) << "t = " << t;
  }

  const Mesh box = make_tet_box(3, 2, 2, 3.0, 2.0, 2.0);
  const auto neighbours = element_neighbours(box.F);
  std::srand(7);
  std::vector<Eigen::Matrix3d> random(box.num_elements());
  for (auto& r : random) r = rotation_exp(3.0 * Eigen::Vector3d::Random());
  const TreeRotationBlend arbitrary(neighbours, random);
  const std::vector<Eigen::Matrix3d> at0 = arbitrary.at(0), at1 = arbitrary.at(1);
  for (size_t e = 0; e < random.size(); ++e) {
    EXPECT_LT((at0[e] - Eigen::Matrix3d::Identity()).norm(), 1e-12);
    EXPECT_LT((at1[e] - random[e]).norm(), 1e-12);
  }
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
