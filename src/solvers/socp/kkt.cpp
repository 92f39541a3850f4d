#include "solvers/socp/kkt.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_group.h>

#include "solvers/join_on_exit.h"
#include "solvers/serial_cholmod_scope.h"
#include "solvers/socp/ordering.h"
#include "solvers/socp/soc.h"

namespace strictmin::socp {
namespace {

constexpr int kGrain = 1024;

int pair_index(int l1, int l2) { return l1 * (l1 + 1) / 2 + l2; }  // l1 >= l2

double max_abs(const Eigen::VectorXd& v) { return v.size() ? v.cwiseAbs().maxCoeff() : 0.0; }

constexpr double kEqualityRoundOff = 1e-12;  // |A x - b| left alone by the predictor

double process_cpu() {
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

// Adds the wall and CPU time of its scope to two counters.
class PhaseTimer {
 public:
  PhaseTimer(double& wall, double& cpu)
      : wall_(wall), cpu_(cpu), w0_(std::chrono::steady_clock::now()), c0_(process_cpu()) {}
  ~PhaseTimer() { stop(); }
  void stop() {
    if (stopped_) return;
    stopped_ = true;
    wall_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - w0_).count();
    cpu_ += process_cpu() - c0_;
  }

 private:
  double &wall_, &cpu_;
  std::chrono::steady_clock::time_point w0_;
  double c0_;
  bool stopped_ = false;
};

}  // namespace

NormalEquations::NormalEquations(const ConeProgram& program, const IpmSettings& settings)
    : p_(program), settings_(settings) {
  PhaseTimer timer(timers_.analyze_wall, timers_.analyze_cpu);
  build_pattern();
}

void NormalEquations::build_pattern() {
  const int n = p_.n, c = p_.corners(), L = p_.local_dofs(), E = p_.num_element_cones();
  npairs_ = L * (L + 1) / 2;
  // Equalities: eliminated exactly on dx = Z dy where they have vertex-block form (the seams),
  // otherwise by the penalty. The system's unknowns are then the y nodes' dofs.
  if (p_.num_eq() > 0 && settings_.eliminate_equalities) {
    null_space_ = block_null_space(p_);
    elim_ = null_space_.ok;
  }
  nsys_ = elim_ ? null_space_.num_dofs(n) : p_.num_x;
  const int N = nsys_;
  const int F = N / n;
  // What does not depend on the order runs beside it: METIS keeps this thread (one METIS call
  // at a time, ordering.h), and a thread that waits for this analysis (solve_linf's) or an
  // idle one takes these up. Horse's seamless problem: the
  // seams' element pairs take 0.06 s of the 0.48 s analysis, its ordering 0.25 s.
  std::vector<char> simple_element;
  std::vector<SeamPair> seam_pairs;
  tbb::task_group beside_ordering;  // waited for below
  const JoinOnExit join_beside(beside_ordering);  // on an exception: waited for, not cancelled
  beside_ordering.run([&] {
    simple_element = simple_elements();
    if (elim_) seam_pairs = expand_seam_pairs(simple_element);
  });
  if (p_.num_eq() > 0)
    beside_ordering.run([&] {
      at_ = p_.A.transpose();
      if (elim_) factor_aat();
    });
  // The free vertices' graph (with elimination: the y nodes' graph): elements and equality
  // rows couple their vertices.
  std::vector<int> offset(F + 1, 0), adj;
  {
    std::vector<std::vector<int>> nb(F);
    std::vector<int> nodes;
    for (int i = 0; i < E; ++i) {
      nodes.clear();
      for (int a = 0; a < c; ++a) {
        const int base = p_.dof_base[i * c + a];
        if (base < 0) continue;
        if (!elim_) {
          nodes.push_back(base / n);
          continue;
        }
        const int f = base / n;
        for (int t = null_space_.offset[f]; t < null_space_.offset[f + 1]; ++t) nodes.push_back(null_space_.node[t]);
      }
      for (int a : nodes)
        for (int b : nodes)
          if (a != b) nb[a].push_back(b);
    }
    if (p_.num_eq() > 0 && !elim_) {
      for (int row = 0; row < p_.A.rows(); ++row)
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator a(p_.A, row); a; ++a)
          for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator b(p_.A, row); b; ++b)
            if (a.col() / n != b.col() / n) nb[a.col() / n].push_back(static_cast<int>(b.col() / n));
    }
    for (int f = 0; f < F; ++f) {
      std::sort(nb[f].begin(), nb[f].end());
      nb[f].erase(std::unique(nb[f].begin(), nb[f].end()), nb[f].end());
      offset[f + 1] = offset[f] + static_cast<int>(nb[f].size());
      adj.insert(adj.end(), nb[f].begin(), nb[f].end());
    }
  }
  // Fill-reducing order of the free vertices, expanded to their n dofs. Large problems: split
  // by a top-level separator and factorise the halves on two threads (split_cholesky.h); the
  // order is then [part 0 | part 1 | separator].
  std::vector<int> order;
  if (F * n >= settings_.split_min_dofs) {
    const std::vector<int> part = vertex_bisection(offset, adj);
    if (!part.empty()) {
      order = bisected_ordering(offset, adj, part, split_sizes_);
      for (int& size : split_sizes_) size *= n;
    }
  }
  if (order.empty()) order = vertex_ordering(offset, adj);
  std::vector<int> rank(F);  // vertex -> its place in the order
  for (int i = 0; i < F; ++i) rank[order[i]] = i;
  perm_.assign(N, 0);
  for (int v = 0; v < F; ++v)
    for (int r = 0; r < n; ++r) perm_[v * n + r] = rank[v] * n + r;

  // The upper triangle's pattern (in the new numbering), straight from the graph: the columns
  // of vertex J hold, for each neighbour I < J (ascending), the n rows of I, then J's own rows
  // up to the diagonal. Upper, because CHOLMOD's supernodal factorisation reads the upper
  // triangle: a lower one would be transposed on every factorisation.
  std::vector<int> lower_offset(F + 1, 0), lower;
  for (int v = 0; v < F; ++v)
    for (int e = offset[v]; e < offset[v + 1]; ++e)
      if (rank[adj[e]] < rank[v]) ++lower_offset[rank[v] + 1];
  for (int J = 0; J < F; ++J) lower_offset[J + 1] += lower_offset[J];
  lower.resize(lower_offset[F]);
  parallel_for_index(F, kGrain, [&](int begin, int end) {
    for (int v = begin; v < end; ++v) {
      const int J = rank[v];
      int* out = lower.data() + lower_offset[J];
      for (int e = offset[v]; e < offset[v + 1]; ++e)
        if (rank[adj[e]] < J) *out++ = rank[adj[e]];
      std::sort(lower.data() + lower_offset[J], out);
    }
  });
  matrix_.resize(N, N);
  {
    std::vector<int> outer(N + 1, 0);
    for (int J = 0; J < F; ++J)
      for (int r = 0; r < n; ++r) {
        const int column = J * n + r;
        outer[column + 1] = outer[column] + n * (lower_offset[J + 1] - lower_offset[J]) + r + 1;
      }
    matrix_.resizeNonZeros(outer[N]);
    std::copy(outer.begin(), outer.end(), matrix_.outerIndexPtr());
    int* inner = matrix_.innerIndexPtr();
    parallel_for_index(F, kGrain, [&](int begin, int end) {
      for (int J = begin; J < end; ++J)
        for (int r = 0; r < n; ++r) {
          int* out = inner + outer[J * n + r];
          for (int e = lower_offset[J]; e < lower_offset[J + 1]; ++e)
            for (int q = 0; q < n; ++q) *out++ = lower[e] * n + q;
          for (int q = 0; q <= r; ++q) *out++ = J * n + q;
        }
    });
    std::fill(matrix_.valuePtr(), matrix_.valuePtr() + outer[N], 0.0);
  }
  const int* outer = matrix_.outerIndexPtr();
  // The nonzero of entry (row, col), row <= col, in the new numbering.
  auto find = [&](int row, int col) {
    const int I = row / n, J = col / n;
    if (I == J) return outer[col] + n * (lower_offset[J + 1] - lower_offset[J]) + row % n;
    const int* first = lower.data() + lower_offset[J];
    const int* last = lower.data() + lower_offset[J + 1];
    const int k = static_cast<int>(std::lower_bound(first, last, I) - first);
    return outer[col] + n * k + row % n;
  };
  auto upper_of = [&](Eigen::Index r, Eigen::Index col) {
    const int a = perm_[r], b = perm_[col];
    return std::make_pair(std::min(a, b), std::max(a, b));
  };
  // Equalities: A^T A / rho joins the matrix (its couplings are edges of the graph above),
  // unless they are eliminated; then A A^T gives the particular solutions and multipliers.
  Eigen::SparseMatrix<double> ata;
  if (p_.num_eq() > 0 && !elim_)
    ata = (Eigen::SparseMatrix<double>(p_.A.transpose()) * Eigen::SparseMatrix<double>(p_.A)).pruned();
  beside_ordering.wait();
  const Eigen::Index nnz = matrix_.nonZeros();
  slot_target_.assign(static_cast<size_t>(E) * npairs_, -1);
  p_values_.setZero(nnz);
  // Each element pair's nonzero (in parallel), then the counts.
  parallel_for_index(E, kGrain, [&](int begin, int end) {
    std::vector<int> local(L);
    for (int i = begin; i < end; ++i) {
      if (!simple_element[i]) continue;
      for (int j = 0; j < c; ++j)
        for (int r = 0; r < n; ++r) {
          const int base = p_.dof_base[i * c + j];
          local[j * n + r] = base < 0 ? -1 : perm_[corner_dof(base) + r];
        }
      for (int l1 = 0; l1 < L; ++l1)
        for (int l2 = 0; l2 <= l1; ++l2)
          if (local[l1] >= 0 && local[l2] >= 0)
            slot_target_[static_cast<size_t>(i) * npairs_ + pair_index(l1, l2)] =
                find(std::min(local[l1], local[l2]), std::max(local[l1], local[l2]));
    }
  });
  // The seams' pairs in the new numbering.
  extra_.resize(seam_pairs.size());
  parallel_for_index(static_cast<int>(seam_pairs.size()), kGrain, [&](int begin, int end) {
    for (int z = begin; z < end; ++z) {
      const SeamPair& q = seam_pairs[z];
      const int ya = perm_[q.a], yb = perm_[q.b];
      extra_[z] = {q.slot, find(std::min(ya, yb), std::max(ya, yb)), q.coef};
    }
  });
  std::vector<SeamPair>().swap(seam_pairs);  // 24 bytes a pair (horse: 36 MB), before the sort's copy
  if (elim_) {
    // In the matrix's order: the gather then writes each nonzero once, in sequence. The
    // entries were made in ascending slots, so a stable counting sort by target orders them
    // by (target, slot) in one pass (horse: 1.5M entries, a comparison sort took 1.3% of
    // the whole solve).
    std::vector<int> start(static_cast<size_t>(matrix_.nonZeros()) + 1, 0);
    for (const ExtraSlot& x : extra_) ++start[x.target + 1];
    for (size_t z = 1; z < start.size(); ++z) start[z] += start[z - 1];
    std::vector<ExtraSlot> sorted(extra_.size());
    for (const ExtraSlot& x : extra_) sorted[start[x.target]++] = x;
    extra_.swap(sorted);
  }
  std::vector<int> count(nnz + 1, 0);
  for (int target : slot_target_)
    if (target >= 0) ++count[target + 1];
  if (p_.has_quad()) {
    auto slot_p = [&](int slot) {  // the objective's 2 w_i (I (x) L_i) entry of a pair
      const int i = slot / npairs_, pair = slot % npairs_;
      int l1 = 0;
      while (pair_index(l1 + 1, 0) <= pair) ++l1;
      const int l2 = pair - pair_index(l1, 0);
      if (l1 % n != l2 % n) return 0.0;
      const double* g = p_.grad.data() + static_cast<size_t>(i) * c * p_.m;
      double gram = 0;
      for (int col = 0; col < p_.m; ++col) gram += g[(l1 / n) * p_.m + col] * g[(l2 / n) * p_.m + col];
      return 2.0 * p_.quad_weight[i] * gram;
    };
    for (size_t slot = 0; slot < slot_target_.size(); ++slot)
      if (slot_target_[slot] >= 0) p_values_[slot_target_[slot]] += slot_p(static_cast<int>(slot));
    for (const ExtraSlot& x : extra_) p_values_[x.target] += x.coef * slot_p(x.slot);
  }
  for (Eigen::Index z = 0; z < nnz; ++z) count[z + 1] += count[z];
  gather_offset_.assign(count.begin(), count.end());
  gather_.assign(count.back(), 0);
  for (size_t slot = 0; slot < slot_target_.size(); ++slot)
    if (slot_target_[slot] >= 0) gather_[count[slot_target_[slot]]++] = static_cast<int>(slot);
  diagonal_.resize(N);
  for (int d = 0; d < N; ++d) diagonal_[d] = find(perm_[d], perm_[d]);
  ata_values_.setZero(nnz);
  if (p_.num_eq() > 0)
    for (int col = 0; col < ata.outerSize(); ++col)
      for (Eigen::SparseMatrix<double>::InnerIterator it(ata, col); it; ++it)
        if (it.row() >= it.col()) {
          const auto [r, cc] = upper_of(it.row(), it.col());
          ata_values_[find(r, cc)] += it.value();
        }
  slot_values_.resize(static_cast<Eigen::Index>(E) * npairs_);
  cone_k_.resize(static_cast<Eigen::Index>(E) * L);
  // Supernodal symbolic analysis in our order (CHOLMOD's own ordering switched off).
  if (split_sizes_[0] > 0) {
    split_ = std::make_unique<SplitCholesky>();
    if (!split_->analyze(matrix_, split_sizes_[0], split_sizes_[1])) split_.reset();
  }
  if (N > 0 && !split_) {
    cholesky_ = std::make_unique<SupernodalCholesky>();
    if (!cholesky_->analyze(matrix_)) cholesky_.reset();
  }
  if (settings_.verbose && elim_) {
    int most_terms = 0;
    std::vector<int> users(null_space_.num_nodes, 0);
    for (size_t f = 0; f + 1 < null_space_.offset.size(); ++f) {
      most_terms = std::max(most_terms, null_space_.offset[f + 1] - null_space_.offset[f]);
      for (int t = null_space_.offset[f]; t < null_space_.offset[f + 1]; ++t) ++users[null_space_.node[t]];
    }
    std::sort(users.rbegin(), users.rend());
    std::fprintf(stderr,
                 "kkt: %d equalities eliminated: %d of %d free vertices are unknowns, %zu terms (at most %d per "
                 "vertex), most used nodes %d %d %d, %zu seam pair terms\n",
                 p_.num_eq(), null_space_.num_nodes, p_.num_x / n, null_space_.node.size(), most_terms,
                 users.size() > 0 ? users[0] : 0, users.size() > 1 ? users[1] : 0, users.size() > 10 ? users[10] : 0,
                 extra_.size());
  }
  if (settings_.verbose && N > 0) {
    std::fprintf(stderr, "kkt: %d dofs, %ld nonzeros, factor %.3g nonzeros, %.3g flops per factorisation\n", N,
                 static_cast<long>(matrix_.nonZeros()), factor_nonzeros(), analyze_flops());
    if (split_)
      std::fprintf(stderr, "kkt: split in halves of %d and %d dofs and a separator of %d, factorised in parallel\n",
                   split_sizes_[0], split_sizes_[1], split_sizes_[2]);
  }
}

