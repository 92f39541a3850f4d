// Barycentric gradients and Jacobians on affine maps (identity, rotation, scaling, shear),
// for planar triangles, surface triangles in their local frames, and tets.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>

#include "strictmin/io/input_error.h"
#include "strictmin/measures/measures.h"
#include "strictmin/mesh/generators.h"
#include "strictmin/problem/parts.h"
#include "strictmin/problem/problem.h"
#include "strictmin/problem/subproblem.h"
#include "strictmin/tasks/map_distortion.h"

using namespace strictmin;

namespace {

Eigen::MatrixXd apply_affine(const Eigen::MatrixXd& V, const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
  return ((V * A.transpose()).rowwise() + b.transpose()).eval();
}

TEST(Problem, GradientsSumToZeroAndReproduceLinearFunctions) {
  Mesh mesh = make_grid(3, 2, 2.0, 1.0);
  const Problem p = make_problem(mesh);
  ASSERT_EQ(p.num_elements(), 12);
  EXPECT_NEAR(p.weights.sum(), 2.0, 1e-14);
  for (int e = 0; e < p.num_elements(); ++e) {
    const auto g = p.gradients.middleRows(e * 3, 3);
    EXPECT_LT(g.colwise().sum().norm(), 1e-13);
    // grad of the linear function x (resp. y) is (1, 0) (resp. (0, 1)).
    Eigen::Vector2d gx = Eigen::Vector2d::Zero(), gy = Eigen::Vector2d::Zero();
    for (int j = 0; j < 3; ++j) {
      gx += mesh.V(p.elements(e, j), 0) * g.row(j).transpose();
      gy += mesh.V(p.elements(e, j), 1) * g.row(j).transpose();
    }
    EXPECT_LT((gx - Eigen::Vector2d(1, 0)).norm(), 1e-13);
    EXPECT_LT((gy - Eigen::Vector2d(0, 1)).norm(), 1e-13);
  }
}

TEST(Problem, AffineMapsOfPlanarTriangles) {
  const Mesh mesh = make_grid(4, 4, 1.0, 1.0, -0.5, -0.5);
  const Problem p = make_problem(mesh);
  const double a = 0.4;
  Eigen::Matrix2d rot, scale, shear;
  rot << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  scale << 2.0, 0.0, 0.0, 0.5;
  shear << 1.0, 0.3, 0.0, 1.0;
  const Eigen::Matrix2d I = Eigen::Matrix2d::Identity();
  for (const Eigen::Matrix2d& A : {Eigen::Matrix2d(I), rot, scale, shear}) {
    const Eigen::MatrixXd X = apply_affine(mesh.V, A, Eigen::Vector2d(0.3, -1.2));
    for (int e = 0; e < p.num_elements(); ++e) {
      EXPECT_LT((p.jacobian(e, X) - A).norm(), 1e-13);
      EXPECT_NEAR(distortion(Measure::FieldDeviation, p.jacobian(e, X), p.target(e)), (A - I).norm(), 1e-13);
    }
  }
  // Exact distortions by hand: rotation by a: FD 2 sqrt(2) sin(a/2), ARAP 0;
  // scale diag(2, 1/2): ARAP sqrt(1 + 1/4); shear 0.3: ASAP 0.3/sqrt(2).
  const Eigen::MatrixXd Xr = apply_affine(mesh.V, rot, Eigen::Vector2d::Zero());
  EXPECT_NEAR(distortion(Measure::FieldDeviation, p.jacobian(0, Xr), I), 2 * std::sqrt(2.0) * std::sin(a / 2), 1e-13);
  EXPECT_NEAR(distortion(Measure::Arap, p.jacobian(0, Xr), I), 0.0, 1e-13);
  EXPECT_NEAR(distortion(Measure::Arap, p.jacobian(3, apply_affine(mesh.V, scale, Eigen::Vector2d::Zero())), I),
              std::sqrt(1.25), 1e-13);
  EXPECT_NEAR(distortion(Measure::Asap, p.jacobian(5, apply_affine(mesh.V, shear, Eigen::Vector2d::Zero())), I),
              0.3 / std::sqrt(2.0), 1e-13);
}

TEST(Problem, JacobianOperatorMatchesPerElementJacobians) {
  const Mesh mesh = make_tet_box(2, 2, 1);
  const Problem p = make_problem(mesh);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::MatrixXd X = mesh.V;
  for (int i = 0; i < X.size(); ++i) X(i) += 0.1 * u(rng);
  Eigen::VectorXd q(X.size());
  for (int v = 0; v < X.rows(); ++v) q.segment(3 * v, 3) = X.row(v).transpose();
  const Eigen::VectorXd J = p.jacobian_operator() * q;
  for (int e = 0; e < p.num_elements(); ++e) {
    const Eigen::MatrixXd Je = p.jacobian(e, X);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(J(e * 9 + r * 3 + c), Je(r, c), 1e-12);
  }
}

TEST(Problem, ReducedSystemEliminatesFixedVertices) {
  const Mesh mesh = make_grid(3, 3);
  Problem p = make_problem(mesh);
  p.fix({{0, Eigen::Vector2d(0.1, 0.2)}, {15, Eigen::Vector2d(1.5, 0.9)}});
  EXPECT_EQ(p.num_free(), 14);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::VectorXd x(p.num_free() * 2);
  for (int i = 0; i < x.size(); ++i) x(i) = u(rng);
  const Eigen::MatrixXd X = p.with_free_dofs(x);
  EXPECT_LT((p.free_dofs(X) - x).norm(), 1e-15);
  const auto red = p.reduced();
  const Eigen::VectorXd r = red.G * x - red.h;
  for (int e = 0; e < p.num_elements(); ++e) {
    const Eigen::MatrixXd D = p.jacobian(e, X) - p.target(e);
    for (int i = 0; i < 2; ++i)
      for (int c = 0; c < 2; ++c) EXPECT_NEAR(r(e * 4 + i * 2 + c), D(i, c), 1e-12);
  }
}

TEST(Problem, TetsAffineMaps) {
  const Mesh mesh = make_tet_box(2, 1, 1, 2.0, 1.0, 1.0);
  const Problem p = make_problem(mesh);
  EXPECT_EQ(p.image_dim, 3);
  EXPECT_NEAR(p.weights.sum(), 2.0, 1e-14);
  const Eigen::Matrix3d A = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix() *
                            Eigen::Vector3d(1.5, 1.0, 0.8).asDiagonal();
  const Eigen::MatrixXd X = apply_affine(mesh.V, A, Eigen::Vector3d(1, 2, 3));
  for (int e = 0; e < p.num_elements(); ++e) {
    EXPECT_LT((p.jacobian(e, X) - A).norm(), 1e-13);
    EXPECT_NEAR(distortion(Measure::Arap, p.jacobian(e, X), p.target(e)), std::sqrt(0.25 + 0.04), 1e-12);
  }
}

// The 3 x 3 grid turned into 3D by a rigid motion (its flat positions are an isometry of it).
Mesh grid_bent_into_3d(const Mesh& flat) {
  Mesh surface;
  surface.F = flat.F;
  surface.V.resize(flat.V.rows(), 3);
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(0.9, Eigen::Vector3d(1, -1, 2).normalized()).toRotationMatrix();
  for (int v = 0; v < flat.V.rows(); ++v) surface.V.row(v) = (Q * Eigen::Vector3d(flat.V(v, 0), flat.V(v, 1), 0)).transpose();
  return surface;
}

TEST(Problem, SurfaceTrianglesGetIsometricFrames) {
  // A grid bent into 3D by a rigid motion: every local-frame Jacobian of the flattened
  // (original 2D) positions is a rotation, so ARAP is 0 and areas are preserved.
  const Mesh flat = make_grid(3, 3);
  const Mesh surface = grid_bent_into_3d(flat);
  const Problem p = make_problem(surface);
  EXPECT_EQ(p.image_dim, 2);
  EXPECT_NEAR(p.weights.sum(), 1.0, 1e-13);
  for (int e = 0; e < p.num_elements(); ++e) {
    const Eigen::MatrixXd J = p.jacobian(e, flat.V);
    EXPECT_NEAR(distortion(Measure::Arap, J, p.target(e)), 0.0, 1e-12);
    EXPECT_NEAR(J.determinant(), 1.0, 1e-12);
  }
}

// The frame's second axis, (e1 x e2) x e1, is cubic in the size: a surface with coordinates
// about 1e60 had non-finite gradients ("a degenerate element"), and about 1e-60 zero ones,
// though the reader takes sizes up to 1e150. Edges that far from unit length are measured
// scaled by an exact power of two; ordinary ones exactly as before.
TEST(Problem, SurfaceFramesAtEverySize) {
  const Mesh flat = make_grid(3, 3);
  const Mesh surface = grid_bent_into_3d(flat);
  const Problem unit = make_problem(surface);
  for (const double scale : {1e60, 1e120, 1e-60, 1e-120}) {
    Mesh scaled = surface;
    scaled.V *= scale;
    const Problem p = make_problem(scaled);
    ASSERT_TRUE(p.gradients.allFinite()) << scale;
    EXPECT_NEAR(p.weights.sum() / (scale * scale), 1.0, 1e-13) << scale;
    EXPECT_LT((p.gradients * scale - unit.gradients).cwiseAbs().maxCoeff(), 1e-12) << scale;
    for (int e = 0; e < p.num_elements(); ++e)
      EXPECT_NEAR(distortion(Measure::Arap, p.jacobian(e, flat.V * scale), p.target(e)), 0.0, 1e-12) << scale;
    // A surface mapped in 3D (deform, eval): the identity is undistorted at every size.
    const MapDistortion identity = map_distortion(scaled, scaled, Measure::FieldDeviation);
    EXPECT_LT(identity.stats.max, 1e-12) << scale;
  }
}

TEST(Problem, HandlesAreChecked) {
  Problem p = make_problem(make_grid(2, 2));
  EXPECT_THROW(p.fix({{9, Eigen::Vector2d(0, 0)}}), InputError);
  EXPECT_THROW(p.fix({{1, Eigen::Vector3d(0, 0, 0)}}), InputError);
  try {
    p.fix({{-1, Eigen::Vector2d(0, 0)}});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("vertex -1"), std::string::npos);
  }
}

}  // namespace

