#pragma once
// Bisection on the level of a Section 7 measure for fixed frames (paper Section 7: "a
// binary-search (bisection) L-infinity optimization"). For fixed frames the largest
// frame-relative value max_T (qc: |b_T| / <a_T, r_T>) is quasi-convex in the map, so the
// feasible levels form an interval [L*, inf) and bisection on the level is exact.
#include <Eigen/Core>
#include <string>

#include "strictmin/measures/measures.h"
#include "solvers/qc/qc_program.h"
#include "solvers/qc/sparse_socp.h"

namespace strictmin::qc {

enum class Verdict { Feasible, Infeasible, Undecided };

// One feasibility question: is there a map with frame value <= level_T on every active
// element (levels: `free_level` for free elements, bounds[i] >= 0 for bounded ones)?
// Feasible: a witness map (x) was found, its largest free frame value in `value`.
// Infeasible: a dual bound of the slack program, corrected to exact dual feasibility
// (sparse_socp.h: corrected_dual_bound), is positive. Undecided: the optimum slack is 0 to the solver's accuracy.
struct FeasibilityTest {
  Verdict verdict = Verdict::Undecided;
  Eigen::VectorXd x;
  double value = 0;
  int ipm_iterations = 0;
  bool capped = false;  // undecided because the program reached its interior-point cap
  std::string message;
};

struct BisectionSetup {
  Measure measure = Measure::Quasiconformal;
  const ConformalParts* parts = nullptr;
  Eigen::VectorXd frames;      // 2 per active element
  Eigen::VectorXd slack_scale; // per active element (qc_program.h: slack_scales; empty: 1)
  Eigen::VectorXd bounds;      // per active element, < 0: free
  SparseSocpSettings ipm;
  SparseCholeskyCache* cache = nullptr;
};

FeasibilityTest test_level(const BisectionSetup& setup, double free_level, const Eigen::VectorXd& x_start);

// The interior-point settings of a feasibility test. The witness and the certificate stop it
// early, so its own criterion only says when to give up: the gap is taken down to 1e-12 (the
// slack is of order 1), and each Newton system is refined up to 10 times (not 3), so that
// levels close below the optimum, where the optimal slack is small but positive, can still
// be certified.
SparseSocpSettings feasibility_settings(int max_iterations);

struct BisectionOutcome {
  Eigen::VectorXd x;           // the lowest feasible map found
  double value = 0;            // its largest free frame value (+inf: none found)
  double lower = 0;            // bracket's lower end (certified or undecided)
  double certified_lower = std::numeric_limits<double>::quiet_NaN();  // largest level certified infeasible
  int steps = 0, ipm_iterations = 0;
  int capped_tests = 0;  // tests left undecided by the interior-point cap (--max-iterations)
  // The certified bracket [max(floor, certified_lower), value] is within the tolerance.
  bool converged = false;
  // Not converged, but the bracket [lower, value] is: its lower end is a level that the test
  // could not decide (twice at the closing levels), not a certificate.
  bool closed_undecided = false;
  bool feasible = false;       // some feasible map (the start counts when its value is finite)
  std::string message;
};

// One feasibility test at `level` from out.x, counted in out (steps, interior-point
// iterations); a witness becomes out's map and lowers out.value to its own value.
FeasibilityTest test_into(const BisectionSetup& setup, double level, BisectionOutcome& out);

// From the map x0 (its free frame value is the first upper end; +inf: the first test is at
// level `cap`), down to a bracket of width tolerance * max(1, upper). `floor` is a certified
// lower end (both measures are >= 1).
BisectionOutcome bisect(const BisectionSetup& setup, const Eigen::VectorXd& x0, double floor, double cap,
                        double tolerance, int max_steps);

// The largest frame value over the free active elements of x.
double free_max(const BisectionSetup& setup, const Eigen::VectorXd& x);

}  // namespace strictmin::qc