double NormalEquations::factor_nonzeros() const {
  if (split_) return split_->nonzeros();
  return cholesky_ ? cholesky_->nonzeros() : 0.0;
}

double NormalEquations::analyze_flops() const {
  if (split_) return split_->flops();
  return cholesky_ ? cholesky_->flops() : 0.0;
}

Eigen::VectorXd NormalEquations::llt_solve(const Eigen::VectorXd& b) const {
  PhaseTimer timer(timers_.solve_wall, timers_.solve_cpu);
  SerialCholmodScope serial;  // one BLAS thread (serial_cholmod_scope.h)
  ++timers_.solves;
  const int N = nsys_;
  Eigen::VectorXd bp(N), out(N);
  for (int d = 0; d < N; ++d) bp[perm_[d]] = b[d];
  Eigen::VectorXd xp(N);
  if (split_)
    split_->solve(bp, xp);
  else
    cholesky_->solve(bp.data(), xp.data());
  for (int d = 0; d < N; ++d) out[d] = xp[perm_[d]];
  return out;
}

void NormalEquations::llt_solve2(const Eigen::VectorXd& b0, const Eigen::VectorXd& b1, Eigen::VectorXd& x0,
                                 Eigen::VectorXd& x1) const {
  PhaseTimer timer(timers_.solve_wall, timers_.solve_cpu);
  SerialCholmodScope serial;  // one BLAS thread (serial_cholmod_scope.h)
  ++timers_.solves;
  const int N = nsys_;
  Eigen::VectorXd bp0(N), bp1(N), xp0(N), xp1(N);
  for (int d = 0; d < N; ++d) {
    bp0[perm_[d]] = b0[d];
    bp1[perm_[d]] = b1[d];
  }
  if (split_)
    split_->solve2(bp0, bp1, xp0, xp1);
  else
    cholesky_->solve2(bp0.data(), bp1.data(), xp0.data(), xp1.data());
  x0.resize(N);
  x1.resize(N);
  for (int d = 0; d < N; ++d) {
    x0[d] = xp0[perm_[d]];
    x1[d] = xp1[perm_[d]];
  }
}

