#pragma once
// When solve_linf tries the active-set solves (linf_active_set.h) and on which elements
// (private). Only for tight tolerances, once the main iterates are near the optimum:
// - the bound from the elements within reach of the maximum (reach: a multiple of the
//   iterates' certified gap, widened tenfold on each retry, at most kMaxBoundAttempts tries);
// - the map from the same elements widened by rings, tried again at a later iterate while k
//   stays above a bound close to it (at most kMaxMaps maps);
// - before those, probes: the bound and at once the map, on iterates where the method's own
//   gap is below kProbeGap and few elements are within reach of the maximum (at most
//   kMaxProbes, one an iteration; they do not count against the attempts above). A probe
//   looks at where the iterates are heading as well as at the iterate (see probe()).
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "linf_main_solve.h"
#include "solvers/linf_active_set.h"
#include "linf_program.h"
#include "solvers/socp/residuals.h"
#include "solvers/socp/settings.h"

namespace strictmin::linf_detail {

class ActiveSetPolicy {
 public:
  // Loose tolerances (the strict minimizers' later levels) reach theirs about as soon from
  // the iterates' own certificate, and a restriction tried early costs more.
  static constexpr double kTightestLooseTolerance = 1e-6;
  // Near: the method's gap or dual objective within kNear tolerances of k; or within kSettled
  // tolerances once the maps have settled (the last step lowered k by under kSettledStep of
  // the certified gap: the gap is then the dual's lag).
  static constexpr double kNear = 1e3;
  static constexpr double kSettled = 1e4;
  static constexpr double kSettledStep = 1e-2;
  // The reach: kReach times the iterates' certified gap, times kReachGrowth per retry.
  static constexpr double kReach = 1e3;
  static constexpr double kReachGrowth = 10;
  static constexpr int kMaxBoundAttempts = 3;
  // A retry waits until the iterates' gap falls below kRetryGapFraction of the gap left to
  // the last restriction's bound (or their dual objective passes that bound).
  static constexpr double kRetryGapFraction = 0.1;
  // A retry whose elements grew by less than this factor cannot do better: the last.
  static constexpr double kSameElements = 1.2;
  // The map helps only once the bound is within kBoundClose tolerances of k.
  static constexpr double kBoundClose = 1e2;
  static constexpr int kMaxMaps = 2;
  // The map's restriction: up to kMapRings rings around the chosen elements, while at most
  // kMapGrowth times as many.
  static constexpr int kMapRings = 2;
  static constexpr double kMapGrowth = 3.0;
  // With equalities (the seamless problems), whose elements at the maximum can be a handful
  // (igea_100k: 6), the rings may reach kMapMinElements: a ring around 6 elements is already
  // 3 times as many, and without it every vertex of theirs is held and the map moves nothing.
  static constexpr size_t kMapMinElements = 300;
  // At most max(kCapMin, E / kCapDivisor) elements in a restriction (the reach shrinks tenfold
  // until they fit).
  static constexpr size_t kCapMin = 1000;
  static constexpr int kCapDivisor = 20;
  // Probes. The restriction can hold the dual's support long before the main iterates'
  // certificate closes: on igea_100k (seams) the 23 elements nearest the maximum at a method
  // gap of 4e-2 give the optimum, four iterations before the tests above would try; on horse
  // the 1,353 elements nearest the heading's maximum (below) at a gap of 1.3e-2 give it, five
  // iterations early. kProbeGap is relative to max(1, |k|), as the tolerance.
  static constexpr double kProbeGap = 5e-2;
  // The heading: 2 x_k - x_(k-1), the last step taken once more (see probe()). Its elements
  // within kHeadingReach method gaps of its maximum (or k, if lower), the reach halved up to
  // kHeadingHalvings times to fit the limit below. A probe takes them with the iterate's own
  // elements within reach: horse's support at iteration 10 lies within 2.3 gaps of the
  // heading's maximum (the iterate's elements within reach miss part of it), but at 4e-2 only
  // 4 of igea's 6 are within 3 gaps of the heading's maximum (all within reach of the
  // iterate's).
  static constexpr double kHeadingReach = 4;
  static constexpr int kHeadingHalvings = 2;
  // A probe is made only when its elements are at most 1 / kProbeDivisor of them, and its map
  // takes kMapRings rings around the heading's elements, more up to kProbeMapRings until it
  // holds kMapMinElements, while at most 1 / kProbeMapDivisor of them: a probe that misses
  // then costs under an iteration (horse: 0.06 s for the bound and 0.07 s for the map,
  // against 0.22 s an iteration). Cow's map from 16 elements misses by 4e-8 with 2 rings (81
  // elements) and holds the optimum with 8 (295): 11 -> 9 iterations; 6 rings everywhere
  // cost horse 0.25 s.
  static constexpr int kProbeDivisor = 40;
  static constexpr int kProbeMapDivisor = 10;
  static constexpr int kProbeMapRings = 8;
  static constexpr int kMaxProbes = 3;

