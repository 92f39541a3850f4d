#include "solvers/qc/qc_program.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "strictmin/io/input_error.h"

namespace strictmin::qc {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Appends a cone's two tail rows, the map's 2-vector a_T (tail_a) or b_T: s = o - L M y, with
// x = L y (ConformalParts::map_scale).
void add_tail(const ConformalParts& parts, int i, bool tail_a, int row, std::vector<Eigen::Triplet<double>>& t,
              std::vector<double>& h) {
  const auto& M = tail_a ? parts.A : parts.B;
  const auto& o = tail_a ? parts.a0 : parts.b0;
  for (int j = 0; j < 2; ++j) {
    add_row(M, 2 * i + j, -parts.map_scale, row + 1 + j, t);
    h.push_back(o[2 * i + j]);
  }
}

}  // namespace

void add_row(const Eigen::SparseMatrix<double, Eigen::RowMajor>& M, int r, double c, int out_row,
             std::vector<Eigen::Triplet<double>>& t) {
  for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(M, r); it; ++it)
    t.emplace_back(out_row, static_cast<int>(it.col()), c * it.value());
}

ConformalParts conformal_parts(const Problem& p) {
  // 1. Only 2D triangle maps: a and b are the 2D conformal / anticonformal parts.
  if (p.image_dim != 2 || p.domain_dim != 2)
    throw InputError("the qc and iso measures are defined for 2D maps of triangles (planar deformation, disk "
                     "parametrization); this problem maps " +
                     std::to_string(p.domain_dim) + "D elements to " + std::to_string(p.image_dim) + "D");
  if (p.has_equalities())
    throw InputError("the qc and iso measures do not support linear equality constraints (seams)");
  // 2. vec(J_T) = G x + j0 (problem.h: h = vec(R) - G_fixed q_fixed).
  const Problem::Reduced red = p.reduced();
  Eigen::VectorXd j0(red.h.size());
  for (int e = 0; e < p.num_elements(); ++e)
    for (int r = 0; r < 2; ++r)
      for (int c = 0; c < 2; ++c) j0[4 * e + 2 * r + c] = p.targets(2 * e + r, c) - red.h[4 * e + 2 * r + c];
  const Eigen::SparseMatrix<double, Eigen::RowMajor> G = red.G;
  // 3. Active elements: those with a free vertex (the others are constants of the problem).
  ConformalParts out;
  out.num_x = static_cast<int>(G.cols());
  for (int e = 0; e < p.num_elements(); ++e)
    if (G.row(4 * e).nonZeros() + G.row(4 * e + 1).nonZeros() + G.row(4 * e + 2).nonZeros() +
            G.row(4 * e + 3).nonZeros() > 0)
      out.element.push_back(e);
  // 4. a = ((J00 + J11)/2, (J10 - J01)/2), b = ((J00 - J11)/2, (J10 + J01)/2).
  const int E = out.count();
  std::vector<Eigen::Triplet<double>> ta, tb;
  out.a0.resize(2 * E);
  out.b0.resize(2 * E);
  for (int i = 0; i < E; ++i) {
    const int e = out.element[i], r = 4 * e;
    add_row(G, r + 0, 0.5, 2 * i, ta), add_row(G, r + 3, 0.5, 2 * i, ta);
    add_row(G, r + 2, 0.5, 2 * i + 1, ta), add_row(G, r + 1, -0.5, 2 * i + 1, ta);
    add_row(G, r + 0, 0.5, 2 * i, tb), add_row(G, r + 3, -0.5, 2 * i, tb);
    add_row(G, r + 2, 0.5, 2 * i + 1, tb), add_row(G, r + 1, 0.5, 2 * i + 1, tb);
    out.a0[2 * i] = 0.5 * (j0[r] + j0[r + 3]);
    out.a0[2 * i + 1] = 0.5 * (j0[r + 2] - j0[r + 1]);
    out.b0[2 * i] = 0.5 * (j0[r] - j0[r + 3]);
    out.b0[2 * i + 1] = 0.5 * (j0[r + 2] + j0[r + 1]);
  }
  out.A.resize(2 * E, out.num_x);
  out.B.resize(2 * E, out.num_x);
  out.A.setFromTriplets(ta.begin(), ta.end());
  out.B.setFromTriplets(tb.begin(), tb.end());
  // 5. The programs' length unit.
  double sum = 0;
  for (int k = 0; k < out.A.nonZeros(); ++k) sum += out.A.valuePtr()[k] * out.A.valuePtr()[k];
  out.map_scale = sum > 0 ? 1.0 / std::sqrt(sum / static_cast<double>(out.A.nonZeros())) : 1.0;
  return out;
}

void evaluate_ab(const ConformalParts& parts, const Eigen::VectorXd& x, Eigen::VectorXd& a, Eigen::VectorXd& b) {
  a = parts.A * x + parts.a0;
  b = parts.B * x + parts.b0;
}

