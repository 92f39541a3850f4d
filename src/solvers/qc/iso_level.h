#pragma once
// The least iso level for fixed frames in one cone program (qc_program.h: iso_program)
// instead of a bisection over feasibility tests: minimize S directly, its certified lower
// bound from the dual (sparse_socp.h: corrected_dual_bound). When the program stops short of
// a certified optimum, the bisection's closing tests (bisection.h: test_level) just below the
// best map's value decide the bracket, or leave it closed only through an undecided level.
#include <Eigen/Core>

#include "solvers/qc/bisection.h"

namespace strictmin::qc {

// From the map x0 (feasible for the frames: a finite free frame value; the caller bisects
// otherwise), the map of least largest free frame value for setup's frames and bounds, to
// tolerance * max(1, value) with a certified lower end (BisectionOutcome's fields as
// bisect's; steps counts cone programs).
BisectionOutcome minimize_iso_level(const BisectionSetup& setup, const Eigen::VectorXd& x0, double tolerance);

}  // namespace strictmin::qc
