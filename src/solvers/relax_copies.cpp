// Relaxation (paper Algorithm 3) on a problem whose points have copies related by the
// seams' transitions (Problem::copy_base; docs/gparam.md, "relax with seams"). A group (the
// copies of one surface vertex) moves as one point: when its base moves by delta, copy v
// moves by R_v delta (t_v held), so each element T of the group's ring has
// J_T - R_T = D_T + (R_v delta) g^T and D_T^2 = ||R_v^T D_T + delta g^T||^2, the planar
// 1-ring term (one_ring.h). Moving a group keeps every equality: every transition's
// translation is unchanged.
//
// As the planar sweep (relax_sweep.cpp): every element's D_T = J_T - R_T is kept up to date
// as groups move (recomputed from the positions every kRefreshInterval sweeps), each ring
// solve starts from the previous solve's support, a move is taken only if it lowers the
// ring's maximum and improves the ring in the area-weighted strict order (ring_order.h), and
// the sweep's maximum comes from the elements' final values, without a pass over the map.
#include "relax_copies.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <mutex>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "ring_order.h"
#include "relax_sweep.h"
#include "socp/vector_clones.h"
#include "strictmin/measures/field_deviation.h"
#include "strictmin/solvers/interrupt.h"
#include "strictmin/solvers/one_ring.h"
#include "strictmin/solvers/vertex_colouring.h"