bool NormalEquations::factor(const Scaling& sc) {
  scaling_ = &sc;
  const auto tf0 = std::chrono::steady_clock::now();
  auto lap = [last = tf0]() mutable {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - last).count();
    last = now;
    return s;
  };
  const int N = nsys_, n = p_.n, m = p_.m, c = p_.corners(), L = p_.local_dofs(), E = p_.num_element_cones();
  const bool has_k = p_.has_k;
  PhaseTimer assemble_timer(timers_.assemble_wall, timers_.assemble_cpu);
  // Element contributions, in parallel; the k-k entry sums in a fixed order (deterministic
  // reduce), so that the same input gives bitwise the same iterates run after run.
  hkk_ = tbb::parallel_deterministic_reduce(
      tbb::blocked_range<int>(0, E, kGrain), 0.0,
      [&](const tbb::blocked_range<int>& range, double acc) {
        double gram[16], pv[12], v[10];
        for (int i = range.begin(); i < range.end(); ++i) {
          const Eigen::Index o = p_.cone_offset(i);
          const int d = p_.t() + 1;
          winv2_vector(sc.w.data() + o, d, v);
          const double ib2 = 1.0 / (sc.beta[i] * sc.beta[i]);
          const double* g = p_.grad.data() + static_cast<size_t>(i) * c * m;
          for (int j1 = 0; j1 < c; ++j1)
            for (int j2 = 0; j2 <= j1; ++j2) {
              double t = 0;
              for (int col = 0; col < m; ++col) t += g[j1 * m + col] * g[j2 * m + col];
              gram[j1 * c + j2] = t;
            }
          for (int j = 0; j < c; ++j)
            for (int r = 0; r < n; ++r) {
              double t = 0;
              for (int col = 0; col < m; ++col) t += g[j * m + col] * v[1 + r * m + col];
              pv[j * n + r] = t;
            }
          double* slots = slot_values_.data() + static_cast<Eigen::Index>(i) * npairs_;
          for (int l1 = 0; l1 < L; ++l1)
            for (int l2 = 0; l2 <= l1; ++l2) {
              const double block = (l1 % n == l2 % n) ? gram[(l1 / n) * c + (l2 / n)] : 0.0;
              slots[pair_index(l1, l2)] = ib2 * (block + 2.0 * pv[l1] * pv[l2]);
            }
          if (has_k) {
            const double a = p_.head_a[i];
            double* kv = cone_k_.data() + static_cast<Eigen::Index>(i) * L;
            for (int l = 0; l < L; ++l) kv[l] = a * ib2 * 2.0 * v[0] * pv[l];
            acc += a * a * ib2 * (2.0 * v[0] * v[0] - 1.0);
          }
        }
        return acc;
      },
      [](double a, double b) { return a + b; });
  if (has_k && p_.has_scalar) {
    const int i = E;
    const double b = sc.beta[i];
    hkk_ += p_.head_a[i] * p_.head_a[i] / (b * b);
  }
  if (N == 0) {
    schur_ = hkk_ > 0 ? hkk_ : 1.0;
    return std::isfinite(hkk_);
  }
  // Gather into the matrix.
  double* values = matrix_.valuePtr();
  const double max_diag_raw = [&] {
    parallel_for_index(static_cast<int>(matrix_.nonZeros()), 8 * kGrain, [&](int begin, int end) {
      for (int z = begin; z < end; ++z) {
        double t = p_values_[z];
        for (int e = gather_offset_[z]; e < gather_offset_[z + 1]; ++e) t += slot_values_[gather_[e]];
        values[z] = t;
      }
    });
    for (const ExtraSlot& x : extra_) values[x.target] += x.coef * slot_values_[x.slot];
    double mx = 0;
    for (int d = 0; d < N; ++d) mx = std::max(mx, values[diagonal_[d]]);
    return mx;
  }();
  const double t_assemble = lap();
  if (!std::isfinite(max_diag_raw) || max_diag_raw <= 0) return false;
  inv_rho_ = p_.num_eq() > 0 && !elim_ ? max_diag_raw / settings_.equality_penalty : 0.0;
  if (p_.num_eq() > 0 && !elim_)
    for (Eigen::Index z = 0; z < matrix_.nonZeros(); ++z) values[z] += inv_rho_ * ata_values_[z];
  assemble_timer.stop();
  PhaseTimer factor_timer(timers_.factorize_wall, timers_.factorize_cpu);
  ++timers_.factorizations;
  // Regularisation relative to each diagonal entry (they span many orders of magnitude near
  // the optimum), with a floor relative to the largest.
  delta_ = settings_.regularization;
  diag_saved_.resize(N);
  for (int d = 0; d < N; ++d) diag_saved_[d] = values[diagonal_[d]];
  bool ok = false;
  SerialCholmodScope serial;  // serial_cholmod_scope.h: CHOLMOD's OpenMP loops and BLAS threads cost more than they gain
  for (int attempt = 0; attempt <= settings_.factorization_retries && !ok; ++attempt) {
    if (attempt > 0) delta_ = std::max(100.0 * delta_, 1e-14);
    // The floor relative to the largest diagonal entry only after a failed factorisation: near
    // the optimum a bounded cone at its bound makes that entry ~1e17 (docs/linf.md, "Accuracy of
    // the Newton systems"), and the floor then swamps the smallest entries (~1e-3) and spoils
    // the factor as the preconditioner of the refinement.
    const double floor = attempt > 0 ? 1e-3 * delta_ * max_diag_raw : 0.0;
    for (int d = 0; d < N; ++d) values[diagonal_[d]] = diag_saved_[d] * (1.0 + delta_) + floor;
    if (split_) {
      ok = split_->factorize(values);
    } else {
      ok = cholesky_ && cholesky_->factorize(values);
    }
  }
  const double t_factor = lap();
  factor_timer.stop();
  if (!ok) return false;
  PhaseTimer border_timer(timers_.border_wall, timers_.border_cpu);
  if (has_k) {
    hxk_.setZero(p_.num_x);
    const int free_vertices = p_.num_x / n;
    parallel_for_index(free_vertices, kGrain, [&](int begin, int end) {
      for (int f = begin; f < end; ++f)
        for (int e = p_.incidence_offset[f]; e < p_.incidence_offset[f + 1]; ++e) {
          const int i = p_.incidence[e] / c, j = p_.incidence[e] % c;
          for (int r = 0; r < n; ++r) hxk_[f * n + r] += cone_k_[static_cast<Eigen::Index>(i) * L + j * n + r];
        }
    });
    if (elim_) {
      Eigen::VectorXd reduced;
      apply_zt(null_space_, n, hxk_, reduced);
      hxk_.swap(reduced);
    }
    // u = H_xx^{-1} h_xk is solved together with the first right-hand side (solve_normal):
    // one pass over the factor for both.
    border_pending_ = true;
    border_failed_ = false;
  }
  if (settings_.verbose >= 2)
    std::fprintf(stderr, "kkt: assemble %.4fs factorize %.4fs bordering %.4fs\n", t_assemble, t_factor, lap());
  return true;
}

