#pragma once
// Internals of the relaxation (relax.h): the per-mesh sweep structure and one sweep.
#include <Eigen/Core>
#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "strictmin/problem/problem.h"
#include "strictmin/solvers/vertex_colouring.h"

namespace strictmin::relax_detail {

// relax() keeps every element's J_T - R_T up to date as vertices move, and recomputes it
// from the positions every this many sweeps so that rounding cannot pile up.
constexpr int kRefreshInterval = 8;

struct SweepData {
  int dim = 2;
  VertexColouring colouring;
  std::vector<int> corners;       // #E * (d+1) vertex indices
  // #E * (d+1) * (d+1): corner j of e at (e*(d+1)+j)*(d+1): its gradient g, then 1 / |g|^2
  std::vector<double> gradients;
  std::vector<int> ring_start;    // per position in colouring.order, into ring (+1 at the end)
  // element << 3 | corner << 1 | last, where last = 1 when, of the element's free corners,
  // this vertex moves last in a sweep (it then sees the element's final value).
  std::vector<uint32_t> ring;
  std::vector<double> weights;    // #E areas (volumes), for the acceptance test
  std::vector<int> closed;        // elements without a free corner: they never change
  int max_ring = 0;
  // RelaxOptions::no_flips: moves stay in the ring's kernel (det J_T > 0 where it was).
  bool no_flips = false;
  // Per position in colouring.order: the support of the vertex's last ring solve (up to 4
  // term indices within its ring, a byte each, 0xff = none), the next solve's first guess.
  // Relaxed atomics: only a heuristic, but sweeps on one sweeper may run concurrently.
  std::unique_ptr<std::atomic<uint32_t>[]> guesses;
};

// J_T - R_T of every element (column-major d by d blocks) for the current map.
struct Deviations {
  std::vector<double> M;
  int age = -1;  // sweeps since computed from the positions; -1: not computed
};

// Checks the problem (InputError) and fills s: packed elements and gradients, the colouring
// of the free vertices, their rings in sweep order.
void build(const Problem& p, SweepData& s);

// One sweep over every free vertex, colour by colour, moving X in place; dev is computed
// from X first if dev.age < 0, then kept up to date. A vertex moves to its ring's minimax
// position only if that improves the ring in the strict order with values within
// accept_tolerance * (ring maximum) counted as equal (RelaxOptions). Returns the largest
// move; sets *max_distortion (if not null) to the largest field deviation after the sweep.
double sweep_any(const SweepData& s, const Problem& p, Eigen::MatrixXd& X, Deviations& dev, double accept_tolerance,
                 double* max_distortion);

}  // namespace strictmin::relax_detail
