#include "solvers/strict_constants.h"

#include <algorithm>
#include <limits>

#include "strictmin/measures/field_deviation.h"

namespace strictmin {

std::vector<char> movable_elements(const Problem& p) {
  std::vector<char> movable(p.num_elements(), 0);
  for (int e = 0; e < p.num_elements(); ++e)
    for (int j = 0; j < p.corners(); ++j) movable[e] |= p.fixed[p.elements(e, j)] ? 0 : 1;
  return movable;
}

double bound_constant_elements(const Problem& p, const std::vector<char>& movable, Eigen::VectorXd& bounds) {
  double largest = -std::numeric_limits<double>::infinity();
  for (int e = 0; e < p.num_elements(); ++e) {
    if (movable[e]) continue;
    const double value = field_deviation(p, p.positions, e);
    bounds(e) = std::max(bounds(e), value);
    largest = std::max(largest, value);
  }
  return largest;
}

Result unmovable_answer(const Problem& p) {
  Result out;
  out.positions = p.positions;
  out.distortion = field_deviation(p, p.positions);
  out.lower_bound = out.distortion.size() ? out.distortion.maxCoeff() : 0.0;
  out.message = "nothing to optimise: every element has all its vertices fixed";
  return out;
}

}  // namespace strictmin