namespace strictmin::relax_detail {
namespace {

using Vec2 = Eigen::Vector2d;
using Mat2 = Eigen::Matrix2d;

// A move must lower the ring's maximum squared distortion by at least this much (relative),
// as in the planar sweep.
constexpr double kAcceptRelative = 1e-13;
constexpr uint32_t kNoGuess = 0xffffffffu;

// One element of a group's ring, packed for the sweep (32 bytes): the corner's gradient g,
// 1 / |g|^2 and the copy's rotation R_v as an index into Groups::rotations (0: the identity,
// which the sweep skips: I^T D and D agree but for the sign of a zero).
struct RingEntry {
  int element = 0;
  // rotation index << 1 | last (of the element's moving groups, this one moves last in a sweep)
  uint32_t info = 0;
  double g[2] = {0, 0}, inv_a = 0;
  int rotation() const { return static_cast<int>(info >> 1); }
  bool last() const { return info & 1u; }
};

// A member copy of a group and its rotation (index into Groups::rotations).
struct Member {
  int vertex = 0;
  int rotation = 0;
};

// The copies' rotations and their transposes: index 0 is the identity (every copy off the
// seams), shared; any other rotation gets its own index.
struct Rotations {
  std::vector<Mat2> R{Mat2::Identity()}, Rt{Mat2::Identity()};
  int index(const Mat2& M) {
    if (M == Mat2::Identity()) return 0;
    R.push_back(M);
    Rt.push_back(M.transpose());
    return static_cast<int>(R.size()) - 1;
  }
};

struct Groups {
  VertexColouring colouring;               // of the group bases (their surface vertex)
  std::vector<int> order;                  // group bases, colour by colour
  std::vector<int> colour_offsets;
  std::vector<int> member_start;           // per position in order
  std::vector<Member> members;
  std::vector<int> ring_start;
  std::vector<RingEntry> ring;
  Rotations rotations;
  std::vector<int> closed;                 // elements no moving group touches
  int max_ring = 0;
  // Per position: the support of the last ring solve (term indices, a byte each, 0xff =
  // none), the next solve's first guess.
  std::unique_ptr<std::atomic<uint32_t>[]> guesses;
  // Per position: the other moving groups that share an element with it (CSR), and whether
  // a neighbour moved since the group's last solve: a group whose ring did not change would
  // solve the same problem again and stay, so it is skipped.
  std::vector<int> neighbour_start, neighbours;
  std::unique_ptr<std::atomic<uint8_t>[]> dirty;
};

Vec2 gradient(const Problem& p, int e, int j) { return Vec2(p.gradients(e * 3 + j, 0), p.gradients(e * 3 + j, 1)); }

Mat2 rotation(const Problem& p, int v) {
  Mat2 R;
  R << p.copy_rotation(2 * v, 0), p.copy_rotation(2 * v, 1), p.copy_rotation(2 * v + 1, 0), p.copy_rotation(2 * v + 1, 1);
  return R;
}

int base_of(const Problem& p, int v) { return p.copy_base[v] >= 0 ? p.copy_base[v] : v; }

// Per group, the other groups at the corners of its ring's elements, each once.
template <class GroupOf>
void find_neighbours(const Problem& p, Groups& g, const GroupOf& group_of) {
  const int n = static_cast<int>(g.order.size()), c = p.corners();
  std::vector<int> seen(n, -1);
  g.neighbour_start.assign(1, 0);
  for (int i = 0; i < n; ++i) {
    for (int k = g.ring_start[i]; k < g.ring_start[i + 1]; ++k)
      for (int j = 0; j < c; ++j)
        if (const int o = group_of(p.elements(g.ring[k].element, j)); o >= 0 && o != i && seen[o] != i) {
          seen[o] = i;
          g.neighbours.push_back(o);
        }
    g.neighbour_start.push_back(static_cast<int>(g.neighbours.size()));
  }
}

// Groups that may move: every copy free and the group's transitions closing (base >= 0).
Groups make_groups(const Problem& p) {
  const int V = p.num_vertices, c = p.corners(), E = p.num_elements();
  std::vector<char> held(V, 0);
  for (int v = 0; v < V; ++v)
    if (p.copy_base[v] < 0 || p.fixed[v]) held[base_of(p, v)] = 1;
  Eigen::MatrixXi grouped(E, c);
  for (int e = 0; e < E; ++e)
    for (int j = 0; j < c; ++j) grouped(e, j) = base_of(p, p.elements(e, j));
  Groups g;
  g.colouring = colour_free_vertices(grouped, held);
  const VertexColouring& col = g.colouring;
  g.order = col.order;
  g.colour_offsets = col.offsets;
  const int n = static_cast<int>(g.order.size());
  std::vector<int> position(V, -1);
  for (int i = 0; i < n; ++i) position[g.order[i]] = i;
  auto group_of = [&](int v) { return p.copy_base[v] >= 0 ? position[p.copy_base[v]] : -1; };
  // Members and rings in CSR form, by position.
  g.member_start.assign(n + 1, 0);
  for (int v = 0; v < V; ++v)
    if (group_of(v) >= 0) ++g.member_start[group_of(v) + 1];
  for (int i = 0; i < n; ++i) g.member_start[i + 1] += g.member_start[i];
  g.members.resize(g.member_start[n]);
  std::vector<int> fill(g.member_start.begin(), g.member_start.end() - 1);
  for (int v = 0; v < V; ++v)
    if (group_of(v) >= 0) {
      Member& m = g.members[fill[group_of(v)]++];
      m.vertex = v;
      m.rotation = g.rotations.index(rotation(p, v));
    }
  std::vector<int> last_colour(E, -1);
  g.ring_start.assign(n + 1, 0);
  for (int e = 0; e < E; ++e)
    for (int j = 0; j < c; ++j)
      if (const int i = group_of(p.elements(e, j)); i >= 0) {
        ++g.ring_start[i + 1];
        last_colour[e] = std::max(last_colour[e], col.colour[g.order[i]]);
      }
  for (int i = 0; i < n; ++i) g.ring_start[i + 1] += g.ring_start[i];
  g.ring.resize(g.ring_start[n]);
  fill.assign(g.ring_start.begin(), g.ring_start.end() - 1);
  for (int e = 0; e < E; ++e)
    for (int j = 0; j < c; ++j) {
      const int v = p.elements(e, j), i = group_of(v);
      if (i < 0) continue;
      RingEntry& r = g.ring[fill[i]++];
      r.element = e;
      const bool last = col.colour[g.order[i]] == last_colour[e];
      r.g[0] = p.gradients(e * c + j, 0);
      r.g[1] = p.gradients(e * c + j, 1);
      r.inv_a = 1.0 / (r.g[0] * r.g[0] + r.g[1] * r.g[1]);
      r.info = static_cast<uint32_t>(g.rotations.index(rotation(p, v))) << 1 | (last ? 1u : 0u);
    }
  for (int e = 0; e < E; ++e)
    if (last_colour[e] < 0) g.closed.push_back(e);
  for (int i = 0; i < n; ++i) g.max_ring = std::max(g.max_ring, g.ring_start[i + 1] - g.ring_start[i]);
  g.guesses = std::make_unique<std::atomic<uint32_t>[]>(n);
  g.dirty = std::make_unique<std::atomic<uint8_t>[]>(n);
  for (int i = 0; i < n; ++i) {
    g.guesses[i].store(kNoGuess, std::memory_order_relaxed);
    g.dirty[i].store(1, std::memory_order_relaxed);
  }
  find_neighbours(p, g, group_of);
  return g;
}

// D_T = J_T - R_T of every element for the map X.
void compute_deviations(const Problem& p, const Eigen::MatrixXd& X, std::vector<Mat2>& D) {
  D.resize(p.num_elements());
  tbb::parallel_for(tbb::blocked_range<int>(0, p.num_elements(), 2048), [&](const tbb::blocked_range<int>& r) {
    for (int e = r.begin(); e != r.end(); ++e) {
      Mat2 M;
      M << -p.targets(2 * e, 0), -p.targets(2 * e, 1), -p.targets(2 * e + 1, 0), -p.targets(2 * e + 1, 1);
      for (int k = 0; k < 3; ++k) M.noalias() += X.row(p.elements(e, k)).transpose().head<2>() * gradient(p, e, k).transpose();
      D[e] = M;
    }
  });
}

struct Scratch {
  std::vector<RingTerm<2>> terms;
  std::vector<double> current, before, after, area;
  std::vector<int> order;
};

struct Accumulator {
  double move = 0;  // largest move
  double top = 0;   // largest D_T^2 after the sweep over the elements seen so far
};

// The planar sweep's acceptance (relax_sweep.cpp, accept_move): the ring maximum must go
// down, and either its top level drops by more than tau = tolerance * (ring maximum) or the
// ring improves in the area-weighted strict order with values within tau equal.
// The helpers of move_groups are always inlined into it (and so into its AVX2 clone).
[[gnu::always_inline]] inline bool accept(const Problem& p, const Groups& g, Scratch& sc, int first, int n,
                                          const Vec2& q, double value, double current, double tolerance) {
  if (!(value < current * (1 - kAcceptRelative))) return false;
  const double top = std::sqrt(current), tau = tolerance * top;
  if (value < (top - tau) * (top - tau)) return true;
  for (int k = 0; k < n; ++k) {
    const RingTerm<2>& t = sc.terms[k];
    sc.after[k] = std::sqrt(t.a * (q - t.centre).squaredNorm() + t.b);
    sc.before[k] = std::sqrt(sc.current[k]);
    sc.area[k] = p.weights(g.ring[first + k].element);
  }
  return ring_improves(sc.before.data(), sc.after.data(), sc.area.data(), n, tau, sc.order.data());
}

// The ring's terms in the group's displacement delta (of its base): copy v sees
// R_v^T D_T + delta g^T (the top of this file); returns the ring's current maximum, squared.
[[gnu::always_inline]] inline double gather_terms(const Groups& g, const std::vector<Mat2>& D, int first, int n,
                                                  Scratch& sc) {
  double current = 0;
  for (int k = 0; k < n; ++k) {
    const RingEntry& r = g.ring[first + k];
    const Mat2& Dk = D[r.element];
    const Eigen::Map<const Vec2> grad(r.g);
    if (const int rot = r.rotation(); rot == 0)
      sc.terms[k] = ring_term<2>(Dk, grad, r.inv_a);
    else
      sc.terms[k] = ring_term<2>(Mat2(g.rotations.Rt[rot] * Dk), grad, r.inv_a);
    sc.current[k] = Dk.squaredNorm();
    current = std::max(current, sc.current[k]);
  }
  return current;
}

// Moves the group by q: each copy by R_v q, each ring element's D_T by (R_v q) g^T; the
// neighbours must look again.
[[gnu::always_inline]] inline void apply_move(const Groups& g, int i, int first, int n, const Vec2& q,
                                              Eigen::MatrixXd& X, std::vector<Mat2>& D) {
  for (int m = g.member_start[i]; m < g.member_start[i + 1]; ++m) {
    const Member& member = g.members[m];
    const Vec2 d = member.rotation == 0 ? q : Vec2(g.rotations.R[member.rotation] * q);
    X(member.vertex, 0) += d(0);
    X(member.vertex, 1) += d(1);
  }
  for (int k = 0; k < n; ++k) {
    const RingEntry& r = g.ring[first + k];
    const Eigen::Map<const Vec2> grad(r.g);
    if (const int rot = r.rotation(); rot == 0)
      D[r.element].noalias() += q * grad.transpose();
    else
      D[r.element].noalias() += (g.rotations.R[rot] * q) * grad.transpose();
  }
  for (int k = g.neighbour_start[i]; k < g.neighbour_start[i + 1]; ++k)
    g.dirty[g.neighbours[k]].store(1, std::memory_order_relaxed);
}

// One group's 1-ring move, updating X and D; accumulates the move and the final values of
// the elements it is last to touch.
[[gnu::always_inline]] inline void move_group(const Problem& p, const Groups& g, int i, double tolerance,
                                              Scratch& sc, Eigen::MatrixXd& X, std::vector<Mat2>& D,
                                              Accumulator& acc) {
  const int first = g.ring_start[i], n = g.ring_start[i + 1] - first;
  // Only this thread touches group i's flag during its colour (no neighbour has the same
  // colour): a plain load and store, no locked exchange.
  const bool dirty = g.dirty[i].load(std::memory_order_relaxed);
  if (dirty) g.dirty[i].store(0, std::memory_order_relaxed);
  if (!dirty) {
    for (int k = 0; k < n; ++k)
      if (g.ring[first + k].last()) acc.top = std::max(acc.top, D[g.ring[first + k].element].squaredNorm());
    return;
  }
  const double current = gather_terms(g, D, first, n, sc);
  bool moved = false;
  Vec2 q = Vec2::Zero();
  if (current > 0) {
    int guess[3], guess_size = 0;
    const uint32_t packed = g.guesses[i].load(std::memory_order_relaxed);
    for (int s = 0; s < 3 && ((packed >> (8 * s)) & 0xff) != 0xff; ++s) guess[guess_size++] = static_cast<int>((packed >> (8 * s)) & 0xff);
    const RingSolution<2> sol = solve_one_ring<2>(sc.terms.data(), n, guess, guess_size);
    uint32_t support = kNoGuess;
    if (n < 0xff)
      for (int s = 0; s < sol.active; ++s)
        support = (support & ~(0xffu << (8 * s))) | static_cast<uint32_t>(sol.support[s]) << (8 * s);
    g.guesses[i].store(support, std::memory_order_relaxed);
    if (sol.q.allFinite() && accept(p, g, sc, first, n, sol.q, sol.value, current, tolerance)) {
      moved = true;
      q = sol.q;
      apply_move(g, i, first, n, q, X, D);
      acc.move = std::max(acc.move, q.norm());
    }
  }
  for (int k = 0; k < n; ++k)
    if (g.ring[first + k].last()) {
      const RingTerm<2>& t = sc.terms[k];
      acc.top = std::max(acc.top, moved ? t.a * (q - t.centre).squaredNorm() + t.b : sc.current[k]);
    }
}

// Groups begin..end-1 of one colour, one after the other. Compiled for AVX2 as well as the
// baseline (socp/vector_clones.h): the VEX encoding's three operands spare the register
// copies of this scalar-heavy code; without FMA every operation rounds as the baseline's, so
// the maps are bitwise the same.
STRICTMIN_VECTOR_CLONES
void move_groups(const Problem& p, const Groups& g, int begin, int end, double tolerance, Scratch& sc,
                 Eigen::MatrixXd& X, std::vector<Mat2>& D, Accumulator& acc) {
  for (int i = begin; i != end; ++i) move_group(p, g, i, tolerance, sc, X, D, acc);
}

using ScratchPool = tbb::enumerable_thread_specific<Scratch>;

ScratchPool make_scratch(const Groups& g) {
  return ScratchPool([&g] {
    Scratch sc;
    sc.terms.resize(g.max_ring);
    for (auto* v : {&sc.current, &sc.before, &sc.after, &sc.area}) v->resize(g.max_ring);
    sc.order.resize(2 * g.max_ring);
    return sc;
  });
}

// One sweep over every moving group, colour by colour (the groups of a colour in parallel),
// updating X and D: the largest move and the largest D_T^2 after the sweep.
Accumulator sweep_groups(const Problem& p, const Groups& g, double tolerance, ScratchPool& scratch,
                         Eigen::MatrixXd& X, std::vector<Mat2>& D) {
  const auto join = [](Accumulator x, const Accumulator& y) {
    x.move = std::max(x.move, y.move);
    x.top = std::max(x.top, y.top);
    return x;
  };
  Accumulator total;
  for (int e : g.closed) total.top = std::max(total.top, D[e].squaredNorm());
  const int colours = static_cast<int>(g.colour_offsets.size()) - 1;
  for (int c = 0; c < colours; ++c) {
    const tbb::blocked_range<int> range(g.colour_offsets[c], g.colour_offsets[c + 1], 128);
    total = join(total, tbb::parallel_reduce(range, Accumulator{}, [&](const tbb::blocked_range<int>& r, Accumulator acc) {
      Scratch& sc = scratch.local();
      move_groups(p, g, r.begin(), r.end(), tolerance, sc, X, D, acc);
      return acc;
    }, join));
  }
  return total;
}

}  // namespace

struct CopiesSweeper::State {
  explicit State(const Problem& p) : groups(make_groups(p)), scratch(make_scratch(groups)) {}
  Groups groups;
  ScratchPool scratch;
  std::vector<Mat2> D;
  std::mutex busy;  // one sweep at a time: D and the groups' flags are the sweeper's
};

CopiesSweeper::CopiesSweeper(const Problem& p) : state_(std::make_unique<State>(p)) {}

CopiesSweeper::~CopiesSweeper() = default;

const VertexColouring& CopiesSweeper::colouring() const { return state_->groups.colouring; }

double CopiesSweeper::sweep(const Problem& p, Eigen::MatrixXd& X, double accept_tolerance,
                            double* max_distortion) const {
  State& s = *state_;
  const std::lock_guard<std::mutex> lock(s.busy);
  // The targets may have changed since the last sweep (a local step): every group looks
  // again, from deviations computed afresh.
  compute_deviations(p, X, s.D);
  const int n = static_cast<int>(s.groups.order.size());
  for (int i = 0; i < n; ++i) s.groups.dirty[i].store(1, std::memory_order_relaxed);
  const Accumulator total = sweep_groups(p, s.groups, accept_tolerance, s.scratch, X, s.D);
  if (max_distortion) *max_distortion = std::sqrt(total.top);
  return total.move;
}

Result relax_with_copies(const Problem& p, const Eigen::MatrixXd& initial, const RelaxOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  const Groups g = make_groups(p);
  ScratchPool scratch = make_scratch(g);
  Result result;
  Eigen::MatrixXd X = initial;
  std::vector<Mat2> D;
  int age = -1;  // sweeps since D was computed from X
  bool moves_settled = false;
  for (int s = 1; s <= options.sweeps; ++s) {
    check_interrupt();  // solvers/interrupt.h
    if (age < 0 || age >= kRefreshInterval) {
      compute_deviations(p, X, D);
      age = 0;
    }
    const Accumulator total = sweep_groups(p, g, options.accept_tolerance, scratch, X, D);
    ++age;
    IterationRecord record;
    record.iteration = s;
    record.max_distortion = std::sqrt(total.top);
    record.largest_move = total.move;
    record.time_s = elapsed();
    if ((moves_settled = record_sweep(result, options, record))) break;
  }
  result.positions = std::move(X);
  result.distortion = field_deviation(p, result.positions);
  set_relax_status(result, options, moves_settled);
  result.time_s = elapsed();
  return result;
}

}  // namespace strictmin::relax_detail
