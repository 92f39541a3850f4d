#pragma once
// L_p field deviation: minimize sum_T A_T D_T^p for a given p >= 2, by Newton's method with
// a backtracking line search, with continuation p = 4, 8, 16, ... up to the requested p
// (Polya's algorithm: the L_p minimizers approach the L-infinity / strict minimizer as p
// grows; the paper's Figure 13 shows they move away again for very large p).
#include <functional>
#include <string>

#include "strictmin/problem/problem.h"
#include "strictmin/solvers/result.h"

namespace strictmin {

struct LpOptions {
  double p = 16;
  int max_iterations = 200;           // Newton iterations in all stages together
  double tolerance = 1e-10;           // stop a stage when the Newton decrement^2 / 2 <= tolerance * f
  std::function<void(const IterationRecord&)> progress;

  // Ranges: p >= 2 (finite), max_iterations >= 1, tolerance > 0.
  bool is_valid(std::string* why = nullptr) const;
};

Result solve_lp(const Problem& problem, const LpOptions& options = {});

}  // namespace strictmin
