#pragma once
// Relaxation-based strict minimization (paper Algorithm 3): sweeps over the free vertices,
// each solving its 1-ring L-infinity problem exactly (one_ring.h) and accepting the move
// only if it lowers the ring's maximum, so that no sweep makes the distortion vector worse
// in the strict order. Vertices are coloured so that no two of one colour share an
// element; each colour moves in parallel.
#include <Eigen/Core>
#include <functional>
#include <memory>
#include <vector>

#include "strictmin/problem/problem.h"
#include "strictmin/solvers/result.h"
#include "strictmin/solvers/vertex_colouring.h"

namespace strictmin {

struct RelaxOptions {
  int sweeps = 50;
  // Stop early when the largest vertex move of a sweep is below this (absolute, in the
  // units of the map). 0: always run every sweep.
  double move_tolerance = 0;
  // After each sweep: sweep index (1-based), current maximum field deviation, elapsed
  // seconds (IterationRecord has no field for the largest move: see largest_move).
  std::function<void(const IterationRecord&)> progress;
  // After each sweep, if set: sweep index (1-based) and the largest distance a vertex moved.
  std::function<void(int, double)> largest_move;
};

// Precomputed structure for repeated sweeps on one mesh and fixed set (the ring of every
// free vertex, the colouring). Targets may change between sweeps (ARAP local steps).
class RelaxSweeper {
 public:
  explicit RelaxSweeper(const Problem& problem);
  // One sweep over every free vertex, colour by colour, moving X (#V by image_dim) in place.
  // Returns the largest distance a vertex moved.
  double sweep(const Problem& problem, Eigen::MatrixXd& X) const;
  // The same; also sets *max_distortion (if not null) to the largest field deviation over all
  // elements after the sweep, taken from the rings' values (no extra pass over the mesh).
  double sweep(const Problem& problem, Eigen::MatrixXd& X, double* max_distortion) const;
  int num_colours() const;
  const VertexColouring& colouring() const;

 private:
  struct Impl;
  std::shared_ptr<const Impl> impl_;
};

// Runs up to options.sweeps sweeps from `initial` (#V by image_dim; fixed vertices are taken
// from problem.positions). Result.history has one record per sweep; iterations = sweeps run.
Result relax(const Problem& problem, const Eigen::MatrixXd& initial, const RelaxOptions& options = {});

}  // namespace strictmin
