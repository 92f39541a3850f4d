#pragma once
// Algebra of one second-order cone Q^d = {u = (u0, u1) : u0 >= ||u1||} (d = 1 + dim u1),
// on raw pointers so that a flat vector holds many cones. J = diag(1, -1, ..., -1).
//
// Nesterov-Todd scaling in closed form (Vandenberghe, "The CVXOPT linear and quadratic
// cone program solvers", section on second-order cones): for s, z in int Q,
//   sbar = s / sqrt(s^T J s), zbar = z / sqrt(z^T J z), gamma = sqrt((1 + sbar^T zbar) / 2),
//   wbar = (sbar + J zbar) / (2 gamma),  w = (wbar + e) / sqrt(2 (wbar0 + 1))  (w^T J w = 1),
//   beta = (s^T J s / z^T J z)^(1/4),
//   W = beta (2 w w^T - J),  W^{-1} = (1/beta) (2 (Jw)(Jw)^T - J),  W^2 = beta^2 (2 wbar wbar^T - J),
// and W z = W^{-1} s = lambda, the scaled point. W^{-2} = (1/beta^2)(2 v v^T - J) with
// v = (2 w0^2 - 1, -2 w0 w1) = J wbar. Everything here costs O(d).
#include <cmath>
#include <limits>

namespace strictmin::socp {

inline double tail_norm(const double* u, int d) {
  double t = 0;
  for (int i = 1; i < d; ++i) t += u[i] * u[i];
  return std::sqrt(t);
}

// u^T J u, computed as (u0 - |u1|)(u0 + |u1|) to keep accuracy near the boundary.
inline double soc_det(const double* u, int d) {
  const double t = tail_norm(u, d);
  return (u[0] - t) * (u[0] + t);
}

inline bool soc_interior(const double* u, int d) {
  return std::isfinite(u[0]) && u[0] > tail_norm(u, d);
}

inline double dot(const double* a, const double* b, int d) {
  double t = 0;
  for (int i = 0; i < d; ++i) t += a[i] * b[i];
  return t;
}

// NT scaling of (s, z): returns false if either is not strictly inside the cone.
inline bool nt_scaling(const double* s, const double* z, int d, double& beta, double* w) {
  const double ds2 = soc_det(s, d), dz2 = soc_det(z, d);
  if (!(ds2 > 0) || !(dz2 > 0) || !(s[0] > 0) || !(z[0] > 0)) return false;
  const double ds = std::sqrt(ds2), dz = std::sqrt(dz2);
  double sz = s[0] * z[0];
  for (int i = 1; i < d; ++i) sz += s[i] * z[i];
  const double gamma = std::sqrt(0.5 * (1.0 + sz / (ds * dz)));
  // wbar = (sbar + J zbar) / (2 gamma) is the scaling point of W^2 = beta^2 (2 wbar wbar^T - J);
  // W itself is beta (2 v v^T - J) with v = (wbar + e) / sqrt(2 (wbar0 + 1)).
  const double a = 1.0 / (2.0 * gamma * ds), b = 1.0 / (2.0 * gamma * dz);
  const double wbar0 = a * s[0] + b * z[0];
  const double f = 1.0 / std::sqrt(2.0 * (wbar0 + 1.0));
  w[0] = (wbar0 + 1.0) * f;
  for (int i = 1; i < d; ++i) w[i] = (a * s[i] - b * z[i]) * f;
  beta = std::sqrt(ds / dz);
  return std::isfinite(beta) && std::isfinite(w[0]);
}

// out = W u (out may not alias u).
inline void apply_w(double beta, const double* w, int d, const double* u, double* out) {
  const double t = 2.0 * dot(w, u, d);
  out[0] = beta * (t * w[0] - u[0]);
  for (int i = 1; i < d; ++i) out[i] = beta * (t * w[i] + u[i]);
}

// out = W^{-1} u, with Jw = (w0, -w1).
inline void apply_winv(double beta, const double* w, int d, const double* u, double* out) {
  double t = w[0] * u[0];
  for (int i = 1; i < d; ++i) t -= w[i] * u[i];
  t *= 2.0;
  const double ib = 1.0 / beta;
  out[0] = ib * (t * w[0] - u[0]);
  for (int i = 1; i < d; ++i) out[i] = ib * (-t * w[i] + u[i]);
}

// v of W^{-2} = (1/beta^2)(2 v v^T - J).
inline void winv2_vector(const double* w, int d, double* v) {
  v[0] = 2.0 * w[0] * w[0] - 1.0;
  for (int i = 1; i < d; ++i) v[i] = -2.0 * w[0] * w[i];
}

// out = W^{-2} u.
inline void apply_winv2(double beta, const double* w, int d, const double* u, double* out) {
  const double v0 = 2.0 * w[0] * w[0] - 1.0;
  double t = v0 * u[0];
  for (int i = 1; i < d; ++i) t -= 2.0 * w[0] * w[i] * u[i];
  t *= 2.0;
  const double ib2 = 1.0 / (beta * beta);
  out[0] = ib2 * (t * v0 - u[0]);
  for (int i = 1; i < d; ++i) out[i] = ib2 * (-t * 2.0 * w[0] * w[i] + u[i]);
}

// Jordan product a o b = (a^T b, a0 b1 + b0 a1).
inline void jordan_product(const double* a, const double* b, int d, double* out) {
  out[0] = dot(a, b, d);
  for (int i = 1; i < d; ++i) out[i] = a[0] * b[i] + b[0] * a[i];
}

// Solves l o out = r for out (l strictly inside the cone).
inline void arrow_solve(const double* l, const double* r, int d, double* out) {
  double l1r1 = 0;
  for (int i = 1; i < d; ++i) l1r1 += l[i] * r[i];
  const double q0 = (l[0] * r[0] - l1r1) / soc_det(l, d);
  out[0] = q0;
  for (int i = 1; i < d; ++i) out[i] = (r[i] - q0 * l[i]) / l[0];
}

// Largest alpha >= 0 with l + alpha u in the cone (l strictly inside); +inf if unbounded.
inline double max_step(const double* l, const double* u, int d) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  if (d == 1) return u[0] < 0 ? -l[0] / u[0] : inf;
  double a = u[0] * u[0], b = l[0] * u[0];
  for (int i = 1; i < d; ++i) {
    a -= u[i] * u[i];
    b -= l[i] * u[i];
  }
  const double c = soc_det(l, d);
  const double disc = b * b - a * c;
  if (a > 0 && (b >= 0 || disc < 0)) return inf;
  if (a == 0 && b >= 0) return inf;
  const double den = -b + std::sqrt(disc > 0 ? disc : 0.0);
  return den > 0 ? c / den : 0.0;
}

}  // namespace strictmin::socp