Eigen::VectorXd frames_of(const ConformalParts& parts, const Eigen::VectorXd& x) {
  Eigen::VectorXd a, b;
  evaluate_ab(parts, x, a, b);
  Eigen::VectorXd r(a.size());
  for (int i = 0; i < parts.count(); ++i) {
    const double n = std::hypot(a[2 * i], a[2 * i + 1]);
    r[2 * i] = n > 0 ? a[2 * i] / n : 1.0;
    r[2 * i + 1] = n > 0 ? a[2 * i + 1] / n : 0.0;
  }
  return r;
}

double k_of_K(double K) { return std::isfinite(K) ? (K - 1) / (K + 1) : 1.0; }
double K_of_k(double k) { return k < 1 ? (1 + k) / (1 - k) : kInf; }

Eigen::VectorXd frame_values(Measure m, const ConformalParts& parts, const Eigen::VectorXd& frames,
                             const Eigen::VectorXd& x) {
  Eigen::VectorXd a, b, out(parts.count());
  evaluate_ab(parts, x, a, b);
  for (int i = 0; i < parts.count(); ++i) {
    const double ar = a[2 * i] * frames[2 * i] + a[2 * i + 1] * frames[2 * i + 1];
    const double nb = std::hypot(b[2 * i], b[2 * i + 1]);
    if (!(ar > nb)) {
      out[i] = kInf;
      continue;
    }
    if (m == Measure::Quasiconformal)
      out[i] = (ar + nb) / (ar - nb);
    else
      out[i] = std::max(std::hypot(a[2 * i], a[2 * i + 1]) + nb, 1.0 / (ar - nb));
  }
  return out;
}

int slack_index(Measure m, const ConformalParts& parts) {
  return parts.num_x + (m == Measure::Isometric ? parts.count() : 0);
}

Eigen::VectorXd slack_start(Measure m, const ConformalParts& parts, const Eigen::VectorXd& x) {
  Eigen::VectorXd v = Eigen::VectorXd::Zero(slack_index(m, parts) + 1);
  v.head(parts.num_x) = x / parts.map_scale;
  if (m == Measure::Isometric) {
    Eigen::VectorXd a, b;
    evaluate_ab(parts, x, a, b);
    for (int i = 0; i < parts.count(); ++i) v[parts.num_x + i] = std::hypot(a[2 * i], a[2 * i + 1]);
  }
  return v;
}

Eigen::VectorXd slack_scales(Measure m, const ConformalParts& parts, const Eigen::VectorXd& x) {
  Eigen::VectorXd rho = Eigen::VectorXd::Ones(parts.count());
  if (m != Measure::Quasiconformal) return rho;
  Eigen::VectorXd a, b;
  evaluate_ab(parts, x, a, b);
  double largest = 0;
  for (int i = 0; i < parts.count(); ++i) largest = std::max(largest, std::hypot(a[2 * i], a[2 * i + 1]));
  for (int i = 0; i < parts.count(); ++i)
    rho[i] = largest > 0 ? std::max(std::hypot(a[2 * i], a[2 * i + 1]), 1e-6 * largest) : 1.0;
  return rho;
}

SparseSocp slack_program(Measure m, const ConformalParts& parts, const Eigen::VectorXd& frames,
                         const Eigen::VectorXd& level, double tau_cap, const Eigen::VectorXd& slack_scale) {
  const int E = parts.count(), tau = slack_index(m, parts);
  const bool iso = m == Measure::Isometric;
  const double L = parts.map_scale;  // x = L y
  SparseSocp p;
  std::vector<Eigen::Triplet<double>> t;
  std::vector<double> h;
  int row = 0;
  // The cone (head + tau, tail) with head = sum_j head_coef_j a_j + head_const and tail = b or
  // a, written as G v + s = h: s = h - G v.
  auto cone = [&](int i, double ka, double head_const, int u_sign, bool tail_a) {
    const double r0 = frames[2 * i], r1 = frames[2 * i + 1];
    if (ka != 0) {
      add_row(parts.A, 2 * i, -L * ka * r0, row, t);
      add_row(parts.A, 2 * i + 1, -L * ka * r1, row, t);
    }
    if (u_sign != 0) t.emplace_back(row, parts.num_x + i, -u_sign);
    t.emplace_back(row, tau, slack_scale.size() ? -slack_scale[i] : -1.0);
    h.push_back(ka * (r0 * parts.a0[2 * i] + r1 * parts.a0[2 * i + 1]) + head_const);
    add_tail(parts, i, tail_a, row, t, h);
    p.dims.push_back(3);
    row += 3;
  };
  for (int i = 0; i < E; ++i) {
    if (!iso) {
      cone(i, k_of_K(level[i]), 0.0, 0, false);  // |b| <= k <a, r> + tau
    } else {
      cone(i, 0.0, 0.0, +1, true);               // |a| <= u + tau
      cone(i, 0.0, level[i], -1, false);         // |b| <= S - u + tau
      cone(i, 1.0, -1.0 / level[i], 0, false);   // |b| <= <a, r> - 1/S + tau
    }
  }
  // tau >= -tau_cap (keeps the slack bounded where the map's scale is free).
  t.emplace_back(row, tau, -1.0);
  h.push_back(tau_cap);
  p.dims.push_back(1);
  ++row;
  p.G.resize(row, tau + 1);
  p.G.setFromTriplets(t.begin(), t.end());
  p.h = Eigen::Map<Eigen::VectorXd>(h.data(), static_cast<Eigen::Index>(h.size()));
  p.c = Eigen::VectorXd::Zero(tau + 1);
  p.c[tau] = 1.0;
  return p;
}

