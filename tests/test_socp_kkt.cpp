// The interior-point method's Newton systems (solvers/socp/kkt.h) against a dense solve of
// the unreduced system, on a small program whose fixed-bound cones sit at their bound (as on
// direct's later levels: docs/linf.md, "Accuracy of the Newton systems"). There W^{-1} is
// huge, and the dual equations M^T dz = r_d must still hold to round-off.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "grid_cone_program.h"
#include "solvers/socp/cone_program.h"
#include "solvers/socp/cones.h"
#include "solvers/socp/kkt.h"
#include "solvers/socp/settings.h"

using namespace strictmin::socp;

namespace {

// The grid program with every bounded element at bound 1.
strictmin::socp::ConeProgram grid_program() { return grid_cone_program([](int) { return 1.0; }); }

// A dense matrix of a linear operator on vectors of size cols.
template <class Op>
Eigen::MatrixXd dense(Eigen::Index rows, Eigen::Index cols, Op op) {
  Eigen::MatrixXd out(rows, cols);
  for (Eigen::Index c = 0; c < cols; ++c) out.col(c) = op(Eigen::VectorXd::Unit(cols, c));
  return out;
}

// M: (x, k) -> the cones' (heads, tails), dense.
Eigen::MatrixXd dense_m(const ConeProgram& p) {
  return dense(p.cone_size(), p.num_x + 1, [&](const Eigen::VectorXd& v) {
    Eigen::VectorXd out;
    p.apply_m(v.head(p.num_x), v[p.num_x], false, out);
    return out;
  });
}

// The scaling W (or W^{-1}) as a dense matrix.
Eigen::MatrixXd dense_scaling(const ConeProgram& p, const Scaling& sc, ScalingOp op) {
  return dense(p.cone_size(), p.cone_size(), [&](const Eigen::VectorXd& v) {
    Eigen::VectorXd out;
    apply_scaling(p, sc, op, v, out);
    return out;
  });
}

}  // namespace

TEST(NewtonSystems, DualEquationsHoldWithBoundedConesAtTheirBound) {
  const ConeProgram p = grid_program();
  const int E = p.num_element_cones(), C = static_cast<int>(p.cone_size()), nv = p.num_x + 1;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  // s, z: well inside for the free cones; for the bounded ones on the boundary to 1e-14
  // (s) and 1e-3 (z), with opposite tails (complementary), as at an optimum near the optimum.
  Eigen::VectorXd s(C), z(C);
  for (int i = 0; i < E; ++i) {
    Eigen::Vector4d u(U(rng), U(rng), U(rng), U(rng));
    u.normalize();
    const bool bounded = p.head_a[i] == 0.0;
    s[5 * i] = 1.0;
    z[5 * i] = bounded ? 3.0 : 0.5;
    s.segment<4>(5 * i + 1) = (bounded ? 1.0 - 1e-14 : 0.4) * u;
    z.segment<4>(5 * i + 1) = -(bounded ? (1.0 - 1e-3) * 3.0 : 0.2) * u;
  }
  Scaling sc;
  ASSERT_TRUE(compute_scaling(p, s, z, sc));
  Eigen::VectorXd q(C), rs(C), rdx(p.num_x), req;
  for (int r = 0; r < C; ++r) q[r] = U(rng), rs[r] = 1e-6 * U(rng);
  for (int r = 0; r < p.num_x; ++r) rdx[r] = U(rng);
  const double rdk = U(rng);

  // The dense unreduced system in the scaled dual dzt = W dz:
  //   B^T dzt = r_d,  B dv + dzt = rc,  B = W^{-1} M,  rc = q + W^{-1} rs.
  const Eigen::MatrixXd M = dense_m(p);
  const Eigen::MatrixXd W = dense_scaling(p, sc, ScalingOp::W), Winv = dense_scaling(p, sc, ScalingOp::WInv);
  ASSERT_GT(Winv.cwiseAbs().maxCoeff(), 1e5);  // the ill-conditioned scaling of the bound
  const Eigen::MatrixXd B = Winv * M;
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(nv + C, nv + C);
  K.block(0, nv, nv, C) = B.transpose();
  K.block(nv, 0, C, nv) = B;
  K.block(nv, nv, C, C).setIdentity();
  const Eigen::VectorXd rc = q + Winv * rs;
  Eigen::VectorXd rhs(nv + C);
  rhs << rdx, rdk, rc;
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(K);
  Eigen::VectorXd ref = lu.solve(rhs);
  ref += lu.solve(Eigen::VectorXd(rhs - K * ref));
  const double ref_residual = (K * ref - rhs).cwiseAbs().maxCoeff() / rhs.cwiseAbs().maxCoeff();
  std::printf("dense LU: relative residual %.2e\n", ref_residual);
  ASSERT_LT(ref_residual, 1e-8);

  for (const int refinement : {0, 3}) {
    IpmSettings settings;
    settings.unreduced_refinement = refinement;
    NormalEquations ne(p, settings);
    ASSERT_TRUE(ne.factor(sc));
    Direction d;
    ne.solve_newton(q, rs, rdx, rdk, req, d, 0.0);
    Eigen::VectorXd dv(nv);
    dv << d.dx, d.dk;
    const double scale = rhs.cwiseAbs().maxCoeff();
    const double dual = (M.transpose() * d.dz - rhs.head(nv)).cwiseAbs().maxCoeff() / scale;
    const double dv_error = (dv - ref.head(nv)).cwiseAbs().maxCoeff() / ref.head(nv).cwiseAbs().maxCoeff();
    std::printf("unreduced refinement %d: dual residual %.2e, dv error %.2e, reported %.2e\n", refinement, dual,
                dv_error, d.residual);
    // Without the refinement on the unreduced system the dual residual here is 6.7e-7
    // (dz formed through W^{-1}); with it 3e-10.
    if (refinement > 0) {
      EXPECT_LT(dual, 1e-8);
      EXPECT_LT(d.residual, 1e-7);
    }
    EXPECT_LT(dv_error, 1e-8);
  }
}

