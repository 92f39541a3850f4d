// One relaxation sweep (paper Algorithm 3, Section 5.3; docs/maths.md section 2, "One vertex
// at a time"): each free vertex v solves min_q max_{T in ring(v)} ||J_T - R_T||^2 with
// every other vertex fixed and moves only if that lowers its ring's maximum; vertices of
// one colour share no element, so they move in parallel. Jacobians are n by m (image by
// domain dimension): 2 by 2 (planar), 3 by 3 (tets) or 3 by 2 (triangles of a 3D surface,
// each in its own frame); the vertex moves in R^n either way.
#include "relax_sweep.h"

#include <Eigen/LU>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "strictmin/io/input_error.h"
#include "ring_order.h"
#include "strictmin/solvers/one_ring.h"

namespace strictmin::relax_detail {

// A move must lower the ring's maximum squared distortion by at least this much (relative):
// a strict decrease that rounding cannot fake. Below it, the vertex stays.
constexpr double kAcceptRelative = 1e-13;
constexpr uint32_t kNoGuess = 0xffffffffu;

inline uint32_t pack_entry(int element, int corner, bool last) {
  return static_cast<uint32_t>(element) << 3 | static_cast<uint32_t>(corner) << 1 | (last ? 1u : 0u);
}

template <int d>
using Vec = Eigen::Matrix<double, d, 1>;
template <int n, int m>
using Mat = Eigen::Matrix<double, n, m>;

template <int n, int m>
void compute_deviations(const SweepData& s, const Problem& p, const Eigen::MatrixXd& Xm, Deviations& dev) {
  const int E = static_cast<int>(s.corners.size()) / (m + 1);
  dev.M.resize(static_cast<size_t>(E) * n * m);
  const double* X = Xm.data();
  const Eigen::Index xrows = Xm.rows(), rrows = p.targets.rows();
  const double* R = p.targets.data();
  tbb::parallel_for(tbb::blocked_range<int>(0, E, 2048), [&](const tbb::blocked_range<int>& range) {
    for (int e = range.begin(); e != range.end(); ++e) {
      Eigen::Map<Mat<n, m>> M(&dev.M[static_cast<size_t>(e) * n * m]);
      for (int col = 0; col < m; ++col)
        for (int r = 0; r < n; ++r) M(r, col) = -R[col * rrows + e * n + r];
      for (int i = 0; i < m + 1; ++i) {
        const Eigen::Map<const Vec<m>> g(&s.gradients[(e * (m + 1) + i) * (m + 1)]);
        const int v = s.corners[e * (m + 1) + i];
        for (int r = 0; r < n; ++r) M.row(r) += X[r * xrows + v] * g.transpose();
      }
    }
  });
  dev.age = 0;
}

template <int d>
struct Scratch {
  std::vector<RingTerm<d>> terms;
  std::vector<double> current;  // D_T^2 before the move
  // For the acceptance test: D_T before and after, areas, sort scratch.
  std::vector<double> before, after, area;
  std::vector<int> order;
};

struct Accumulator {
  double move = 0;  // largest move
  double top = 0;   // largest D_T^2 after the sweep over the elements seen so far
};

// Whether moving by q (which lowers the ring maximum from current, squared) is accepted: the
// ring's distortion must improve in the strict order with values within tolerance * (ring
// maximum) counted as equal. Without the tolerance, a move that lowers the maximum by a
// rounding-sized amount while raising the ring's other elements up to it would count as
// progress, and sweeps would creep every element up to the top level.
// Inlined into each sweep (two sweeps, 3x3 and 3x2, call the d = 3 copy; left to itself the
// compiler then keeps it out of line, 0.4% more instructions on tet sweeps).
template <int d>
[[gnu::always_inline]] inline bool accept_move(const SweepData& s, Scratch<d>& sc, int first, int n,
                                               const Vec<d>& q, double value, double current, double tolerance) {
  const double top = std::sqrt(current), tau = tolerance * top;
  // value = the new ring maximum, squared: the top level itself went down (the common case).
  if (value < (top - tau) * (top - tau)) return true;
  for (int k = 0; k < n; ++k) {
    const RingTerm<d>& t = sc.terms[k];
    sc.after[k] = std::sqrt(t.a * (q - t.centre).squaredNorm() + t.b);
  }
  for (int k = 0; k < n; ++k) {
    sc.before[k] = std::sqrt(sc.current[k]);
    sc.area[k] = s.weights[s.ring[first + k] >> 3];
  }
  return ring_improves(sc.before.data(), sc.after.data(), sc.area.data(), n, tau, sc.order.data());
}

// The largest fraction t in [0, 1] of the move q that keeps the ring in its kernel: every
// ring element with det J_T > 0 keeps det > 0. Moving the vertex by t q changes J_T by
// t q g^T, and det(J + t q g^T) = det J (1 + t g^T J^-1 q) (matrix determinant lemma) is
// linear in t, so the kernel is a convex polytope in q and the bound is exact. A margin of
// 10% of the distance to the boundary keeps the elements away from degenerate.
template <int d>
inline double term_value(const RingTerm<d>& t, const Vec<d>& q) {
  return t.a * (q - t.centre).squaredNorm() + t.b;
}

template <int d>
double kernel_step(const SweepData& s, const Problem& p, const Deviations& dev, int first, int n, const Vec<d>& q) {
  const Eigen::Index rrows = p.targets.rows();
  const double* R = p.targets.data();
  double t = 1;
  for (int k = 0; k < n; ++k) {
    const uint32_t entry = s.ring[first + k];
    const int e = static_cast<int>(entry >> 3), j = (entry >> 1) & 3;
    Mat<d, d> J = Eigen::Map<const Mat<d, d>>(&dev.M[static_cast<size_t>(e) * d * d]);
    for (int col = 0; col < d; ++col)
      for (int r = 0; r < d; ++r) J(r, col) += R[col * rrows + e * d + r];
    const double det = J.determinant();
    if (!(det > 0)) continue;  // already flipped: no constraint (no new flips)
    const Eigen::Map<const Vec<d>> g(&s.gradients[(e * (d + 1) + j) * (d + 1)]);
    const double rate = g.dot(J.inverse() * q);  // det(t) = det (1 + t rate)
    if (rate < 0) t = std::min(t, 0.9 / -rate);
  }
  return t;
}

// Image dimension n (the vertex moves in R^n), domain dimension m (m + 1 corners).
template <int n, int m>
double sweep_dim(const SweepData& s, const Problem& p, Eigen::MatrixXd& Xm, Deviations& dev, double accept_tolerance,
                 double* max_distortion) {
  constexpr int d = n;  // the ring problem's dimension
  constexpr int nm = n * m;
  if (dev.age < 0) compute_deviations<n, m>(s, p, Xm, dev);
  double* X = Xm.data();
  const Eigen::Index xrows = Xm.rows();

  tbb::enumerable_thread_specific<Scratch<d>> scratch([&] {
    Scratch<d> sc;
    sc.terms.resize(s.max_ring);
    sc.current.resize(s.max_ring);
    sc.before.resize(s.max_ring);
    sc.after.resize(s.max_ring);
    sc.area.resize(s.max_ring);
    sc.order.resize(2 * s.max_ring);
    return sc;
  });

  Accumulator total;
  for (int e : s.closed)
    total.top = std::max(total.top, Eigen::Map<const Mat<n, m>>(&dev.M[static_cast<size_t>(e) * nm]).squaredNorm());

  const auto body = [&](const tbb::blocked_range<int>& range, Accumulator acc) {
    Scratch<d>& sc = scratch.local();
    for (int idx = range.begin(); idx != range.end(); ++idx) {
      const int v = s.colouring.order[idx];
      const int first = s.ring_start[idx], count = s.ring_start[idx + 1] - first;
      // Ring terms in displacement coordinates q = X_v(new) - X_v: J_T - R_T = M + q g^T
      // with M the current deviation, so D_T^2 = a ||q - c||^2 + b (docs/maths.md).
      double current = 0;
      for (int k = 0; k < count; ++k) {
        const uint32_t entry = s.ring[first + k];
        const int e = static_cast<int>(entry >> 3), j = (entry >> 1) & 3;
        const Eigen::Map<const Mat<n, m>> M(&dev.M[static_cast<size_t>(e) * nm]);
        const double* G = &s.gradients[(e * (m + 1) + j) * (m + 1)];
        const Eigen::Map<const Vec<m>> g(G);
        sc.terms[k] = ring_term<n, m>(M, g, G[m]);
        sc.current[k] = M.squaredNorm();
        current = std::max(current, sc.current[k]);
      }
      bool moved = false;
      Vec<d> q = Vec<d>::Zero();
      if (current > 0) {
        int guess[d + 1], guess_size = 0;
        const uint32_t packed = s.guesses[idx].load(std::memory_order_relaxed);
        for (int i = 0; i < d + 1 && ((packed >> (8 * i)) & 0xff) != 0xff; ++i)
          guess[guess_size++] = static_cast<int>((packed >> (8 * i)) & 0xff);
        const RingSolution<d> sol = solve_one_ring<d>(sc.terms.data(), count, guess, guess_size);
        uint32_t support = kNoGuess;
        if (count < 0xff)
          for (int i = 0; i < sol.active; ++i)
            support = (support & ~(0xffu << (8 * i))) | static_cast<uint32_t>(sol.support[i]) << (8 * i);
        s.guesses[idx].store(support, std::memory_order_relaxed);
        Vec<d> step = sol.q;
        double value = sol.value;
        if constexpr (n == m) {  // no_flips is refused for rectangular Jacobians (check_no_flips)
          if (s.no_flips) {
            const double t = kernel_step<d>(s, p, dev, first, count, step);
            if (t < 1) {
              step *= t;
              value = 0;
              for (int k = 0; k < count; ++k) value = std::max(value, term_value<d>(sc.terms[k], step));
            }
          }
        }
        if (value < current * (1 - kAcceptRelative) &&
            accept_move<d>(s, sc, first, count, step, value, current, accept_tolerance)) {
          moved = true;
          q = step;
          for (int r = 0; r < d; ++r) X[r * xrows + v] += q(r);
          acc.move = std::max(acc.move, q.norm());
          for (int k = 0; k < count; ++k) {  // the ring's deviations follow the move
            const uint32_t entry = s.ring[first + k];
            const int e = static_cast<int>(entry >> 3), j = (entry >> 1) & 3;
            Eigen::Map<Mat<n, m>> M(&dev.M[static_cast<size_t>(e) * nm]);
            M.noalias() += q * Eigen::Map<const Vec<m>>(&s.gradients[(e * (m + 1) + j) * (m + 1)]).transpose();
          }
        }
      }
      for (int k = 0; k < count; ++k) {
        if (!(s.ring[first + k] & 1u)) continue;
        const RingTerm<d>& t = sc.terms[k];
        acc.top = std::max(acc.top, moved ? t.a * (q - t.centre).squaredNorm() + t.b : sc.current[k]);
      }
    }
    return acc;
  };
  const auto join = [](Accumulator x, const Accumulator& y) {
    x.move = std::max(x.move, y.move);
    x.top = std::max(x.top, y.top);
    return x;
  };
  for (int c = 0; c < s.colouring.num_colours; ++c) {
    const tbb::blocked_range<int> range(s.colouring.offsets[c], s.colouring.offsets[c + 1], 128);
    total = join(total, tbb::parallel_reduce(range, Accumulator{}, body, join));
  }
  ++dev.age;
  if (max_distortion) *max_distortion = std::sqrt(total.top);
  return total.move;
}

double sweep_any(const SweepData& s, const Problem& p, Eigen::MatrixXd& X, Deviations& dev, double accept_tolerance,
                 double* max_distortion) {
  if (s.dim == 2) return sweep_dim<2, 2>(s, p, X, dev, accept_tolerance, max_distortion);
  if (s.domain_dim == 3) return sweep_dim<3, 3>(s, p, X, dev, accept_tolerance, max_distortion);
  return sweep_dim<3, 2>(s, p, X, dev, accept_tolerance, max_distortion);
}

void check_no_flips(const Problem& p, bool no_flips, const std::string& who) {
  if (no_flips && p.image_dim != p.domain_dim)
    throw InputError(who + ": no_flips needs square Jacobians (planar triangles or tets); a triangle surface in 3D "
                     "maps each triangle by a 3 by 2 Jacobian, which has no orientation sign");
}

// Packs the problem's elements and gradients, colours the free vertices and lists their
// rings in sweep order.
void build(const Problem& p, SweepData& s) {
  // The problem's contract (sizes, dimensions, indices) is checked by the callers
  // (check_problem in relax() and RelaxSweeper's constructor).
  const int n = p.image_dim, m = p.domain_dim;
  if (p.has_equalities()) throw InputError("relax: linear equality constraints (seams) are not supported");
  const int E = p.num_elements(), c = m + 1;

  s.dim = n;
  s.domain_dim = m;
  s.weights.assign(p.weights.data(), p.weights.data() + E);
  s.colouring = colour_free_vertices(p.elements, p.fixed);
  s.corners.resize(static_cast<size_t>(E) * c);
  s.gradients.resize(static_cast<size_t>(E) * c * (m + 1));
  std::vector<int> last_colour(E, -1);
  for (int e = 0; e < E; ++e)
    for (int j = 0; j < c; ++j) {
      const int v = p.elements(e, j);
      s.corners[e * c + j] = v;
      double* G = &s.gradients[(e * c + j) * (m + 1)];
      for (int k = 0; k < m; ++k) G[k] = p.gradients(e * c + j, k);
      G[m] = 1.0 / p.gradients.row(e * c + j).squaredNorm();
      last_colour[e] = std::max(last_colour[e], s.colouring.colour[v]);
    }
  for (int e = 0; e < E; ++e)
    if (last_colour[e] < 0) s.closed.push_back(e);

  // Rings (element, corner) of the coloured vertices, in sweep order.
  const int nv = p.num_vertices;
  std::vector<int> start(nv + 1, 0);
  for (int e = 0; e < E; ++e)
    for (int j = 0; j < c; ++j) ++start[p.elements(e, j) + 1];
  for (int v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<uint32_t> incident(start[nv]);
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (int e = 0; e < E; ++e)
    for (int j = 0; j < c; ++j) {
      const int v = p.elements(e, j);
      incident[fill[v]++] = pack_entry(e, j, s.colouring.colour[v] >= 0 && s.colouring.colour[v] == last_colour[e]);
    }
  s.ring_start.reserve(s.colouring.order.size() + 1);
  s.ring_start.push_back(0);
  for (int v : s.colouring.order) {
    s.ring.insert(s.ring.end(), incident.begin() + start[v], incident.begin() + start[v + 1]);
    s.ring_start.push_back(static_cast<int>(s.ring.size()));
    s.max_ring = std::max(s.max_ring, start[v + 1] - start[v]);
  }
  s.guesses = std::make_unique<std::atomic<uint32_t>[]>(s.colouring.order.size());
  for (size_t i = 0; i < s.colouring.order.size(); ++i) s.guesses[i].store(kNoGuess, std::memory_order_relaxed);
}

}  // namespace strictmin::relax_detail
