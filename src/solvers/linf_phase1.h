#pragma once
// Phase 1 of solve_linf (private): when the start misses some fixed bound k_T, find a map
// that meets them all, or certify that none does: min t s.t. D_T <= k_T + t over the bounded
// elements only (always feasible).
#include <Eigen/Core>
#include <string>

#include "linf_program.h"
#include "strictmin/problem/problem.h"
#include "strictmin/solvers/linf.h"
#include "solvers/socp/fd_program.h"

namespace strictmin::linf_detail {

struct Phase1 {
  bool feasible = true;
  bool certified = false;     // not feasible, and certified so (else: undecided)
  double t = -kInf;           // max_T (D_T - k_T) at the returned map
  double lower_bound = -kInf; // certified: no map does better than this t
  Eigen::MatrixXd X;          // the map (vertices outside the bounded elements unchanged)
  int iterations = 0;
  std::string message;
  // The vertices outside the bounded elements are held, which is exact without equalities
  // (no bounded element sees them) but a restriction when an equality ties one of them to a
  // moving vertex (a seam partner): then "no map meets the bounds" holds only for maps that
  // keep those vertices where X0 has them, and is not certified.
  bool restricted = false;
};

// Vertices of no bounded element stay where X0 has them; a part of the bounded elements
// without any fixed vertex is anchored at one vertex (D_T is translation invariant). With
// equalities that tie held vertices to moving ones (Phase1::restricted), an infeasible
// outcome is never certified.
Phase1 run_phase1(const Problem& p, const socp::ElementClasses& cls, const Eigen::VectorXd& bounds,
                  const Eigen::MatrixXd& X0, const LinfOptions& options);

}  // namespace strictmin::linf_detail