// Equalities that make one free vertex equal to another (x_1 = x_0, an identity block: what a
// seam's transitions can reduce to on direct's restricted levels) put two corners of the
// elements between them on one unknown of the eliminated system (kkt.h, null_space.h). Their
// cross pairs belong twice on that unknown's diagonal block; counted once, Z^T H Z was wrong
// (and indefinite on cow's fifth level). The factor alone (no CG, no refinement on the
// unreduced system) must give the direction of a dense solve of the unreduced system.
TEST(NewtonSystems, EliminatedEqualitiesJoiningTwoCornersOfAnElement) {
  ConeProgram p = grid_program();
  // x_1 - x_0 = 0 (free vertices 0 and 1 are grid points (1, 1) and (2, 1): they share an edge).
  std::vector<Eigen::Triplet<double>> entries;
  for (int r = 0; r < 2; ++r) {
    entries.emplace_back(r, 2 + r, 1.0);
    entries.emplace_back(r, r, -1.0);
  }
  p.A.resize(2, p.num_x);
  p.A.setFromTriplets(entries.begin(), entries.end());
  p.beq = Eigen::VectorXd::Zero(2);
  p.finalize();
  const int E = p.num_element_cones(), C = static_cast<int>(p.cone_size()), nv = p.num_x + 1;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  Eigen::VectorXd s(C), z(C);  // every cone well inside: the matrix is well-conditioned
  for (int i = 0; i < E; ++i) {
    Eigen::Vector4d u(U(rng), U(rng), U(rng), U(rng));
    u.normalize();
    s[5 * i] = 1.0;
    z[5 * i] = 0.5 + 0.25 * (U(rng) + 1.0);
    s.segment<4>(5 * i + 1) = (0.5 + 0.2 * U(rng)) * u;
    z.segment<4>(5 * i + 1) = -0.2 * u;
  }
  Scaling sc;
  ASSERT_TRUE(compute_scaling(p, s, z, sc));
  Eigen::VectorXd q(C), rs(C), rdx(p.num_x), req = Eigen::VectorXd::Zero(2);
  for (int r = 0; r < C; ++r) q[r] = U(rng), rs[r] = 0.1 * U(rng);
  for (int r = 0; r < p.num_x; ++r) rdx[r] = U(rng);
  const double rdk = U(rng);

  // The dense unreduced system: B^T dzt + A~^T dy = r_d, A~ dv = -r_eq, B dv + dzt = rc.
  const Eigen::MatrixXd M = dense_m(p);
  const Eigen::MatrixXd Winv = dense_scaling(p, sc, ScalingOp::WInv);
  const Eigen::MatrixXd B = Winv * M;
  Eigen::MatrixXd At = Eigen::MatrixXd::Zero(nv, 2);
  At.topRows(p.num_x) = Eigen::MatrixXd(p.A).transpose();
  const int N = nv + 2 + C;
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(N, N);
  K.block(0, nv, nv, 2) = At;
  K.block(0, nv + 2, nv, C) = B.transpose();
  K.block(nv, 0, 2, nv) = At.transpose();
  K.block(nv + 2, 0, C, nv) = B;
  K.block(nv + 2, nv + 2, C, C).setIdentity();
  Eigen::VectorXd rhs(N);
  rhs << rdx, rdk, -req, q + Winv * rs;
  const Eigen::VectorXd ref = K.fullPivLu().solve(rhs);
  ASSERT_LT((K * ref - rhs).cwiseAbs().maxCoeff(), 1e-10 * rhs.cwiseAbs().maxCoeff());

  IpmSettings settings;
  settings.refinement_steps = 0;
  settings.unreduced_refinement = 0;
  NormalEquations ne(p, settings);
  ASSERT_TRUE(ne.eliminates_equalities());
  ASSERT_TRUE(ne.factor(sc));
  Direction d;
  ne.solve_newton(q, rs, rdx, rdk, req, d, 0.0);
  Eigen::VectorXd dv(nv);
  dv << d.dx, d.dk;
  const double dv_error = (dv - ref.head(nv)).cwiseAbs().maxCoeff() / ref.head(nv).cwiseAbs().maxCoeff();
  std::printf("eliminated x_1 = x_0: dv error %.2e\n", dv_error);
  EXPECT_LT(dv_error, 1e-10);
  EXPECT_LT((d.dx.segment<2>(2) - d.dx.head<2>()).cwiseAbs().maxCoeff(), 1e-14);
}