  ActiveSetPolicy(const MainProgram& mp, const Eigen::VectorXd& effective_bounds);

  // Called at each certified iterate s (distortions d, its k): tries a bound and/or a map
  // when it is time, updating best.
  void consider(const socp::IpmState& s, const Eigen::VectorXd& d, double k, const socp::IpmIteration& info,
                BestSoFar& best);
  // Whether consider() will probe this iterate (x, its distortions d and k): the caller then
  // certifies it. Chooses the probe's elements.
  bool probe_due(const Eigen::VectorXd& x, const Eigen::VectorXd& d, double k, const socp::IpmIteration& info);
  // Called with every iterate, after the two above: the next probe's heading starts from it.
  void remember(const Eigen::VectorXd& x);

 private:
  // Whether a probe can still come: options allow it, the program has equalities, and
  // neither the probes nor the late attempts have started or run out.
  bool probes_left() const;
  std::vector<int> near_maximum(const Eigen::VectorXd& d, double k, double reach, double tol) const;
  // The late attempts' map region: chosen and up to kMapRings rings around it (kMapGrowth).
  std::vector<int> map_region(const std::vector<int>& chosen) const;
  void try_map(const std::vector<int>& chosen, const Eigen::MatrixXd& X, BestSoFar& best);
  void try_bound(const std::vector<int>& chosen, const Eigen::MatrixXd& X, double tol, BestSoFar& best);
  void probe(const socp::IpmState& s, double tol, BestSoFar& best);
  // The probe's map region around `elements` (rings, see kProbeMapRings).
  std::vector<int> probe_map_region(const std::vector<int>& elements) const;
  // The restricted solves themselves: each raises best where it does better, and returns its bound / nothing.
  double restricted_bound(const std::vector<int>& chosen, const Eigen::MatrixXd& X, BestSoFar& best) const;
  void restricted_map(const std::vector<int>& region, const Eigen::MatrixXd& X, BestSoFar& best) const;
  ActiveSetSolve solve_map(const std::vector<int>& region, const Eigen::MatrixXd& X) const;
  void keep_map(const ActiveSetSolve& m, BestSoFar& best) const;

  const MainProgram& mp_;
  const Eigen::VectorXd& effective_bounds_;
  int attempts_ = 0;
  int last_iteration_ = -1;  // of the last bound tried
  double bound_ = -kInf;     // of the last restriction tried
  int maps_ = 0;
  size_t elements_ = 0;      // in the last restriction tried
  int probes_ = 0;
  int due_iteration_ = -1;   // the iterate probe_due chose probe_elements_ for
  std::vector<int> probe_elements_;    // the probe's bound: the iterate's and the heading's
  std::vector<int> heading_elements_;  // near the heading's maximum: the probe's map
  Eigen::VectorXd previous_x_;         // the iterate before the current one (probes only)
  Eigen::VectorXd heading_, heading_distortions_;
};

}  // namespace strictmin::linf_detail
