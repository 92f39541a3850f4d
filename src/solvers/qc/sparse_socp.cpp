#include "solvers/qc/sparse_socp.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <stdexcept>

#include "solvers/socp/soc.h"
#include "strictmin/solvers/interrupt.h"
#include "strictmin/solvers/sparse_cholesky.h"

namespace strictmin::qc {

struct SparseCholeskyCache::Impl {
  SparseCholesky cholesky{true};  // AMD: the slack's dense column goes last
  SparseCholesky gram{true};      // G^T D G, for corrected_dual_bound
};
SparseCholeskyCache::SparseCholeskyCache() : impl_(new Impl) {}
SparseCholeskyCache::~SparseCholeskyCache() { delete impl_; }

namespace {

using socp::apply_w;
using socp::apply_winv;
using socp::arrow_solve;
using socp::jordan_product;
using socp::max_step;
using socp::nt_scaling;
using socp::soc_interior;
using socp::tail_norm;

double max_abs(const Eigen::VectorXd& v) { return v.size() ? v.cwiseAbs().maxCoeff() : 0.0; }

// The cones' row offsets.
std::vector<int> cone_offsets(const SparseSocp& p) {
  std::vector<int> off(p.dims.size() + 1, 0);
  for (size_t i = 0; i < p.dims.size(); ++i) off[i + 1] = off[i] + p.dims[i];
  return off;
}

// Nesterov-Todd scaling of every cone (socp/soc.h): W_i = beta_i (2 w_i w_i^T - J).
struct Scaling {
  Eigen::VectorXd beta, w, lambda;
};

class Cones {
 public:
  explicit Cones(const SparseSocp& p) : dims_(p.dims), off_(cone_offsets(p)) {}
  int count() const { return static_cast<int>(dims_.size()); }
  int dim(int i) const { return dims_[i]; }
  int offset(int i) const { return off_[i]; }