void NormalEquations::finish_bordering(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  llt_solve2(b, hxk_, x, u_);
  border_pending_ = false;
  PhaseTimer border_timer(timers_.border_wall, timers_.border_cpu);
  // S = h_kk - h_xk^T u cancels badly near the optimum (each active cone adds two huge,
  // nearly equal terms). The same number is min over x of (x,1)^T H (x,1), attained at
  // x = -u: S = sum_i ||W_i^{-1} M_i (-u, 1)||^2, a sum of squares without cancellation
  // (plus the regularisation's share, which the factor also contains).
  Eigen::VectorXd mv, wm;
  const Eigen::VectorXd xu = to_dofs(u_);
  p_.apply_m(-xu, 1.0, false, mv);
  apply_scaling(p_, *scaling_, ScalingOp::WInv, mv, wm);
  const double* values = matrix_.valuePtr();
  double reg_part = 0;
  for (int d = 0; d < nsys_; ++d) reg_part += (values[diagonal_[d]] - diag_saved_[d]) * u_[d] * u_[d];
  schur_ = wm.squaredNorm() + reg_part;
  if (p_.has_quad()) {
    Eigen::VectorXd pu;
    p_.apply_p(xu, pu);
    schur_ += xu.dot(pu);
  }
  if (!(schur_ > 0) || !std::isfinite(schur_) || !u_.allFinite()) {
    border_failed_ = true;
    schur_ = std::numeric_limits<double>::quiet_NaN();  // every direction comes out non-finite
  }
}

