#pragma once
// Internal: relaxation sweeps that move each group of copies (seam wedges) as one point.
#include <memory>

#include "strictmin/problem/problem.h"
#include "strictmin/solvers/relax.h"
#include "strictmin/solvers/vertex_colouring.h"

namespace strictmin::relax_detail {

// problem.copy_base must be set (one entry per vertex); fixed vertices and groups with
// copy_base -1 hold still.
// The status of a relaxation run (relax and relax_with_copies): the criterion is the
// requested number of sweeps, or, with a move tolerance, no vertex moving more than it (then
// running out of sweeps first is the cap).
void set_relax_status(Result& result, const RelaxOptions& options, bool moves_settled);

// Records sweep `record` (its iteration, maximum, largest_move and time set) in the result's
// history and reports it; true when its largest move is below the move tolerance.
bool record_sweep(Result& result, const RelaxOptions& options, const IterationRecord& record);

Result relax_with_copies(const Problem& problem, const Eigen::MatrixXd& initial, const RelaxOptions& options);

// The sweep of relax_with_copies kept across calls, one sweep a call: local-global's relax
// steps (--measure arap|asap --method relax on a seamless problem), whose targets change
// between sweeps. Same preconditions as relax_with_copies; sweeps are serialized.
class CopiesSweeper {
 public:
  explicit CopiesSweeper(const Problem& problem);
  ~CopiesSweeper();
  // One sweep of X (#V by 2) in place for the problem's current targets: the largest move;
  // *max_distortion (if not null) the largest field deviation after the sweep.
  double sweep(const Problem& problem, Eigen::MatrixXd& X, double accept_tolerance, double* max_distortion) const;
  const VertexColouring& colouring() const;  // of the groups' surface vertices

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace strictmin::relax_detail
