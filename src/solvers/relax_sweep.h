#pragma once
// Internals of the relaxation (relax.h): the per-mesh sweep structure and one sweep.
#include <Eigen/Core>
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "strictmin/problem/problem.h"
#include "strictmin/solvers/vertex_colouring.h"

namespace strictmin::relax_detail {

// relax() keeps every element's J_T - R_T up to date as vertices move, and recomputes it
// from the positions every this many sweeps so that rounding cannot pile up.
constexpr int kRefreshInterval = 8;

// Jacobians are n by m: n = dim (the image dimension, the map's columns), m = domain_dim;
// 2 by 2 (planar), 3 by 3 (tets) or 3 by 2 (a triangle surface in 3D, each triangle in its
// own frame).
struct SweepData {
  int dim = 2;
  int domain_dim = 2;
  VertexColouring colouring;
  std::vector<int> corners;       // #E * (m+1) vertex indices
  // #E * (m+1) * (m+1): corner j of e at (e*(m+1)+j)*(m+1): its gradient g, then 1 / |g|^2
  std::vector<double> gradients;
  std::vector<int> ring_start;    // per position in colouring.order, into ring (+1 at the end)
  // element << 3 | corner << 1 | last, where last = 1 when, of the element's free corners,
  // this vertex moves last in a sweep (it then sees the element's final value).
  std::vector<uint32_t> ring;
  std::vector<double> weights;    // #E areas (volumes), for the acceptance test
  std::vector<int> closed;        // elements without a free corner: they never change
  int max_ring = 0;
  // RelaxOptions::no_flips: moves stay in the ring's kernel (det J_T > 0 where it was).
  // Square Jacobians only (check_no_flips).
  bool no_flips = false;
  // Per position in colouring.order: the support of the vertex's last ring solve (up to 4
  // term indices within its ring, a byte each, 0xff = none), the next solve's first guess.
  // Relaxed atomics: only a heuristic, but sweeps on one sweeper may run concurrently.
  std::unique_ptr<std::atomic<uint32_t>[]> guesses;
};

// J_T - R_T of every element (column-major n by m blocks) for the current map.
struct Deviations {
  std::vector<double> M;
  int age = -1;  // sweeps since computed from the positions; -1: not computed
};

// Fills s (the Problem already checked: check_problem): packed elements and gradients, the colouring
// of the free vertices, their rings in sweep order.
void build(const Problem& p, SweepData& s);

// Throws InputError when no_flips is asked for a problem whose Jacobians are not square (a
// triangle surface in 3D: a 3 by 2 map has no sign of orientation, docs/arap.md).
void check_no_flips(const Problem& p, bool no_flips, const std::string& who = "relax");

// One sweep over every free vertex, colour by colour, moving X in place; dev is computed
// from X first if dev.age < 0, then kept up to date. A vertex moves to its ring's minimax
// position only if that improves the ring in the strict order with values within
// accept_tolerance * (ring maximum) counted as equal (RelaxOptions). Returns the largest
// move; sets *max_distortion (if not null) to the largest field deviation after the sweep.
double sweep_any(const SweepData& s, const Problem& p, Eigen::MatrixXd& X, Deviations& dev, double accept_tolerance,
                 double* max_distortion);

}  // namespace strictmin::relax_detail
