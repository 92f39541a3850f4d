#pragma once
// Lawson's iteratively reweighted least squares for the L-infinity problem (Rice & Usow
// 1968), the baseline of the paper's Section 6: weighted L2 solves with per-element weights
// w_T updated as w_T <- w_T D_T / sum_S A_S w_S D_S. Its convergence rate depends on the
// ratio of the largest to the second largest distortion, so it improves on L2 but stays
// away from the strict minimizer.
#include <functional>
#include <string>

#include "strictmin/problem/problem.h"
#include "strictmin/solvers/result.h"

namespace strictmin {

struct IrlsOptions {
  int iterations = 50;
  std::function<void(const IterationRecord&)> progress;

  // Range: iterations >= 1 (--method l2 is the plain L2 map).
  bool is_valid(std::string* why = nullptr) const;
};

Result solve_irls(const Problem& problem, const IrlsOptions& options = {});

}  // namespace strictmin
