#include "strictmin/solvers/socp/ipm.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "strictmin/solvers/socp/cones.h"
#include "strictmin/solvers/socp/kkt.h"
#include "strictmin/solvers/socp/soc.h"

namespace strictmin::socp {
namespace {



void fill_info(const Residuals& r, double nu, IpmIteration& info) {
  info.pobj = r.pobj;
  info.dobj = r.dobj;
  info.gap = r.gap;
  info.mu = nu > 0 ? r.gap / nu : 0.0;
  info.pres = r.pres;
  info.dres = r.dres;
}

}  // namespace

void initialize(const ConeProgram& p, const Eigen::VectorXd& x0, double k0, double margin, double dual_scale,
                IpmState& st) {
  st.x = x0;
  st.k = p.has_k ? k0 : 0.0;
  p.apply_m(st.x, st.k, true, st.s);
  st.z.resize(p.cone_size());
  double denom = 0;
  for (int i = 0; i < p.num_cones(); ++i) {
    const Eigen::Index o = p.cone_offset(i);
    const int d = p.cone_dim(i);
    double* s = st.s.data() + o;
    const double tn = tail_norm(s, d);
    if (s[0] - tn < margin) s[0] = tn + margin;
    const double det = soc_det(s, d);
    double* z = st.z.data() + o;
    z[0] = s[0] / det;
    for (int j = 1; j < d; ++j) z[j] = -s[j] / det;
    denom += p.head_a[i] * z[0];
  }
  const double mu0 = (p.has_k && denom > 0) ? p.c_k / denom : dual_scale;
  st.z *= mu0;
  st.y.setZero(p.num_eq());
}

bool default_converged(const Residuals& r, const IpmSettings& settings) {
  const double scale = std::max(1.0, std::min(std::abs(r.pobj), std::abs(r.dobj)));
  return r.pres <= settings.feasibility_tolerance && r.dres <= settings.feasibility_tolerance &&
         r.gap <= settings.gap_tolerance * scale;
}

IpmOutcome run_ipm(const ConeProgram& p, IpmState& st, const IpmSettings& settings, const IpmMonitor& monitor) {
  const auto t0 = std::chrono::steady_clock::now();
  auto elapsed = [t0] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  IpmOutcome out;
  auto clock = [] { return std::chrono::steady_clock::now(); };
  auto since = [](std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  };
  struct Finish {  // fills total_s and prints the breakdown on every return
    IpmOutcome& out;
    const IpmSettings& settings;
    std::function<double()> elapsed;
    ~Finish() {
      out.total_s = elapsed();
      if (settings.verbose)
        std::fprintf(stderr, "ipm: %d iterations, %.3fs (analyze %.3f, factor %.3f, solve %.3f, monitor %.3f)\n",
                     out.iterations, out.total_s, out.analyze_s, out.factor_s, out.solve_s, out.monitor_s);
    }
  } finish{out, settings, elapsed};
  auto tp = clock();
  NormalEquations kkt(p, settings);
  out.analyze_s = since(tp);
  const ResidualScales scales = residual_scales(p);
  const double nu = p.num_cones();
  Residuals res;
  compute_residuals(p, scales, st, res);
  IpmIteration info;
  fill_info(res, nu, info);
  info.time_s = elapsed();
  tp = clock();
  const bool done = monitor(st, res, info);
  out.monitor_s += since(tp);
  if (done) {
    out.status = IpmStatus::Converged;
    return out;
  }
  Scaling sc;
  Eigen::VectorXd ll, corr, rc, qa, qc, s_new, z_new;
  int small_steps = 0, bad_directions = 0;
  for (int it = 1; it <= settings.max_iterations; ++it) {
    out.iterations = it;
    if (!compute_scaling(p, st.s, st.z, sc)) {
      out.status = IpmStatus::NumericalError;
      out.message = "an iterate left the cones (round-off)";
      return out;
    }
    const double mu = sc.lambda.squaredNorm() / nu;
    tp = clock();
    const bool factored = kkt.factor(sc);
    out.factor_s += since(tp);
    if (!factored) {
      out.status = IpmStatus::NumericalError;
      out.message = "the normal equations could not be factorised (not positive definite)";
      return out;
    }
    auto direction = [&](const Eigen::VectorXd& q, Direction& d) {
      const auto ts = clock();
      kkt.solve_newton(q, res.rs, res.rdx, res.rdk, res.req, d);
      out.solve_s += since(ts);
    };
    // Predictor (affine scaling direction).
    Direction aff;
    qa = -sc.lambda;
    direction(qa, aff);
    const double amax = std::min(cone_max_step(p, sc.lambda, aff.dst), cone_max_step(p, sc.lambda, aff.dzt));
    const double alpha_a = std::min(1.0, amax);
    const double ratio = 1.0 - alpha_a + alpha_a * alpha_a * aff.dst.dot(aff.dzt) / sc.lambda.squaredNorm();
    const double sigma = std::pow(std::clamp(ratio, 0.0, 1.0), 3);
    // Corrector: second-order term and centring.
    cone_product(p, sc.lambda, sc.lambda, ll);
    cone_product(p, aff.dst, aff.dzt, corr);
    rc = -ll - corr + cone_identity(p, sigma * mu);
    cone_arrow_solve(p, sc.lambda, rc, qc);
    Direction dir;
    direction(qc, dir);
    const double cmax = std::min(cone_max_step(p, sc.lambda, dir.dst), cone_max_step(p, sc.lambda, dir.dzt));
    double alpha = std::min(1.0, settings.step_fraction * cmax);
    if (!std::isfinite(alpha) || !dir.dx.allFinite() || !std::isfinite(dir.dk)) {
      out.status = IpmStatus::NumericalError;
      out.message = "the Newton direction is not finite";
      return out;
    }
    // Round-off may put a coordinate of a nearly-active cone just outside: back off.
    for (int tries = 0; tries < 30; ++tries) {
      s_new = st.s + alpha * dir.ds;
      z_new = st.z + alpha * dir.dz;
      if (cone_min_margin(p, s_new) > 0 && cone_min_margin(p, z_new) > 0) break;
      alpha *= 0.5;
    }
    st.x += alpha * dir.dx;
    st.k += alpha * dir.dk;
    st.s.swap(s_new);
    st.z.swap(z_new);
    if (st.y.size()) st.y += alpha * dir.dy;
    compute_residuals(p, scales, st, res);
    info = IpmIteration{};
    info.iteration = it;
    fill_info(res, nu, info);
    info.step = alpha;
    info.sigma = sigma;
    info.refinement = dir.refinement;
    info.kkt_residual = dir.residual;
    info.time_s = elapsed();
    if (settings.verbose)
      std::fprintf(stderr,
                   "ipm %3d pobj %+.12e dobj %+.12e gap %.2e pres %.2e dres %.2e mu %.2e step %.3f sigma %.2e "
                   "ref %d kkt %.1e t %.3fs\n",
                   it, info.pobj, info.dobj, info.gap, info.pres, info.dres, info.mu, info.step, info.sigma,
                   info.refinement, info.kkt_residual, info.time_s);
    tp = clock();
    const bool stop = monitor(st, res, info);
    out.monitor_s += since(tp);
    if (stop) {
      out.status = IpmStatus::Converged;
      return out;
    }
    bad_directions = dir.residual > settings.max_newton_residual ? bad_directions + 1 : 0;
    if (bad_directions >= settings.max_bad_directions) {
      out.status = IpmStatus::NumericalError;
      out.message = "the Newton systems became too ill-conditioned (relative residual " +
                    std::to_string(dir.residual) + ")";
      return out;
    }
    small_steps = alpha < settings.min_step ? small_steps + 1 : 0;
    if (small_steps >= settings.max_small_steps) {
      out.status = IpmStatus::NumericalError;
      out.message = "the method stalled (steps below " + std::to_string(settings.min_step) + ")";
      return out;
    }
  }
  out.status = IpmStatus::MaxIterations;
  out.message = "no convergence within " + std::to_string(settings.max_iterations) + " iterations";
  return out;
}

}  // namespace strictmin::socp