  // Moves u inside every cone: u_i += (||u_i1|| - u_i0 + margin)_+ e.
  void push_inside(Eigen::VectorXd& u, double margin) const {
    for (int i = 0; i < count(); ++i) {
      double* ui = u.data() + off_[i];
      const double need = (dims_[i] > 1 ? tail_norm(ui, dims_[i]) : 0.0) - ui[0] + margin;
      if (need > 0) ui[0] += need;
    }
  }
  bool scale(const Eigen::VectorXd& s, const Eigen::VectorXd& z, Scaling& sc) const {
    sc.beta.resize(count());
    sc.w.resize(s.size());
    sc.lambda.resize(s.size());
    for (int i = 0; i < count(); ++i) {
      const int o = off_[i], d = dims_[i];
      if (!nt_scaling(s.data() + o, z.data() + o, d, sc.beta[i], sc.w.data() + o)) return false;
      apply_w(sc.beta[i], sc.w.data() + o, d, z.data() + o, sc.lambda.data() + o);
    }
    return true;
  }
  enum class Op { W, WInv };
  void apply(const Scaling& sc, Op op, const Eigen::VectorXd& u, Eigen::VectorXd& out) const {
    out.resize(u.size());
    for (int i = 0; i < count(); ++i) {
      const int o = off_[i], d = dims_[i];
      if (op == Op::W)
        apply_w(sc.beta[i], sc.w.data() + o, d, u.data() + o, out.data() + o);
      else
        apply_winv(sc.beta[i], sc.w.data() + o, d, u.data() + o, out.data() + o);
    }
  }
  void product(const Eigen::VectorXd& a, const Eigen::VectorXd& b, Eigen::VectorXd& out) const {
    out.resize(a.size());
    for (int i = 0; i < count(); ++i) jordan_product(a.data() + off_[i], b.data() + off_[i], dims_[i], out.data() + off_[i]);
  }
  void arrow(const Eigen::VectorXd& l, const Eigen::VectorXd& r, Eigen::VectorXd& out) const {
    out.resize(l.size());
    for (int i = 0; i < count(); ++i) arrow_solve(l.data() + off_[i], r.data() + off_[i], dims_[i], out.data() + off_[i]);
  }
  Eigen::VectorXd identity(double value) const {
    Eigen::VectorXd e = Eigen::VectorXd::Zero(off_.back());
    for (int i = 0; i < count(); ++i) e[off_[i]] = value;
    return e;
  }
  double step(const Eigen::VectorXd& l, const Eigen::VectorXd& u) const {
    double a = std::numeric_limits<double>::infinity();
    for (int i = 0; i < count(); ++i) a = std::min(a, max_step(l.data() + off_[i], u.data() + off_[i], dims_[i]));
    return a;
  }
 private:
  std::vector<int> dims_;
  std::vector<int> off_;
};

// The normal equations H dx = r with H = G^T W^{-2} G (+ regularisation), refined against
// the unregularised H. H's pattern (lower triangle) and each cone's slots in it are found
// once; every factorisation refills the values in place, cone by cone:
//   H_i = G_i^T W_i^{-2} G_i = (1/beta_i^2) (2 p p^T - G_i^T J G_i),  p = G_i^T v_i
// (soc.h: W^{-2} = (1/beta^2)(2 v v^T - J)), with G_i^T J G_i constant and kept.
class Normal {
 public:
  Normal(const SparseSocp& p, const Cones& cones, const SparseSocpSettings& st, SparseCholesky& chol)
      : p_(p), cones_(cones), st_(st), chol_(chol) {
    build();
  }
  bool factor(const Scaling& sc) {
    sc_ = &sc;
    // 1. Element contributions into the values (in place).
    double* values = h_.valuePtr();
    std::fill(values, values + h_.nonZeros(), 0.0);
    double v[16], pv[64];
    for (int i = 0; i < cones_.count(); ++i) {
      const int d = cones_.dim(i), nc = cols_off_[i + 1] - cols_off_[i];
      const double* g = local_g_.data() + g_off_[i];
      socp::winv2_vector(sc.w.data() + cones_.offset(i), d, v);
      const double ib2 = 1.0 / (sc.beta[i] * sc.beta[i]);
      for (int a = 0; a < nc; ++a) {
        double t = 0;
        for (int r = 0; r < d; ++r) t += v[r] * g[r * nc + a];
        pv[a] = t;
      }
      const int* slot = slots_.data() + slot_off_[i];
      const double* gjg = gjg_.data() + slot_off_[i];
      for (int a = 0, k = 0; a < nc; ++a)
        for (int b = 0; b <= a; ++b, ++k) values[slot[k]] += ib2 * (2.0 * pv[a] * pv[b] - gjg[k]);
    }
    // 2. Regularised factorisation (raised on failure), each diagonal entry raised relative to
    //    itself: the dense columns (tau, S) carry a diagonal many orders above the map's, and a
    //    shift relative to the largest entry perturbed the map's columns enough that the dual
    //    residual grew to 1e-8 near the optimum and no bound could be certified there.
    double mx = 0;
    for (int j : diag_) mx = std::max(mx, values[j]);
    if (!(mx > 0) || !std::isfinite(mx)) return false;
    saved_.resize(static_cast<Eigen::Index>(diag_.size()));
    for (size_t j = 0; j < diag_.size(); ++j) saved_[j] = values[diag_[j]];
    for (double delta = st_.regularization; delta < 1e-2; delta *= 100) {
      delta_ = delta;
      for (size_t j = 0; j < diag_.size(); ++j) values[diag_[j]] = saved_[j] * (1 + delta) + 1e-6 * delta * mx + 1e-300;
      if (!chol_.analyzed()) chol_.analyze(h_);
      if (chol_.factorize(h_)) return true;
    }
    return false;
  }
  // W^{-2} u, cone by cone.
  void winv2(const Eigen::VectorXd& u, Eigen::VectorXd& out) const {
    Eigen::VectorXd t;
    cones_.apply(*sc_, Cones::Op::WInv, u, t);
    cones_.apply(*sc_, Cones::Op::WInv, t, out);
  }
  // Iterative refinement until the residual reaches round-off or stops falling (by half per
  // step; a step that raised it is undone).
  Eigen::VectorXd solve(const Eigen::VectorXd& r) const {
    Eigen::VectorXd x = chol_.solve(r), w, previous;
    const double scale = std::max(1e-300, max_abs(r));
    double last = std::numeric_limits<double>::infinity();
    for (int k = 0; k <= st_.refinement_steps; ++k) {
      winv2(p_.G * x, w);
      const Eigen::VectorXd res = r - p_.G.transpose() * w;
      const double size = max_abs(res);
      if (size > last) {  // the last step made it worse
        x = previous;
        break;
      }
      last_residual_ = size / scale;
      if (size <= 1e-15 * std::max(1.0, max_abs(r)) || size > 0.5 * last || k == st_.refinement_steps) break;
      last = size;
      previous = x;
      x += chol_.solve(res);
    }
    return x;
  }
  double last_residual() const { return last_residual_; }
  double delta() const { return delta_; }

