#pragma once
// Orientation checks shared by the no-flips options (issue: "no new flips"): which elements
// a map flips that another map did not, and the cut-back of a step so that it adds none.
#include <Eigen/Core>

#include "strictmin/problem/problem.h"
#include "strictmin/solvers/result.h"

namespace strictmin {

// Per element, 1 when det J_T > 0 for the map X (#V by n); non-square Jacobians (3D
// surfaces) always count as positive.
Eigen::VectorXi positively_oriented(const Problem& problem, const Eigen::MatrixXd& X);

// Elements with det J_T > 0 under `from` and det J_T <= 0 under `to`.
int flips_added(const Problem& problem, const Eigen::MatrixXd& from, const Eigen::MatrixXd& to);

// from + t (to - from) for the largest t in {1, 1/2, 1/4, ..., 2^-30} that adds no flip to
// `from`, or `from` itself when none does. *fraction (if not null) gets t (0 for `from`).
Eigen::MatrixXd cut_back_to_no_new_flips(const Problem& problem, const Eigen::MatrixXd& from,
                                         const Eigen::MatrixXd& to, double* fraction = nullptr);

// A one-solve result cut back from `start` so that it adds no flip (--no-flips with fd): when
// the cut changes the map, its distortion (field deviation) is recomputed, the message says
// so, and a solved status becomes stalled: the cut map need not meet the solver's criterion.
// lower_bound stays (it bounds every map).
void cut_back_result(const Problem& problem, const Eigen::MatrixXd& start, Result& result);

}  // namespace strictmin
