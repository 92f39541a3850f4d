#pragma once
// Relaxation-based strict minimization (paper Algorithm 3): sweeps over the free vertices,
// each solving its 1-ring L-infinity problem exactly (one_ring.h) and accepting the move
// only if it lowers the ring's maximum, so that no sweep makes the distortion vector worse
// in the strict order, and only if the ring as a whole improves in the strict order with a
// small tolerance (accept_tolerance below). Vertices are coloured so that no two of one colour share an
// element; each colour moves in parallel.
#include <Eigen/Core>
#include <functional>
#include <string>
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
  // A move that lowers the ring maximum must also improve the ring's distortion in the strict
  // order when values within accept_tolerance * (ring maximum) count as equal. Without it
  // (0), moves that lower the maximum by a rounding-sized amount while raising the ring's
  // other elements up to it are taken, and the sweeps creep every element up to the top
  // level (the Figure 2 square ends with all 800 triangles at 0.3). Larger values stop
  // earlier, further from the L-infinity optimum when starting from L2 (docs/strict.md).
  double accept_tolerance = 1e-4;
  // No new flips (paper Section 5.3's remark): every move stays in the ring's kernel, det J_T
  // > 0 on each ring element that has it before the move (a half-space in the vertex's
  // position by the matrix determinant lemma, so the 1-ring problem stays convex); a move
  // past the kernel's boundary is shortened into it (which still lowers the ring's maximum:
  // its terms are convex).
  bool no_flips = false;
  // After each sweep: sweep index (1-based), current maximum field deviation, the largest
  // distance a vertex moved (largest_move), elapsed seconds.
  std::function<void(const IterationRecord&)> progress;

  // Ranges: sweeps >= 0, move_tolerance >= 0, accept_tolerance in [0, 1).
  bool is_valid(std::string* why = nullptr) const;
};

// Precomputed structure for repeated sweeps on one mesh and fixed set (the ring of every
// free vertex, the colouring). Targets may change between sweeps (ARAP local steps).
class RelaxSweeper {
 public:
  // accept_tolerance, no_flips: as RelaxOptions. Throws InputError for an accept_tolerance
  // outside [0, 1) or a problem that fails check_problem.
  explicit RelaxSweeper(const Problem& problem, double accept_tolerance = RelaxOptions{}.accept_tolerance,
                        bool no_flips = false);
  // One sweep over every free vertex, colour by colour, moving X (#V by image_dim) in place.
  // Returns the largest distance a vertex moved. Throws InputError when the problem's vertex
  // or element count is not the construction's, or X is not #V by image_dim.
  double sweep(const Problem& problem, Eigen::MatrixXd& X) const;
  // The same; also sets *max_distortion (if not null) to the largest field deviation over all
  // elements after the sweep, taken from the rings' values (no extra pass over the mesh).
  double sweep(const Problem& problem, Eigen::MatrixXd& X, double* max_distortion) const;
  int num_colours() const;
  const VertexColouring& colouring() const;

 private:
  struct Impl;
  std::shared_ptr<const Impl> impl_;
  double accept_tolerance_;
};

// Runs up to options.sweeps sweeps from `initial` (#V by image_dim; fixed vertices are taken
// from problem.positions). Result.history has one record per sweep; iterations = sweeps run.
Result relax(const Problem& problem, const Eigen::MatrixXd& initial, const RelaxOptions& options = {});

}  // namespace strictmin