 private:
  // Each cone's columns, its dense rows of G, the lower-triangle pattern of H and the slots.
  void build() {
    const Eigen::SparseMatrix<double, Eigen::RowMajor> rows = p_.G;
    const int n = static_cast<int>(p_.G.cols()), E = cones_.count();
    cols_off_.assign(E + 1, 0);
    g_off_.assign(E + 1, 0);
    std::vector<Eigen::Triplet<double>> pattern;
    for (int i = 0; i < E; ++i) {
      const int o = cones_.offset(i), d = cones_.dim(i);
      std::vector<int> cols;
      for (int r = o; r < o + d; ++r)
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(rows, r); it; ++it)
          cols.push_back(static_cast<int>(it.col()));
      std::sort(cols.begin(), cols.end());
      cols.erase(std::unique(cols.begin(), cols.end()), cols.end());
      const int nc = static_cast<int>(cols.size());
      if (d > 16 || nc > 64)  // the fixed buffers of factor()
        throw std::invalid_argument("sparse SOCP: cones of at most 16 rows over at most 64 variables");
      cols_.insert(cols_.end(), cols.begin(), cols.end());
      cols_off_[i + 1] = cols_off_[i] + nc;
      std::vector<double> g(static_cast<size_t>(d) * nc, 0.0);
      for (int r = o; r < o + d; ++r)
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(rows, r); it; ++it) {
          const int a = static_cast<int>(std::lower_bound(cols.begin(), cols.end(), it.col()) - cols.begin());
          g[static_cast<size_t>(r - o) * nc + a] += it.value();
        }
      local_g_.insert(local_g_.end(), g.begin(), g.end());
      g_off_[i + 1] = g_off_[i] + d * nc;
      for (int a = 0; a < nc; ++a)
        for (int b = 0; b <= a; ++b) {
          pattern.emplace_back(cols[a], cols[b], 0.0);
          double t = 0;  // (G^T J G)_ab
          for (int r = 0; r < d; ++r) t += (r == 0 ? 1.0 : -1.0) * g[r * nc + a] * g[r * nc + b];
          gjg_.push_back(t);
        }
    }
    for (int j = 0; j < n; ++j) pattern.emplace_back(j, j, 0.0);  // every diagonal entry
    h_.resize(n, n);
    h_.setFromTriplets(pattern.begin(), pattern.end());
    h_.makeCompressed();
    auto index = [&](int r, int c) {
      const int* first = h_.innerIndexPtr() + h_.outerIndexPtr()[c];
      const int* last = h_.innerIndexPtr() + h_.outerIndexPtr()[c + 1];
      return static_cast<int>(std::lower_bound(first, last, r) - h_.innerIndexPtr());
    };
    slot_off_.assign(E + 1, 0);
    for (int i = 0; i < E; ++i) {
      const int* cols = cols_.data() + cols_off_[i];
      const int nc = cols_off_[i + 1] - cols_off_[i];
      for (int a = 0; a < nc; ++a)
        for (int b = 0; b <= a; ++b) slots_.push_back(index(cols[a], cols[b]));
      slot_off_[i + 1] = static_cast<int>(slots_.size());
    }
    diag_.resize(n);
    for (int j = 0; j < n; ++j) diag_[j] = index(j, j);
  }

  const SparseSocp& p_;
  const Cones& cones_;
  const SparseSocpSettings& st_;
  SparseCholesky& chol_;
  const Scaling* sc_ = nullptr;
  Eigen::SparseMatrix<double> h_;  // lower triangle of H
  std::vector<int> cols_, cols_off_, g_off_, slots_, slot_off_, diag_;
  std::vector<double> local_g_, gjg_;
  Eigen::VectorXd saved_;
  mutable double last_residual_ = 0;
  double delta_ = 0;
};

}  // namespace