// A problem restricted to movable vertices (problem/subproblem.h): the elements with a
// movable vertex, their other vertices held at X, the same Jacobians there, and equalities
// with the held columns moved to the right-hand side.
TEST(Subproblem, KeepsTheElementsOfMovableVerticesAndTheirJacobians) {
  const Mesh mesh = make_grid(6, 6);  // 7 x 7 vertices, the centre is 24
  Problem p = make_problem(mesh);
  p.fix({{0, Eigen::Vector2d(0.0, 0.0)}});
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  Eigen::MatrixXd X = p.positions;
  for (int i = 0; i < X.size(); ++i) X.data()[i] += u(rng);
  X.row(0) = Eigen::RowVector2d(0.0, 0.0);
  // Two equalities: q_24,x - q_48,x = 0.3 (24 movable, the corner 48 left out) and
  // q_47,y + q_46,y = 1 (both left out).
  std::vector<Eigen::Triplet<double>> t = {{0, 48, 1.0}, {0, 96, -1.0}, {1, 95, 1.0}, {1, 93, 1.0}};
  p.eq_matrix.resize(2, 2 * p.num_vertices);
  p.eq_matrix.setFromTriplets(t.begin(), t.end());
  p.eq_rhs = Eigen::Vector2d(0.3, 1.0);
  std::vector<char> seeds(p.num_vertices, 0);
  seeds[24] = 1;
  const std::vector<char> ring2 = vertices_within_rings(p, seeds, 2);
  int count = 0;
  for (char c : ring2) count += c;
  EXPECT_EQ(count, 9);  // the centre and the 8 grid points around it (alternating diagonals)
  EXPECT_EQ(vertices_within_rings(p, seeds, 0), std::vector<char>(p.num_vertices, 1));
  std::vector<char> movable = ring2;
  movable[0] = 1;  // a fixed vertex never moves, whatever its flag
  const Subproblem sub = restrict_to_movable(p, movable, X);
  const Problem& s = sub.problem;
  EXPECT_EQ(s.num_free(), 9);
  for (int i = 0; i < s.num_vertices; ++i) {
    EXPECT_EQ(s.fixed[i] != 0, !ring2[sub.vertex[i]]) << "vertex " << sub.vertex[i];
    EXPECT_EQ(s.positions.row(i), X.row(sub.vertex[i]));
  }
  EXPECT_EQ(std::count(sub.vertex.begin(), sub.vertex.end(), 0), 0);
  // Every element with a movable vertex, and nothing else.
  int kept = 0;
  for (int e = 0; e < p.num_elements(); ++e) {
    bool touches = false;
    for (int j = 0; j < 3; ++j) touches = touches || (ring2[p.elements(e, j)] && !p.fixed[p.elements(e, j)]);
    if (!touches) continue;
    ASSERT_LT(kept, static_cast<int>(sub.element.size()));
    EXPECT_EQ(sub.element[kept], e);
    EXPECT_LT((s.jacobian(kept, s.positions) - p.jacobian(e, X)).norm(), 1e-14);
    EXPECT_EQ(s.target(kept), p.target(e));
    EXPECT_EQ(s.weights[kept], p.weights[e]);
    ++kept;
  }
  EXPECT_EQ(kept, static_cast<int>(sub.element.size()));
  // The first equality keeps its movable column, the left-out one moves to the right-hand
  // side; the second has no movable column and goes.
  ASSERT_EQ(s.eq_matrix.rows(), 1);
  const int local24 = static_cast<int>(std::find(sub.vertex.begin(), sub.vertex.end(), 24) - sub.vertex.begin());
  EXPECT_EQ(s.eq_matrix.coeff(0, 2 * local24), 1.0);
  EXPECT_EQ(s.eq_matrix.nonZeros(), 1);
  EXPECT_EQ(std::count(sub.vertex.begin(), sub.vertex.end(), 48), 0);
  EXPECT_NEAR(s.eq_rhs[0], 0.3 + X(48, 0), 1e-15);
}

