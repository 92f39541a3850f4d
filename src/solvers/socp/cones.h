#pragma once
// Operations on vectors that hold one entry block per cone of a ConeProgram (s, z, the
// scaled point lambda, directions), each cone by the closed forms of soc.h, in parallel.
#include <Eigen/Core>

#include "solvers/socp/cone_program.h"

namespace strictmin::socp {

// Nesterov-Todd scaling of every cone: W_i = beta_i (2 w_i w_i^T - J), and lambda = W z.
struct Scaling {
  Eigen::VectorXd beta;    // #cones
  Eigen::VectorXd w;       // cone layout
  Eigen::VectorXd lambda;  // cone layout
};

// False when some s_i or z_i is not strictly inside its cone.
bool compute_scaling(const ConeProgram& p, const Eigen::VectorXd& s, const Eigen::VectorXd& z, Scaling& out);

enum class ScalingOp { W, WInv, WInv2 };
// out = op(W) u, cone by cone (out must not alias u).
void apply_scaling(const ConeProgram& p, const Scaling& sc, ScalingOp op, const Eigen::VectorXd& u, Eigen::VectorXd& out);

// The cone parts of a Newton direction from its (dx, dk), in one pass over the cones
// instead of one per operation (m = M (dx, dk) is formed per cone and never stored):
//   with rc, dz:        dz  = W^-1 (rc - W^-1 m)            (the eliminated dz of the system)
//   with rs, ds, dst:   ds  = m - rs,  dst = W^-1 ds        (the primal step, scaled;
//                                                            an empty rs stands for 0)
//   with dzt:           dzt = W dz                          (dz computed here or given)
// Null pointers skip a part; dz is an input when rc is null.
void cone_direction_parts(const ConeProgram& p, const Scaling& sc, const Eigen::VectorXd& dx, double dk,
                          const Eigen::VectorXd* rc, Eigen::VectorXd* dz, const Eigen::VectorXd* rs,
                          Eigen::VectorXd* ds, Eigen::VectorXd* dst, Eigen::VectorXd* dzt);

// Jordan product a o b and the solution of l o out = r, cone by cone.
void cone_product(const ConeProgram& p, const Eigen::VectorXd& a, const Eigen::VectorXd& b, Eigen::VectorXd& out);
void cone_arrow_solve(const ConeProgram& p, const Eigen::VectorXd& l, const Eigen::VectorXd& r, Eigen::VectorXd& out);

// The identity e (1 in every head, 0 in the tails), scaled by `value`.
Eigen::VectorXd cone_identity(const ConeProgram& p, double value);

// Largest alpha with l + alpha u in every cone (l strictly inside); +inf if none limits it.
// Gondzio's centrality target: for each cone, the spectral values v0 +- ||v1|| of v moved
// into [lo, hi] (those above hi by at most hi), returned as the difference t (same spectral
// frame as v): zero in cones that are already well centred.
void cone_centrality_correction(const ConeProgram& p, const Eigen::VectorXd& v, double lo, double hi, Eigen::VectorXd& t);

double cone_max_step(const ConeProgram& p, const Eigen::VectorXd& l, const Eigen::VectorXd& u);
// The same along u + v, without forming it (a trial sum of directions).
double cone_max_step_of_sum(const ConeProgram& p, const Eigen::VectorXd& l, const Eigen::VectorXd& u,
                            const Eigen::VectorXd& v);

// Smallest u0 - ||u1|| over the cones (negative when u is outside some cone).
double cone_min_margin(const ConeProgram& p, const Eigen::VectorXd& u);

}  // namespace strictmin::socp