SparseSocpOutcome solve_sparse_socp(const SparseSocp& p, const Eigen::VectorXd& x0, const SparseSocpSettings& settings,
                                    const SparseSocpMonitor& monitor, SparseCholeskyCache* cache) {
  // 1. Start: x from the caller, s = h - G x pushed inside the cones, z = e.
  const Cones cones(p);
  std::unique_ptr<SparseCholeskyCache> own;
  if (!cache) {
    own = std::make_unique<SparseCholeskyCache>();
    cache = own.get();
  }
  Normal normal(p, cones, settings, cache->impl().cholesky);
  SparseSocpOutcome out;
  Eigen::VectorXd x = x0, s = p.h - p.G * x0;
  const double scale_h = std::max(1.0, max_abs(p.h)), scale_c = std::max(1.0, max_abs(p.c));
  cones.push_inside(s, 1.0);
  Eigen::VectorXd z = cones.identity(1.0);
  const int ncones = cones.count();
  Scaling sc;
  double best_worst = std::numeric_limits<double>::infinity();
  int stalled = 0;
  for (int it = 0;; ++it) {
    check_interrupt();  // solvers/interrupt.h
    // 2. Residuals: rx = c + G^T z (dual), rz = G x + s - h (primal); objectives, gap.
    const Eigen::VectorXd rx = p.c + p.G.transpose() * z;
    const Eigen::VectorXd rz = p.G * x + s - p.h;
    out.pobj = p.c.dot(x);
    out.dobj = -p.h.dot(z);
    const double gap = s.dot(z);
    out.pres = max_abs(rz) / scale_h;
    out.dres = max_abs(rx) / scale_c;
    out.iterations = it;
    SparseSocpIterate info{it, &x, &z, out.pobj, out.dobj, gap, out.pres, out.dres};
    if (settings.verbose)
      std::fprintf(stderr, "socp %3d  pobj %+.10e  dobj %+.10e  gap %.2e  pres %.2e  dres %.2e\n", it, out.pobj,
                   out.dobj, gap, out.pres, out.dres);
    if (monitor && monitor(info)) {
      out.status = SparseSocpStatus::Stopped;
      break;
    }
    if (out.pres <= settings.feasibility_tolerance && out.dres <= settings.feasibility_tolerance &&
        gap <= settings.gap_tolerance * std::max(1.0, std::abs(out.pobj))) {
      out.status = SparseSocpStatus::Converged;
      break;
    }
    // Stalled: the residuals and the gap no longer fall (the normal equations' accuracy is
    // exhausted near the optimum): eight iterations without lowering the worst of them by 10%.
    const double worst = std::max({out.pres, out.dres, gap / std::max(1.0, std::abs(out.pobj))});
    if (worst < 0.9 * best_worst) {
      best_worst = worst;
      stalled = 0;
    } else if (++stalled >= 8) {
      out.status = SparseSocpStatus::NumericalError;
      out.message = "the cone program stalled (residuals and gap no longer fall)";
      break;
    }
    if (it >= settings.max_iterations) {
      out.status = SparseSocpStatus::MaxIterations;
      out.message = "the cone program reached its iteration limit";
      break;
    }
    // 3. Scaling and the normal equations' factorisation.
    if (!cones.scale(s, z, sc)) {
      out.status = SparseSocpStatus::NumericalError;
      out.message = "an iterate left the cones' interior";
      break;
    }
    if (!normal.factor(sc)) {
      out.status = SparseSocpStatus::NumericalError;
      out.message = "the normal equations could not be factorised";
      break;
    }
    const double mu = gap / ncones;
    // Newton direction for lambda o (W^{-1} ds + W dz) = rc:
    //   q = lambda \ rc, H dx = -rx - G^T (W^{-1} q + W^{-2} rz), dz = W^{-2} (G dx + W q + rz),
    //   ds = -rz - G dx (the primal equation, exactly: W (q - W dz) is the same in exact
    //   arithmetic, but W^2 dz cancels badly near the optimum and the primal residual grows).
    auto direction = [&](const Eigen::VectorXd& rc, Eigen::VectorXd& dx, Eigen::VectorXd& ds, Eigen::VectorXd& dz) {
      Eigen::VectorXd q, wiq, t;
      cones.arrow(sc.lambda, rc, q);
      cones.apply(sc, Cones::Op::WInv, q, wiq);
      normal.winv2(rz, t);
      dx = normal.solve(-rx - p.G.transpose() * (wiq + t));
      ds = -rz - p.G * dx;
      normal.winv2(ds, t);
      dz = wiq - t;
      // dz = W^{-1} q - W^{-2} ds  (from W^{-1} ds + W dz = q)
    };
    // 4. Predictor (affine) direction and Mehrotra's centring parameter.
    Eigen::VectorXd ll, dxa, dsa, dza;
    cones.product(sc.lambda, sc.lambda, ll);
    direction(-ll, dxa, dsa, dza);
    const double alpha_a = std::min({1.0, cones.step(s, dsa), cones.step(z, dza)});
    const double sigma = std::pow(1.0 - alpha_a, 3);
    // 5. Combined direction with the second-order term (W^{-1} ds_a) o (W dz_a).
    Eigen::VectorXd sa, za, so;
    cones.apply(sc, Cones::Op::WInv, dsa, sa);
    cones.apply(sc, Cones::Op::W, dza, za);
    cones.product(sa, za, so);
    Eigen::VectorXd dx, ds, dz;
    direction(-ll - so + cones.identity(sigma * mu), dx, ds, dz);
    if (settings.verbose)
      std::fprintf(stderr, "      sigma %.2e  regularization %.1e  normal residual %.2e\n", sigma, normal.delta(),
                   normal.last_residual());
    if (!dx.allFinite() || !ds.allFinite() || !dz.allFinite()) {
      out.status = SparseSocpStatus::NumericalError;
      out.message = "the Newton direction is not finite";
      break;
    }
    // 6. Step: a fraction of the longest step keeping s and z inside.
    const double alpha = std::min(1.0, settings.step_fraction * std::min(cones.step(s, ds), cones.step(z, dz)));
    x += alpha * dx;
    s += alpha * ds;
    z += alpha * dz;
    if (!(alpha > 1e-12)) {
      out.status = SparseSocpStatus::NumericalError;
      out.message = "the step length vanished";
      break;
    }
  }
  out.x = x;
  out.s = s;
  out.z = z;
  return out;
}