// Parts: a 2 x 1 grid (4 triangles, 6 vertices) and a separate triangle (3 more vertices).
TEST(Parts, JoinVerticesThroughElementsAndFindTheUnanchored) {
  Mesh mesh = make_grid(2, 1);
  const int V0 = mesh.num_vertices(), E0 = mesh.num_elements();
  mesh.V.conservativeResize(V0 + 3, Eigen::NoChange);
  mesh.V.bottomRows(3) << 5, 0, 6, 0, 5, 1;
  mesh.F.conservativeResize(E0 + 1, Eigen::NoChange);
  mesh.F.row(E0) << V0, V0 + 1, V0 + 2;
  Problem p = make_problem(mesh);
  const ElementParts all = element_parts(p);
  ASSERT_EQ(all.count, 2);
  for (int v = 0; v < V0; ++v) EXPECT_EQ(all.part[v], 0) << v;
  for (int v = V0; v < V0 + 3; ++v) EXPECT_EQ(all.part[v], 1) << v;
  EXPECT_EQ(unanchored_parts(all, p.fixed), (std::vector<int>{0, V0}));
  p.fix({{V0 + 1, Eigen::Vector2d(6, 0)}});
  EXPECT_EQ(unanchored_parts(all, p.fixed), (std::vector<int>{0}));
  // Only the separate triangle: the grid's vertices are in no part.
  std::vector<char> only(p.num_elements(), 0);
  only[E0] = 1;
  const ElementParts one = element_parts(p, &only);
  ASSERT_EQ(one.count, 1);
  for (int v = 0; v < V0; ++v) EXPECT_EQ(one.part[v], -1) << v;
  EXPECT_EQ(one.part[V0 + 2], 0);
  EXPECT_TRUE(unanchored_parts(one, p.fixed).empty());
}
