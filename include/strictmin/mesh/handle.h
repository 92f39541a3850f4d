#pragma once
// A positional constraint: vertex (0-based) goes to position.
#include <Eigen/Core>

namespace strictmin {

struct Handle {
  int vertex = -1;
  Eigen::VectorXd position;
};

}  // namespace strictmin