void NormalEquations::solve_normal(const Eigen::VectorXd& r1x, double r1k, const Eigen::VectorXd& r2,
                                   Eigen::VectorXd& dx, double& dk, Eigen::VectorXd& w) const {
  dk = 0;
  if (nsys_ == 0) {  // no unknown dofs (with elimination: every free dof fixed by the equalities)
    dx.resize(0);
    if (p_.has_k) dk = r1k / schur_;
    w.setZero(p_.num_eq());
    return;
  }
  Eigen::VectorXd b = r1x;
  if (p_.num_eq() > 0 && !elim_) b.noalias() += inv_rho_ * (at_ * r2);
  if (border_pending_)
    finish_bordering(b, dx);
  else
    dx = llt_solve(b);
  if (p_.has_k) {
    dk = (r1k - hxk_.dot(dx)) / schur_;
    dx.noalias() -= dk * u_;
  }
  if (p_.num_eq() > 0 && !elim_)
    w = inv_rho_ * (p_.A * dx - r2);
  else
    w.resize(0);
}

Eigen::VectorXd NormalEquations::to_dofs(const Eigen::VectorXd& y) const {
  if (!elim_) return y;
  Eigen::VectorXd x;
  apply_z(null_space_, p_.n, y, x);
  return x;
}

int NormalEquations::corner_dof(int base) const {
  return elim_ ? null_space_.node[null_space_.offset[base / p_.n]] * p_.n : base;
}

