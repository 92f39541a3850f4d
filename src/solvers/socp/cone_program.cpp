#include "solvers/socp/cone_program.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "solvers/socp/fixed_sizes.h"

namespace strictmin::socp {

void parallel_for_index(int count, int grain, const std::function<void(int, int)>& body) {
  if (count <= 0) return;
  if (count <= grain) {
    body(0, count);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<int>(0, count, grain),
                    [&](const tbb::blocked_range<int>& r) { body(r.begin(), r.end()); });
}

namespace {
constexpr int kGrain = 2048;
}

void ConeProgram::finalize() {
  const int c = corners();
  const int free_vertices = num_x / n;
  incidence_offset.assign(free_vertices + 1, 0);
  for (int i = 0; i < num_element_cones(); ++i)
    for (int j = 0; j < c; ++j) {
      const int base = dof_base[i * c + j];
      if (base >= 0) ++incidence_offset[base / n + 1];
    }
  for (int f = 0; f < free_vertices; ++f) incidence_offset[f + 1] += incidence_offset[f];
  incidence.assign(incidence_offset.back(), 0);
  std::vector<int> next(incidence_offset.begin(), incidence_offset.end() - 1);
  for (int i = 0; i < num_element_cones(); ++i)
    for (int j = 0; j < c; ++j) {
      const int base = dof_base[i * c + j];
      if (base >= 0) incidence[next[base / n]++] = i * c + j;
    }
}

// The element loops below take n, m (and the corner count m + 1) as compile-time constants
// for the common element kinds (fixed_sizes.h): they run once per Newton solve or more.
void ConeProgram::apply_g(const Eigen::VectorXd& x, Eigen::VectorXd& tails) const {
  tails.resize(static_cast<Eigen::Index>(num_element_cones()) * t());
  with_element_sizes(n, m, [&](auto n_c, auto m_c) {
    parallel_for_index(num_element_cones(), kGrain, [&](int begin, int end) {
      const int nn = n_c, mm = m_c, c = mm + 1, tt = nn * mm;
      for (int i = begin; i < end; ++i) {
        double* out = tails.data() + static_cast<Eigen::Index>(i) * tt;
        for (int a = 0; a < tt; ++a) out[a] = 0.0;
        for (int j = 0; j < c; ++j) {
          const int base = dof_base[i * c + j];
          if (base < 0) continue;
          const double* g = grad.data() + (static_cast<size_t>(i) * c + j) * mm;
          for (int r = 0; r < nn; ++r) {
            const double xr = x[base + r];
            for (int col = 0; col < mm; ++col) out[r * mm + col] += xr * g[col];
          }
        }
      }
    });
  });
}

void ConeProgram::apply_gt(const double* tails, Eigen::Index stride, Eigen::Index first, Eigen::VectorXd& x) const {
  const int free_vertices = num_x / n;
  x.resize(num_x);
  with_element_sizes(n, m, [&](auto n_c, auto m_c) {
    parallel_for_index(free_vertices, kGrain, [&](int begin, int end) {
      const int nn = n_c, mm = m_c, c = mm + 1;
      for (int f = begin; f < end; ++f) {
        double acc[3] = {0, 0, 0};
        for (int e = incidence_offset[f]; e < incidence_offset[f + 1]; ++e) {
          const int i = incidence[e] / c;
          const double* g = grad.data() + static_cast<size_t>(incidence[e]) * mm;
          const double* y = tails + static_cast<Eigen::Index>(i) * stride + first;
          for (int r = 0; r < nn; ++r)
            for (int col = 0; col < mm; ++col) acc[r] += y[r * mm + col] * g[col];
        }
        for (int r = 0; r < nn; ++r) x[f * nn + r] = acc[r];
      }
    });
  });
}

void ConeProgram::apply_m(const Eigen::VectorXd& x, double k, bool with_offset, Eigen::VectorXd& out) const {
  const int E = num_element_cones();
  out.resize(cone_size());
  with_element_sizes(n, m, [&](auto n_c, auto m_c) {
    parallel_for_index(E, kGrain, [&](int begin, int end) {
      const Eigen::Index d = static_cast<int>(n_c) * static_cast<int>(m_c) + 1;
      for (int i = begin; i < end; ++i) element_m(*this, n_c, m_c, i, x.data(), k, with_offset, out.data() + i * d);
    });
  });
  if (has_scalar) out[cone_offset(E)] = head_a[E] * k + (with_offset ? head_b[E] : 0.0);
}

void ConeProgram::apply_mt(const Eigen::VectorXd& u, Eigen::VectorXd& gx, double& gk) const {
  apply_gt(u.data(), t() + 1, 1, gx);
  gk = 0;
  if (!has_k) return;
  for (int i = 0; i < num_element_cones(); ++i) gk += head_a[i] * u[cone_offset(i)];
  if (has_scalar) gk += head_a[num_element_cones()] * u[cone_offset(num_element_cones())];
}

void ConeProgram::apply_p(const Eigen::VectorXd& x, Eigen::VectorXd& out) const {
  if (!has_quad()) {
    out.setZero(num_x);
    return;
  }
  Eigen::VectorXd tails;
  apply_g(x, tails);
  const int tt = t();
  for (int i = 0; i < num_element_cones(); ++i) tails.segment(static_cast<Eigen::Index>(i) * tt, tt) *= 2.0 * quad_weight[i];
  apply_gt(tails.data(), tt, 0, out);
}

Eigen::VectorXd ConeProgram::linear_term() const {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(num_x);
  if (!has_quad()) return q;
  const int tt = t();
  Eigen::VectorXd scaled(h.size());
  for (int i = 0; i < num_element_cones(); ++i)
    scaled.segment(static_cast<Eigen::Index>(i) * tt, tt) = -2.0 * quad_weight[i] * h.segment(static_cast<Eigen::Index>(i) * tt, tt);
  apply_gt(scaled.data(), tt, 0, q);
  return q;
}

double ConeProgram::constant_term() const {
  if (!has_quad()) return 0.0;
  const int tt = t();
  double sum = 0;
  for (int i = 0; i < num_element_cones(); ++i)
    sum += quad_weight[i] * h.segment(static_cast<Eigen::Index>(i) * tt, tt).squaredNorm();
  return sum;
}

}  // namespace strictmin::socp