IsoProgram iso_program(const ConformalParts& parts, const Eigen::VectorXd& frames, const Eigen::VectorXd& bounds) {
  // 1. Variables: x, u per active element, v per free one, S.
  const int E = parts.count(), nx = parts.num_x;
  IsoProgram out;
  out.v_index.assign(E, -1);
  int next = nx + E;
  for (int i = 0; i < E; ++i)
    if (!(bounds.size() && bounds[i] >= 0)) out.v_index[i] = next++;
  out.s_index = next;
  const int S = out.s_index;
  const double L = parts.map_scale;  // x = L y
  // 2. The cones, as G v + s = h (s = h - G v): head rows first, then the tails.
  SparseSocp& p = out.program;
  std::vector<Eigen::Triplet<double>> t;
  std::vector<double> h;
  int row = 0;
  std::vector<double> per_s, constant;  // per cone: its head's bound (IsoProgram::head_bounds)
  auto tail = [&](int i, bool tail_a) {
    add_tail(parts, i, tail_a, row, t, h);
    p.dims.push_back(3);
    row += 3;
  };
  for (int i = 0; i < E; ++i) {
    const int u = nx + i, v = out.v_index[i];
    const bool bounded = v < 0;
    const double r0 = frames[2 * i], r1 = frames[2 * i + 1];
    for (int k = 0; k < 3; ++k) per_s.push_back(bounded ? 0.0 : 1.0), constant.push_back(bounded ? bounds[i] : 0.0);
    if (!bounded) per_s.push_back(2.0), constant.push_back(0.0);
    // |a| <= u
    t.emplace_back(row, u, -1.0);
    h.push_back(0.0);
    tail(i, true);
    // |b| <= S - u (bounded: S_i - u)
    t.emplace_back(row, u, 1.0);
    if (bounded) {
      h.push_back(bounds[i]);
    } else {
      t.emplace_back(row, S, -1.0);
      h.push_back(0.0);
    }
    tail(i, false);
    // |b| <= <a, r> - v (bounded: <a, r> - 1/S_i)
    add_row(parts.A, 2 * i, -L * r0, row, t);
    add_row(parts.A, 2 * i + 1, -L * r1, row, t);
    if (!bounded) t.emplace_back(row, v, 1.0);
    h.push_back(r0 * parts.a0[2 * i] + r1 * parts.a0[2 * i + 1] - (bounded ? 1.0 / bounds[i] : 0.0));
    tail(i, false);
    // v S >= 1: (v + S, v - S, 2) in the 3-cone
    if (!bounded) {
      t.emplace_back(row, v, -1.0), t.emplace_back(row, S, -1.0);
      t.emplace_back(row + 1, v, -1.0), t.emplace_back(row + 1, S, 1.0);
      h.push_back(0.0), h.push_back(0.0), h.push_back(2.0);
      p.dims.push_back(3);
      row += 3;
    }
  }
  // S >= 1.
  per_s.push_back(1.0), constant.push_back(0.0);
  out.head_per_s = Eigen::Map<Eigen::VectorXd>(per_s.data(), static_cast<Eigen::Index>(per_s.size()));
  out.head_const = Eigen::Map<Eigen::VectorXd>(constant.data(), static_cast<Eigen::Index>(constant.size()));
  t.emplace_back(row, S, -1.0);
  h.push_back(-1.0);
  p.dims.push_back(1);
  ++row;
  p.G.resize(row, S + 1);
  p.G.setFromTriplets(t.begin(), t.end());
  p.h = Eigen::Map<Eigen::VectorXd>(h.data(), static_cast<Eigen::Index>(h.size()));
  p.c = Eigen::VectorXd::Zero(S + 1);
  p.c[S] = 1.0;
  return out;
}

Eigen::VectorXd iso_start(const IsoProgram& program, const ConformalParts& parts, const Eigen::VectorXd& frames,
                          const Eigen::VectorXd& x, double s0) {
  Eigen::VectorXd a, b;
  evaluate_ab(parts, x, a, b);
  Eigen::VectorXd v = Eigen::VectorXd::Zero(program.s_index + 1);
  v.head(parts.num_x) = x / parts.map_scale;
  double largest = 0;
  for (int i = 0; i < parts.count(); ++i) {
    v[parts.num_x + i] = std::hypot(a[2 * i], a[2 * i + 1]);
    const int vi = program.v_index[i];
    if (vi < 0) continue;
    v[vi] = a[2 * i] * frames[2 * i] + a[2 * i + 1] * frames[2 * i + 1] - std::hypot(b[2 * i], b[2 * i + 1]);
    largest = std::max(largest, v[vi]);
  }
  for (int vi : program.v_index)
    if (vi >= 0) v[vi] = std::max(v[vi], 1e-3 * largest);
  v[program.s_index] = std::max(s0, 1.0);
  return v;
}

}  // namespace strictmin::qc