// A corner is simple when its dofs are n system dofs of their own (always without
// elimination; with it, a vertex that is its own y node). An element of simple corners maps
// each pair to one nonzero; the others (along the seams) spread each pair over the y dofs of
// their corners' terms (expand_seam_pairs).
std::vector<char> NormalEquations::simple_elements() const {
  const int n = p_.n, c = p_.corners(), E = p_.num_element_cones();
  auto simple_corner = [&](int base) {
    if (base < 0 || !elim_) return true;
    const int f = base / n, t = null_space_.offset[f];
    if (null_space_.offset[f + 1] != t + 1) return false;
    const double* b = null_space_.block.data() + static_cast<size_t>(t) * n * n;
    for (int r = 0; r < n; ++r)
      for (int s = 0; s < n; ++s)
        if (b[r * n + s] != (r == s ? 1.0 : 0.0)) return false;
    return true;
  };
  std::vector<char> simple(E, 1);
  parallel_for_index(E, kGrain, [&](int begin, int end) {
    for (int i = begin; i < end; ++i) {
      for (int j = 0; j < c; ++j)
        if (!simple_corner(p_.dof_base[i * c + j])) simple[i] = 0;
      // Two corners that are one y node (a vertex whose equalities make it equal to another,
      // x_f = x_g) are not simple either: their cross pairs land on that node's diagonal
      // block, where they count twice (below); one nonzero per pair would miss one.
      for (int j1 = 0; j1 < c && elim_ && simple[i]; ++j1)
        for (int j2 = 0; j2 < j1; ++j2) {
          const int b1 = p_.dof_base[i * c + j1], b2 = p_.dof_base[i * c + j2];
          if (b1 >= 0 && b2 >= 0 && corner_dof(b1) == corner_dof(b2)) simple[i] = 0;
        }
    }
  });
  return simple;
}

// Local dof l = (corner j, row r) is sum over its vertex's terms of block(r, s) y(node, s):
// entry (a, b) of Z^T H Z gets sum Z_ia H_ij Z_jb over ordered (i, j). A pair l1 > l2 stands
// for (l1, l2) and (l2, l1); a diagonal pair for (l, l) only. In the y dofs' own numbering,
// before the fill-reducing order.
std::vector<NormalEquations::SeamPair> NormalEquations::expand_seam_pairs(const std::vector<char>& simple) const {
  const int n = p_.n, c = p_.corners(), L = p_.local_dofs(), E = p_.num_element_cones();
  std::vector<SeamPair> pairs;
  std::vector<std::vector<std::pair<int, double>>> expansion(L);
  for (int i = 0; i < E; ++i) {
    if (simple[i]) continue;
    for (int j = 0; j < c; ++j)
      for (int r = 0; r < n; ++r) {
        auto& e = expansion[j * n + r];
        e.clear();
        const int base = p_.dof_base[i * c + j];
        if (base < 0) continue;
        const int f = base / n;
        for (int t = null_space_.offset[f]; t < null_space_.offset[f + 1]; ++t)
          for (int s = 0; s < n; ++s) {
            const double b = null_space_.block[(static_cast<size_t>(t) * n + r) * n + s];
            if (b != 0.0) e.emplace_back(null_space_.node[t] * n + s, b);
          }
      }
    for (int l1 = 0; l1 < L; ++l1)
      for (int l2 = 0; l2 <= l1; ++l2) {
        const int slot = i * npairs_ + pair_index(l1, l2);
        const auto &e1 = expansion[l1], &e2 = expansion[l2];
        for (size_t a = 0; a < e1.size(); ++a)
          for (size_t b = (l1 == l2 ? a : 0); b < e2.size(); ++b) {
            const int ya = e1[a].first, yb = e2[b].first;
            double coef = e1[a].second * e2[b].second;
            if (ya == yb && l1 != l2) coef *= 2.0;
            pairs.push_back({slot, ya, yb, coef});
          }
      }
  }
  return pairs;
}

void NormalEquations::factor_aat() {
  // A A^T (+ a tiny diagonal: redundant rows make it singular, and their right-hand sides
  // are consistent), for x = A^T (A A^T)^-1 r and least-squares multipliers.
  Eigen::SparseMatrix<double> aat = Eigen::SparseMatrix<double>(p_.A * at_);
  double mx = 0;
  for (int r = 0; r < aat.rows(); ++r) mx = std::max(mx, aat.coeff(r, r));
  for (int r = 0; r < aat.rows(); ++r) aat.coeffRef(r, r) += 1e-13 * mx;
  aat_ = std::make_unique<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>(aat);
}

void NormalEquations::apply_full(const Eigen::VectorXd& dx, double dk, Eigen::VectorXd& ox, double& ok) const {
  PhaseTimer timer(timers_.apply_wall, timers_.apply_cpu);
  ++timers_.applies;
  Eigen::VectorXd mv, t2;
  p_.apply_m(dx, p_.has_k ? dk : 0.0, false, mv);
  apply_scaling(p_, *scaling_, ScalingOp::WInv2, mv, t2);
  p_.apply_mt(t2, ox, ok);
  if (p_.has_quad()) {
    Eigen::VectorXd px;
    p_.apply_p(dx, px);
    ox += px;
  }
  if (!p_.has_k) ok = 0;
}

