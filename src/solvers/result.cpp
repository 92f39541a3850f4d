#include "strictmin/solvers/result.h"

namespace strictmin {

std::string status_name(SolveStatus s) {
  switch (s) {
    case SolveStatus::Solved: return "solved";
    case SolveStatus::MaxIterations: return "max-iterations";
    case SolveStatus::NumericalError: return "numerical-error";
    case SolveStatus::Infeasible: return "infeasible";
  }
  return "?";
}

}  // namespace strictmin
