#include "element_bounds_check.h"

#include <cmath>
#include <sstream>

#include "strictmin/io/input_error.h"

namespace strictmin {

void check_element_bounds(const Eigen::VectorXd& bounds, int elements, const std::string& solver) {
  if (bounds.size() != 0 && bounds.size() != elements)
    throw InputError(solver + ": element_bounds has " + std::to_string(bounds.size()) + " entries, the problem has " +
                     std::to_string(elements) + " elements");
  for (Eigen::Index e = 0; e < bounds.size(); ++e) {
    const double b = bounds(e);
    if (std::isfinite(b) && b <= kLargestElementBound) continue;
    std::ostringstream os;
    os << solver << ": element " << e << "'s bound " << b
       << (std::isfinite(b) ? " is beyond 1e100 (the solvers take bounds up to 1e100"
                            : " is not finite (")
       << "; a free element's bound is negative)";
    throw InputError(os.str());
  }
}

}  // namespace strictmin
