#include "solvers/socp/residuals.h"

#include <algorithm>
#include <cmath>

namespace strictmin::socp {
namespace {
double max_abs(const Eigen::VectorXd& v) { return v.size() ? v.cwiseAbs().maxCoeff() : 0.0; }
}  // namespace

ResidualScales residual_scales(const ConeProgram& p) {
  ResidualScales sc;
  sc.primal = std::max({1.0, max_abs(p.h), max_abs(p.head_b), max_abs(p.beq)});
  sc.dual = std::max({1.0, std::abs(p.c_k), max_abs(p.linear_term())});
  return sc;
}

void compute_residuals(const ConeProgram& p, const ResidualScales& scales, const IpmState& st, Residuals& out) {
  Eigen::VectorXd mv;
  p.apply_m(st.x, st.k, true, mv);
  out.rs = st.s - mv;
  const int E = p.num_element_cones(), tt = p.t();
  out.tail_norms.resize(E);
  parallel_for_index(E, 4096, [&](int begin, int end) {
    for (int i = begin; i < end; ++i) out.tail_norms[i] = mv.segment(p.cone_offset(i) + 1, tt).norm();
  });
  double gk = 0;
  p.apply_mt(st.z, out.rdx, gk);
  out.rdx = -out.rdx;
  double quad = 0, lin = 0;
  if (p.has_quad()) {
    Eigen::VectorXd px;
    p.apply_p(st.x, px);
    const Eigen::VectorXd q = p.linear_term();
    out.rdx += px + q;
    quad = 0.5 * st.x.dot(px);
    lin = q.dot(st.x);
  }
  if (p.num_eq() > 0) {
    out.rdx.noalias() -= p.A.transpose() * st.y;
    out.req = p.A * st.x - p.beq;
  } else {
    out.req.resize(0);
  }
  out.rdk = p.has_k ? p.c_k - gk : 0.0;
  // -z^T o = sum_i (-b_i z_i0 + h_i^T z_i,tail)
  double zo = 0;
  for (int i = 0; i < p.num_element_cones(); ++i) {
    const Eigen::Index o = p.cone_offset(i);
    zo += -p.head_b[i] * st.z[o] + p.h.segment(static_cast<Eigen::Index>(i) * tt, tt).dot(st.z.segment(o + 1, tt));
  }
  if (p.has_scalar) zo += -p.head_b[p.num_element_cones()] * st.z[p.cone_offset(p.num_element_cones())];
  const double cst = p.constant_term();
  out.pobj = quad + lin + (p.has_k ? p.c_k * st.k : 0.0) + cst;
  out.dobj = -quad + zo + (p.num_eq() > 0 ? p.beq.dot(st.y) : 0.0) + cst;
  out.gap = st.s.dot(st.z);
  out.pres = std::max(max_abs(out.rs), max_abs(out.req)) / scales.primal;
  out.dres = std::max(max_abs(out.rdx), std::abs(out.rdk)) / scales.dual;
}

}  // namespace strictmin::socp