void NormalEquations::apply_normal(const Eigen::VectorXd& dx, double dk, Eigen::VectorXd& ox, double& ok) const {
  if (elim_) {  // Z^T (H + P) Z
    Eigen::VectorXd full;
    apply_full(to_dofs(dx), dk, full, ok);
    apply_zt(null_space_, p_.n, full, ox);
    return;
  }
  apply_full(dx, dk, ox, ok);
  if (p_.num_eq() > 0) ox.noalias() += inv_rho_ * (at_ * (p_.A * dx));
}

int NormalEquations::pcg(const Eigen::VectorXd& bx, double bk, double threshold, Eigen::VectorXd& x, double& k) const {
  // Preconditioned conjugate gradients on (H + P + A^T A / rho) (x, k) = (bx, bk), the factor
  // (with its regularisation and bordering) as the preconditioner. Near the optimum the
  // factor is accurate except in a few directions, which CG removes in a few steps.
  const Eigen::VectorXd zero_eq = Eigen::VectorXd::Zero(p_.num_eq());
  Eigen::VectorXd w, zx, px, apx;
  double zk = 0, pk = 0, apk = 0;
  solve_normal(bx, bk, zero_eq, x, k, w);
  if (nsys_ == 0) return 0;
  if (!(std::max(max_abs(bx), std::abs(bk)) > 0)) return 0;
  Eigen::VectorXd rx;
  double rk = 0;
  apply_normal(x, k, rx, rk);
  rx = bx - rx;
  rk = bk - rk;
  if (std::max(max_abs(rx), std::abs(rk)) <= threshold) return 0;
  solve_normal(rx, rk, zero_eq, zx, zk, w);
  px = zx;
  pk = zk;
  double rz = rx.dot(zx) + rk * zk;
  // CG residuals are not monotone in the max norm: keep the best iterate, stop on stagnation.
  double best = std::max(max_abs(rx), std::abs(rk));
  Eigen::VectorXd best_x = x;
  double best_k = k;
  int it = 0, stagnant = 0;
  for (; it < settings_.refinement_steps; ++it) {
    if (best <= threshold || !(rz > 0) || stagnant >= settings_.refinement_patience) break;
    apply_normal(px, pk, apx, apk);
    const double pap = px.dot(apx) + pk * apk;
    if (!(pap > 0)) break;
    const double alpha = rz / pap;
    x += alpha * px;
    k += alpha * pk;
    rx -= alpha * apx;
    rk -= alpha * apk;
    const double res = std::max(max_abs(rx), std::abs(rk));
    // Slow progress counts as stagnation too: near the optimum CG on these systems often
    // crawls for many steps without reaching the threshold, and each step costs a solve.
    if (res < settings_.refinement_progress * best)
      stagnant = 0;
    else
      ++stagnant;
    if (res < best) {
      best = res;
      best_x = x;
      best_k = k;
    }
    solve_normal(rx, rk, zero_eq, zx, zk, w);
    const double rz_new = rx.dot(zx) + rk * zk;
    const double beta = rz_new / rz;
    rz = rz_new;
    px = zx + beta * px;
    pk = zk + beta * pk;
  }
  x.swap(best_x);
  k = best_k;
  return it;
}

void NormalEquations::solve_unreduced(const Eigen::VectorXd& rdx, double rdk, const Eigen::VectorXd& rc,
                                      const Eigen::VectorXd& re, Eigen::VectorXd& dx, double& dk, Eigen::VectorXd& w,
                                      Eigen::VectorXd* dz, double threshold, int& steps, bool need_w) const {
  // dz = W^{-1} (rc - W^{-1} M dv);  (H + P) dv + A~^T w = M^T W^{-1} rc - rd,  A~ dv = re,
  // the equalities by the penalty: w = (A dx - re) / rho.
  Eigen::VectorXd t, r1x;
  apply_scaling(p_, *scaling_, ScalingOp::WInv, rc, t);
  double r1k = 0;
  p_.apply_mt(t, r1x, r1k);
  r1x -= rdx;
  r1k -= rdk;
  if (elim_) {
    // dx = x_p + Z dy with A x_p = re (least norm); Z^T (H + P) Z dy = Z^T (r1 - (H + P) x_p);
    // then A^T w = r1 - (H + P) dv in least squares (exact when the reduced equations hold).
    Eigen::VectorXd xp, hx, b, dy;
    double hk = 0;
    // Without multipliers (the predictor) an equality residual at round-off is left alone:
    // the iterates hold the equalities to about 1e-13 from the start, and every step along
    // Z keeps them (Z is exact).
    const double round_off = need_w ? 0.0 : kEqualityRoundOff;
    const bool particular = re.size() > 0 && max_abs(re) > round_off;
    Eigen::VectorXd r1 = r1x;
    double rk = r1k;
    if (particular) {
      xp = at_ * aat_->solve(re);
      apply_full(xp, 0.0, hx, hk);
      r1 -= hx;
      rk -= hk;
    }
    apply_zt(null_space_, p_.n, r1, b);
    steps = pcg(b, p_.has_k ? rk : 0.0, threshold, dy, dk);
    dx = to_dofs(dy);
    if (particular) dx += xp;
    if (need_w) {
      apply_full(dx, dk, hx, hk);
      w = aat_->solve(p_.A * (r1x - hx));
    } else {
      w.setZero(p_.num_eq());
    }
    if (dz) cone_direction_parts(p_, *scaling_, dx, p_.has_k ? dk : 0.0, &rc, dz, nullptr, nullptr, nullptr, nullptr);
    return;
  }
  if (p_.num_eq() > 0) r1x.noalias() += inv_rho_ * (at_ * re);
  steps = pcg(r1x, p_.has_k ? r1k : 0.0, threshold, dx, dk);
  if (p_.num_eq() > 0)
    w = inv_rho_ * (p_.A * dx - re);
  else
    w.resize(0);
  if (dz) cone_direction_parts(p_, *scaling_, dx, p_.has_k ? dk : 0.0, &rc, dz, nullptr, nullptr, nullptr, nullptr);
}

