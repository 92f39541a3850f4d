#include "strictmin/solvers/result.h"

#include <algorithm>

namespace strictmin {

std::string status_name(SolveStatus s) {
  switch (s) {
    case SolveStatus::Solved: return "solved";
    case SolveStatus::AlmostSolved: return "almost-solved";
    case SolveStatus::MaxIterations: return "max-iterations";
    case SolveStatus::Stalled: return "stalled";
    case SolveStatus::NumericalError: return "numerical-error";
    case SolveStatus::Infeasible: return "infeasible";
  }
  return "?";
}

SolveStatus worse_status(SolveStatus a, SolveStatus b) { return std::max(a, b); }

bool status_usable(SolveStatus s) { return s != SolveStatus::NumericalError && s != SolveStatus::Infeasible; }

SolveStatus decide_status(const StopState& s) {
  if (s.infeasible) return SolveStatus::Infeasible;
  if (s.criterion_met) return SolveStatus::Solved;
  if (s.failed) return SolveStatus::NumericalError;
  if (s.within_acceptable) return SolveStatus::AlmostSolved;
  if (s.stalled) return SolveStatus::Stalled;
  if (s.cap_reached) return SolveStatus::MaxIterations;
  return SolveStatus::NumericalError;
}

bool Result::usable() const { return status_usable(status) && positions.size() > 0 && positions.allFinite(); }

}  // namespace strictmin
