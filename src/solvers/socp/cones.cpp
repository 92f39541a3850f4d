#include "solvers/socp/cones.h"

#include <algorithm>
#include <atomic>
#include <limits>
#include <stdexcept>
#include <tbb/parallel_reduce.h>
#include <tbb/blocked_range.h>

#include "solvers/socp/fixed_sizes.h"
#include "solvers/socp/soc.h"

namespace strictmin::socp {
namespace {

constexpr int kGrain = 4096;
constexpr int kMaxConeDim = 16;  // element cones have at most 10 entries (n, m <= 3: tets)

// f(i, offset, dim) for every cone; the element cones with their dimension known at compile
// time (fixed_sizes.h), the optional scalar cone last.
template <class F>
void for_each_cone(const ConeProgram& p, F&& f) {
  const int E = p.num_element_cones();
  with_cone_dim(p.t() + 1, [&](auto dim) {
    parallel_for_index(E, kGrain, [&](int begin, int end) {
      const int d = dim;
      for (int i = begin; i < end; ++i) f(i, static_cast<Eigen::Index>(i) * d, d);
    });
  });
  if (p.has_scalar) f(E, p.cone_offset(E), 1);
}

template <class F>
double min_over_cones(const ConeProgram& p, F&& f) {
  const int E = p.num_element_cones();
  double result = with_cone_dim(p.t() + 1, [&](auto dim) {
    return tbb::parallel_reduce(
        tbb::blocked_range<int>(0, E, kGrain), std::numeric_limits<double>::infinity(),
        [&](const tbb::blocked_range<int>& r, double acc) {
          const int d = dim;
          for (int i = r.begin(); i < r.end(); ++i) acc = std::min(acc, f(static_cast<Eigen::Index>(i) * d, d));
          return acc;
        },
        [](double a, double b) { return std::min(a, b); });
  });
  if (p.has_scalar) result = std::min(result, f(p.cone_offset(E), 1));
  return result;
}

}  // namespace

bool compute_scaling(const ConeProgram& p, const Eigen::VectorXd& s, const Eigen::VectorXd& z, Scaling& out) {
  out.beta.resize(p.num_cones());
  out.w.resize(p.cone_size());
  out.lambda.resize(p.cone_size());
  std::atomic<bool> ok{true};
  for_each_cone(p, [&](int i, Eigen::Index o, int d) {
    double beta = 1;
    if (!nt_scaling(s.data() + o, z.data() + o, d, beta, out.w.data() + o)) {
      ok = false;
      return;
    }
    out.beta[i] = beta;
    apply_w(beta, out.w.data() + o, d, z.data() + o, out.lambda.data() + o);
  });
  return ok;
}

void apply_scaling(const ConeProgram& p, const Scaling& sc, ScalingOp op, const Eigen::VectorXd& u, Eigen::VectorXd& out) {
  out.resize(p.cone_size());
  for_each_cone(p, [&](int i, Eigen::Index o, int d) {
    const double* w = sc.w.data() + o;
    switch (op) {
      case ScalingOp::W: apply_w(sc.beta[i], w, d, u.data() + o, out.data() + o); break;
      case ScalingOp::WInv: apply_winv(sc.beta[i], w, d, u.data() + o, out.data() + o); break;
      case ScalingOp::WInv2: apply_winv2(sc.beta[i], w, d, u.data() + o, out.data() + o); break;
    }
  });
}

void cone_direction_parts(const ConeProgram& p, const Scaling& sc, const Eigen::VectorXd& dx, double dk,
                          const Eigen::VectorXd* rc, Eigen::VectorXd* dz, const Eigen::VectorXd* rs,
                          Eigen::VectorXd* ds, Eigen::VectorXd* dst, Eigen::VectorXd* dzt) {
  const Eigen::Index size = p.cone_size();
  const bool make_dz = rc && dz, make_ds = rs && ds;
  if (p.t() + 1 > kMaxConeDim) throw std::logic_error("cone_direction_parts: element cones above 16 entries");
  if (make_dz) dz->resize(size);
  if (make_ds) ds->resize(size);
  if (make_ds && dst) dst->resize(size);
  if (dzt) dzt->resize(size);
  // One cone: m given (d entries) at offset o.
  auto finish = [&](int i, Eigen::Index o, int d, const double* m) {
    double t[kMaxConeDim];
    const double beta = sc.beta[i];
    const double* w = sc.w.data() + o;
    if (make_dz) {
      apply_winv(beta, w, d, m, t);
      const double* r = rc->data() + o;
      for (int a = 0; a < d; ++a) t[a] = r[a] - t[a];
      apply_winv(beta, w, d, t, dz->data() + o);
    }
    if (make_ds) {
      double* s = ds->data() + o;
      if (rs->size() == 0) {
        for (int a = 0; a < d; ++a) s[a] = m[a];
      } else {
        const double* r = rs->data() + o;
        for (int a = 0; a < d; ++a) s[a] = m[a] - r[a];
      }
      if (dst) apply_winv(beta, w, d, s, dst->data() + o);
    }
    if (dzt) apply_w(beta, w, d, dz->data() + o, dzt->data() + o);
  };
  const int E = p.num_element_cones();
  with_element_sizes(p.n, p.m, [&](auto n_c, auto m_c) {
    parallel_for_index(E, kGrain, [&](int begin, int end) {
      const int d = static_cast<int>(n_c) * static_cast<int>(m_c) + 1;
      double m[kMaxConeDim];
      for (int i = begin; i < end; ++i) {
        element_m(p, n_c, m_c, i, dx.data(), dk, false, m);
        finish(i, static_cast<Eigen::Index>(i) * d, d, m);
      }
    });
  });
  if (p.has_scalar) {
    const double m = p.head_a[E] * dk;
    finish(E, p.cone_offset(E), 1, &m);
  }
}

void cone_product(const ConeProgram& p, const Eigen::VectorXd& a, const Eigen::VectorXd& b, Eigen::VectorXd& out) {
  out.resize(p.cone_size());
  for_each_cone(p, [&](int, Eigen::Index o, int d) { jordan_product(a.data() + o, b.data() + o, d, out.data() + o); });
}

void cone_arrow_solve(const ConeProgram& p, const Eigen::VectorXd& l, const Eigen::VectorXd& r, Eigen::VectorXd& out) {
  out.resize(p.cone_size());
  for_each_cone(p, [&](int, Eigen::Index o, int d) { arrow_solve(l.data() + o, r.data() + o, d, out.data() + o); });
}

Eigen::VectorXd cone_identity(const ConeProgram& p, double value) {
  Eigen::VectorXd e = Eigen::VectorXd::Zero(p.cone_size());
  for (int i = 0; i < p.num_cones(); ++i) e[p.cone_offset(i)] = value;
  return e;
}

void cone_centrality_correction(const ConeProgram& p, const Eigen::VectorXd& v, double lo, double hi, Eigen::VectorXd& t) {
  t.resize(p.cone_size());
  auto move = [&](double e) {
    if (e < lo) return lo - e;
    if (e > hi) return std::max(hi - e, -hi);
    return 0.0;
  };
  for_each_cone(p, [&](int, Eigen::Index o, int d) {
    const double* vv = v.data() + o;
    double* out = t.data() + o;
    const double r = tail_norm(vv, d);
    const double tp = move(vv[0] + r), tm = move(vv[0] - r);
    // t = tp f+ + tm f-, f+- = (1, +-v1/||v1||) / 2.
    out[0] = 0.5 * (tp + tm);
    const double f = r > 0 ? 0.5 * (tp - tm) / r : 0.0;
    for (int j = 1; j < d; ++j) out[j] = f * vv[j];
  });
}

double cone_max_step(const ConeProgram& p, const Eigen::VectorXd& l, const Eigen::VectorXd& u) {
  return min_over_cones(p, [&](Eigen::Index o, int d) { return max_step(l.data() + o, u.data() + o, d); });
}

double cone_max_step_of_sum(const ConeProgram& p, const Eigen::VectorXd& l, const Eigen::VectorXd& u,
                            const Eigen::VectorXd& v) {
  return min_over_cones(p, [&](Eigen::Index o, int d) {
    double w[kMaxConeDim];
    for (int i = 0; i < d; ++i) w[i] = u[o + i] + v[o + i];
    return max_step(l.data() + o, w, d);
  });
}

double cone_min_margin(const ConeProgram& p, const Eigen::VectorXd& u) {
  return min_over_cones(p, [&](Eigen::Index o, int d) { return u[o] - tail_norm(u.data() + o, d); });
}

}  // namespace strictmin::socp