void NormalEquations::solve_newton(const Eigen::VectorXd& q, const Eigen::VectorXd& rs, const Eigen::VectorXd& rdx,
                                   double rdk, const Eigen::VectorXd& req, Direction& d, double tolerance,
                                   bool need_dy) {
  const Scaling& sc = *scaling_;
  Eigen::VectorXd rc, t;
  if (rs.size() == 0) {  // r_s = 0 (the centrality correctors): no pass over the cones
    rc = q;
  } else {
    apply_scaling(p_, sc, ScalingOp::WInv, rs, t);
    rc = q + t;
  }
  const Eigen::VectorXd re = -req;
  Eigen::VectorXd w;
  int steps = 0;
  // The CG residual is the dual residual of the direction: aim at refinement_tolerance
  // relative to this system's right-hand side, but no lower than round-off in dual units.
  const double scale = std::max({max_abs(rc), max_abs(rdx), std::abs(rdk), max_abs(re), 1e-300});
  const double tol = tolerance > 0 ? tolerance : settings_.refinement_tolerance;
  const double threshold = std::max(tol * scale, 1e-14);
  // Outer refinement on the unreduced system: removes the penalty's effect on the equalities
  // (always), and otherwise the round-off of forming dz = W^{-1} (rc - W^{-1} M dv) when W is
  // badly conditioned (a cone at its bound): the normal equations then hold to round-off but
  // the dual equations M^T dz = r_d, which the certificate needs, only to 1e-5 .. 1e-3.
  const bool penalty = p_.num_eq() > 0 && !elim_;
  const int outer = penalty ? 3 : settings_.unreduced_refinement;
  // The residual check costs four passes over the cones; auxiliary directions (predictor,
  // correctors: tolerance given) without equalities skip it (their CG residual is reported)
  // and form all their cone parts in one pass.
  const bool unchecked = tolerance > 0 && !penalty && settings_.verbose < 2;
  solve_unreduced(rdx, rdk, rc, re, d.dx, d.dk, w, unchecked ? nullptr : &d.dz, threshold, steps, need_dy || !unchecked);
  d.refinement = steps;
  if (unchecked) {
    d.residual = 0;
    d.dy = -w;
    cone_direction_parts(p_, sc, d.dx, p_.has_k ? d.dk : 0.0, &rc, &d.dz, &rs, &d.ds, &d.dst, &d.dzt);
    return;
  }
  // Residuals of the unreduced system.
  Eigen::VectorXd ex, ec, ee, mv, px, gx, cx, cw, cz;
  double ek = 0, ck = 0;
  auto residual = [&] {
    double gk = 0;
    p_.apply_mt(d.dz, gx, gk);  // M^T dz
    ex = rdx - gx;
    if (p_.has_quad()) {
      p_.apply_p(d.dx, px);
      ex += px;
    }
    if (p_.num_eq() > 0) ex.noalias() += at_ * w;  // -A^T dy = +A^T w
    ek = p_.has_k ? rdk - gk : 0.0;
    p_.apply_m(d.dx, p_.has_k ? d.dk : 0.0, false, mv);
    apply_scaling(p_, sc, ScalingOp::WInv, mv, t);
    apply_scaling(p_, sc, ScalingOp::W, d.dz, ec);
    ec = rc - t - ec;
    ee = p_.num_eq() > 0 ? Eigen::VectorXd(re - p_.A * d.dx) : Eigen::VectorXd();
    if (settings_.verbose >= 2)
      std::fprintf(stderr, "kkt: residual dual %.2e k %.2e compl %.2e eq %.2e (scale %.2e, %d cg steps)\n",
                   max_abs(ex) / scale, std::abs(ek) / scale, max_abs(ec) / scale, max_abs(ee) / scale, scale, steps);
    return std::max({max_abs(ex), std::abs(ek), max_abs(ec), max_abs(ee)}) / scale;
  };
  double best = residual();
  const int steps_allowed = penalty || best > settings_.unreduced_refinement_above ? outer : 0;
  for (int step = 0; step < steps_allowed && best > tol; ++step) {
    solve_unreduced(ex, ek, ec, ee, cx, ck, cw, &cz, threshold, steps);
    d.refinement += steps + 1;
    d.dx += cx;
    d.dk += ck;
    d.dz += cz;
    if (w.size()) w += cw;
    const double res = residual();
    if (!(res < best)) {  // no progress: undo and stop
      d.dx -= cx;
      d.dk -= ck;
      d.dz -= cz;
      if (w.size()) w -= cw;
      break;
    }
    best = res;
  }
  d.residual = best;
  d.dy = -w;
  // Cone parts: ds from the (linear) primal equation, scaled forms for the step.
  cone_direction_parts(p_, sc, d.dx, p_.has_k ? d.dk : 0.0, nullptr, &d.dz, &rs, &d.ds, &d.dst, &d.dzt);
}

}  // namespace strictmin::socp