double corrected_dual_bound(const SparseSocp& p, const Eigen::VectorXd& z, SparseCholeskyCache* cache,
                            const Eigen::VectorXd& head_bounds) {
  constexpr double kNone = -std::numeric_limits<double>::infinity();
  std::unique_ptr<SparseCholeskyCache> own;
  if (!cache) {
    own = std::make_unique<SparseCholeskyCache>();
    cache = own.get();
  }
  const Cones cones(p);
  SparseCholesky& chol = cache->impl().gram;
  auto margin = [&](const Eigen::VectorXd& u, int i) {
    const int o = cones.offset(i);
    return u[o] - (cones.dim(i) > 1 ? tail_norm(u.data() + o, cones.dim(i)) : 0.0);
  };
  constexpr int kRounds = 3;
  double best = kNone;
  Eigen::VectorXd zc = z, d(p.G.rows());
  for (int round = 0; round < kRounds; ++round) {
    // 1. The metric: per cone its margin squared (z_i0 - |z_i1|)^2, so that the least
    //    correction in it moves no cone by more than a fraction of its margin when it can.
    for (int i = 0; i < cones.count(); ++i) {
      const double m = margin(zc, i);
      d.segment(cones.offset(i), cones.dim(i)).setConstant(std::clamp(m * m, 1e-200, 1e200));
    }
    // 2. The residual and the correction dz = -D G (G^T D G)^{-1} r.
    const Eigen::VectorXd r = p.c + p.G.transpose() * zc;
    Eigen::SparseMatrix<double> gtg = p.G.transpose() * d.asDiagonal() * p.G;
    double mx = 0;
    for (int j = 0; j < gtg.cols(); ++j) mx = std::max(mx, gtg.coeff(j, j));
    for (int j = 0; j < gtg.cols(); ++j) gtg.coeffRef(j, j) += 1e-14 * mx;
    if (!chol.analyzed()) chol.analyze(gtg);
    if (!chol.factorize(gtg)) return best;
    Eigen::VectorXd y = chol.solve(r);
    y += chol.solve(r - p.G.transpose() * (d.asDiagonal() * (p.G * y)));  // one refinement step
    zc -= d.asDiagonal() * (p.G * y);
    // 3. Inside every cone: weak duality holds for the corrected z. Otherwise the heads of
    //    the cones left are raised back inside (by twice what they missed) and the new
    //    residual is corrected in the next round.
    const double raw = -p.h.dot(zc);  // z as corrected: its residual is zero
    int out = 0;
    double worst = 0, missed = 0;  // sum of the misses times their heads' bounds
    for (int i = 0; i < cones.count(); ++i) {
      const double m = margin(zc, i);
      if (!(m >= 0)) {
        ++out;
        worst = std::min(worst, m);
        missed -= m * (head_bounds.size() ? head_bounds[i] : 0.0);
        zc[cones.offset(i)] += -2 * m;
      }
    }
    if (out == 0) return std::max(best, raw);
    if (!std::isfinite(worst)) return best;
    // 4. With bounds B_i on the heads: z raised by exactly its misses (Delta, on the heads)
    //    is in the cones, and for every feasible w, c^T w >= -h^T z - Delta^T s(w) >=
    //    raw - sum_i B_i miss_i.
    if (head_bounds.size() && std::isfinite(missed)) best = std::max(best, raw - missed);
  }
  return best;
}

}  // namespace strictmin::qc
