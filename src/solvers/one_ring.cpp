// Exact 1-ring L-infinity solver: min_q max_T f_T(q), f_T(q) = a_T ||q - c_T||^2 + b_T
// (paper Section 5.3, Proposition 3; docs/maths.md).
//
// The problem is LP-type with combinatorial dimension d+1. We use the basic pivoting
// scheme for LP-type problems: keep a support set B (<= d+1 terms) and its minimizer q_B;
// while some term h is above max_B f(q_B), replace B by the support set of B + {h}, which
// must contain h and is found by trying the subsets of B + {h} that contain h. Each pivot
// raises the value of B, so the loop ends (a pivot cap guards against rounding cycles).
//
// The minimizer of a support set S is its KKT point (see support_points): all terms of S
// equal at q and q = sum l_T a_T c_T / sum l_T a_T with l >= 0, i.e. q lies in the convex
// hull of the centres of S. A candidate is accepted for B + {h} when its point passes the
// KKT check there: barycentric coordinates >= -kBaryTol, every term of S within kValueTol
// (relative) of the maximum over B + {h}. If rounding rejects every candidate, the one with
// the lowest maximum over B + {h} is taken, so the result is always the best point seen.
#include "strictmin/solvers/one_ring.h"

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>

#include "small_lu.h"
#include "socp/vector_clones.h"

namespace strictmin {
namespace {

template <int d>
using Vec = Eigen::Matrix<double, d, 1>;
template <int d>
using Mat = Eigen::Matrix<double, d, d>;

constexpr double kBaryTol = 1e-10;   // barycentric coordinates of a KKT point may be this negative
constexpr double kValueTol = 1e-13;  // relative: terms within this of the maximum count as equal
constexpr double kRefineTol = 1e-6;  // relative: candidates this close to equal get Newton steps
constexpr double kPolishedTol = 1e-15;  // relative: ... until their terms agree to this

// The helpers below are always inlined into the pivoting, and so into its AVX2 clones
// (solve_clones at the end).

template <int d>
inline double term_value(const RingTerm<d>& t, const Vec<d>& q) {
  return t.a * (q - t.centre).squaredNorm() + t.b;
}

template <int d>
struct Candidate {
  Vec<d> q;
  double mu[d];  // q = c_{S[0]} + sum_i mu_i (c_{S[i+1]} - c_{S[0]}): barycentric coordinates
};

// Points where the k terms S (1 <= k <= d+1) are equal and that lie in the convex hull of
// their centres: candidates for the minimizer of max_{T in S} f_T. Reorders S so that S[0]
// is the reference term (smallest a) and writes up to 2 candidates.
//
// With r = S[0] and x = q - c_r, for another term i with e_i = c_i - c_r, f_i(q) = f_r(q)
// reads
//   2 e_i . x = alpha_i s + beta_i,  s = ||x||^2,  alpha_i = 1 - a_r / a_i (in [0, 1)),
//   beta_i = ||e_i||^2 + (b_i - b_r) / a_i,
// which is linear in x for a given s (the spheres of docs/maths.md become planes after lifting
// s). Solved for a given s, x = x_u + s x_w within span{e_i}, and s = ||x||^2 becomes a
// scalar quadratic; its roots whose barycentric coordinates are >= 0 are the candidates.
template <int d>
[[gnu::always_inline]] inline int support_points(const RingTerm<d>* terms, int* S, int k, Candidate<d>* out) {
  if (k == 1) {
    out[0].q = terms[S[0]].centre;
    return 1;
  }
  for (int i = 1; i < k; ++i)
    if (terms[S[i]].a < terms[S[0]].a) std::swap(S[0], S[i]);
  const RingTerm<d>& ref = terms[S[0]];

  if (k == 2) {
    // On the segment q = c_r + mu e = c_o - nu e (nu = 1 - mu), with L = a_o ||e||^2,
    // f_o - f_r decreases from beta = L + b_o - b_r (at c_r) to -gamma (at c_o),
    // gamma = a_r ||e||^2 + b_r - b_o; its root is
    //   mu = beta / (L + sqrt(L^2 - (a_o - a_r) ||e||^2 beta))
    //   nu = gamma / (a_r ||e||^2 + sqrt((a_r ||e||^2)^2 + (a_o - a_r) ||e||^2 gamma)),
    // each free of cancellation; q is placed from the nearer centre (a sliver's large a_o
    // puts q close to c_o, where mu would lose digits).
    const RingTerm<d>& o = terms[S[1]];
    const Vec<d> e = o.centre - ref.centre;
    const double len2 = e.squaredNorm();
    if (!(len2 > 0)) return 0;  // same centre: one of the two alone is the support set
    const double L = o.a * len2, Lr = ref.a * len2, spread = (o.a - ref.a) * len2;
    const double beta = L + o.b - ref.b, gamma = Lr + ref.b - o.b;
    if (!(beta >= -kBaryTol * L && gamma >= -kBaryTol * L)) return 0;
    const double mu = std::max(0.0, beta) / (L + std::sqrt(std::max(0.0, L * L - spread * beta)));
    if (mu <= 0.5) {
      out[0].q = ref.centre + mu * e;
      out[0].mu[0] = mu;
    } else {
      const double nu = std::max(0.0, gamma) / (Lr + std::sqrt(Lr * Lr + spread * std::max(0.0, gamma)));
      out[0].q = o.centre - nu * e;
      out[0].mu[0] = 1.0 - nu;
    }
    return 1;
  }

  const int m = k - 1;
  Vec<d> e[d];
  double alpha[d], beta[d];
  for (int i = 0; i < m; ++i) {
    const RingTerm<d>& t = terms[S[i + 1]];
    e[i] = t.centre - ref.centre;
    alpha[i] = 1.0 - ref.a / t.a;
    beta[i] = e[i].squaredNorm() + (t.b - ref.b) / t.a;
  }
  // x = xu + s xw solves the linear equations for a given s; to_mu maps x to mu.
  Vec<d> xu = Vec<d>::Zero(), xw = Vec<d>::Zero();
  Mat<d> to_mu = Mat<d>::Zero();
  if (m == d) {
    // Square: E^T x = (alpha s + beta) / 2 with E = [e_1 .. e_d], mu = E^{-1} x.
    Mat<d> E;
    double scale = 1;
    for (int i = 0; i < d; ++i) {
      E.col(i) = e[i];
      scale *= e[i].norm();
    }
    // Affinely dependent centres: a smaller support set gives the same point.
    if (!(std::abs(E.determinant()) > 1e-14 * scale)) return 0;
    to_mu = E.inverse();
    for (int i = 0; i < d; ++i) {
      xu += (0.5 * beta[i]) * to_mu.row(i).transpose();
      xw += (0.5 * alpha[i]) * to_mu.row(i).transpose();
    }
  } else {
    // Fewer centres than d+1 (3D, three terms): Gram-Schmidt E = Q R, x = Q y with
    // R^T y = (alpha s + beta) / 2, mu = R^{-1} Q^T x.
    std::array<Vec<d>, d> Q;
    double R[d][d] = {};
    for (int i = 0; i < m; ++i) {
      Vec<d> v = e[i];
      for (int j = 0; j < i; ++j) {
        R[j][i] = Q[j].dot(v);
        v -= R[j][i] * Q[j];
      }
      const double nv = v.norm();
      if (!(nv > 1e-14 * e[i].norm())) return 0;
      R[i][i] = nv;
      Q[i] = v / nv;
    }
    double yu[d], yw[d];
    for (int i = 0; i < m; ++i) {  // forward substitution with R^T
      double u = 0.5 * beta[i], w = 0.5 * alpha[i];
      for (int j = 0; j < i; ++j) {
        u -= R[j][i] * yu[j];
        w -= R[j][i] * yw[j];
      }
      yu[i] = u / R[i][i];
      yw[i] = w / R[i][i];
      xu += yu[i] * Q[i];
      xw += yw[i] * Q[i];
    }
    for (int i = m - 1; i >= 0; --i) {  // rows of R^{-1} Q^T, by back substitution
      Vec<d> row = Q[i];
      for (int j = i + 1; j < m; ++j) row -= R[i][j] * to_mu.row(j).transpose();
      to_mu.row(i) = row.transpose() / R[i][i];
    }
  }
  const double A = xw.squaredNorm(), B = 2 * xu.dot(xw) - 1, C = xu.squaredNorm();  // A s^2 + B s + C = 0
  double roots[2];
  int nroots = 0;
  if (A == 0) {  // equal a: the equal-value sets are planes
    if (B < 0) roots[nroots++] = C / -B;
  } else {
    double disc = B * B - 4 * A * C;
    if (disc < 0) {
      if (disc < -1e-10 * B * B) return 0;  // the spheres do not meet
      disc = 0;                             // tangent, up to rounding
    }
    const double h = -0.5 * (B + std::copysign(std::sqrt(disc), B));  // no cancellation
    if (h != 0) {
      roots[nroots++] = C / h;
      roots[nroots++] = h / A;
    } else {
      roots[nroots++] = 0;
    }
  }
  int count = 0;
  for (int n = 0; n < nroots; ++n) {
    const double s = roots[n];
    if (!(s >= 0)) continue;
    Candidate<d>& c = out[count];
    const Vec<d> x = xu + s * xw;
    double sum = 0;
    bool inside = true;
    for (int i = 0; i < m; ++i) {
      c.mu[i] = to_mu.row(i).dot(x);
      sum += c.mu[i];
      inside = inside && c.mu[i] >= -kBaryTol;
    }
    if (!inside || !(1.0 - sum >= -kBaryTol)) continue;
    c.q = ref.centre + x;
    ++count;
  }
  return count;
}

// One Newton step on f_{S[i]}(q) - f_{S[0]}(q) = 0 (i >= 1) over q = c_{S[0]} + E mu: the
// closed forms lose digits when the spheres are nearly tangent or a's differ by orders of
// magnitude; the residuals, evaluated term by term, do not. Returns false if singular.
template <int d>
[[gnu::always_inline]] inline bool refine(const RingTerm<d>* terms, const int* S, int k, Candidate<d>& c) {
  const int m = k - 1;
  if (m == 0) return true;
  const RingTerm<d>& t0 = terms[S[0]];
  const Vec<d> g0 = t0.a * (c.q - t0.centre);
  const double f0 = term_value(t0, c.q);
  double J[d][d], step[d];
  std::array<Vec<d>, d> E;
  for (int i = 0; i < m; ++i) E[i] = terms[S[i + 1]].centre - t0.centre;
  for (int i = 0; i < m; ++i) {
    const RingTerm<d>& t = terms[S[i + 1]];
    step[i] = term_value(t, c.q) - f0;
    const Vec<d> g = 2 * (t.a * (c.q - t.centre) - g0);  // gradient of the residual in q
    for (int j = 0; j < m; ++j) J[i][j] = g.dot(E[j]);
  }
  small_lu_solve<d>(J, step, m);
  for (int j = 0; j < m; ++j)
    if (!std::isfinite(step[j])) return false;
  for (int j = 0; j < m; ++j) {
    c.q -= step[j] * E[j];
    c.mu[j] -= step[j];
  }
  return true;
}

template <int d>
[[gnu::always_inline]] inline bool inside_hull(const Candidate<d>& c, int k) {
  double sum = 0;
  for (int i = 0; i < k - 1; ++i) {
    if (!(c.mu[i] >= -kBaryTol)) return false;
    sum += c.mu[i];
  }
  return 1.0 - sum >= -kBaryTol;
}

// Subsets of an n-element support set (bit masks) with at most d elements, largest first:
// the order in which the candidates for B + {h} are tried.
template <int d>
struct SubsetOrder {
  std::array<std::array<unsigned char, 16>, d + 2> masks{};
  std::array<int, d + 2> count{};
  constexpr SubsetOrder() {
    for (int n = 0; n <= d + 1; ++n)
      for (int size = std::min(n, d); size >= 0; --size)
        for (unsigned mask = 0; mask < (1u << n); ++mask)
          if (std::popcount(mask) == size) masks[n][count[n]++] = static_cast<unsigned char>(mask);
  }
};

// The term with the largest value at q (and that value). Short rings (planar ones: 6
// triangles on average) in one scan; longer ones values first, then a max with independent
// lanes, then the index: no loop-carried compare-and-select chain.
constexpr int kShortRing = 12;
template <int d>
[[gnu::always_inline]] inline int most_violated(const RingTerm<d>* terms, int n, const Vec<d>& q, double& top) {
  if (n <= kShortRing) {  // the same index and value as the chunks below: the first largest, NaN skipped
    int best = 0;
    top = -1;
    for (int i = 0; i < n; ++i)
      if (const double v = term_value(terms[i], q); v > top) {
        top = v;
        best = i;
      }
    return best;
  }
  constexpr int kChunk = 32;
  double values[kChunk];
  int best = 0;
  top = -1;
  for (int begin = 0; begin < n; begin += kChunk) {
    const int m = std::min(kChunk, n - begin);
    for (int i = 0; i < m; ++i) values[i] = term_value(terms[begin + i], q);
    double lane[4] = {-1, -1, -1, -1};
    int i = 0;
    for (; i + 4 <= m; i += 4)
      for (int l = 0; l < 4; ++l) lane[l] = std::max(lane[l], values[i + l]);
    for (; i < m; ++i) lane[0] = std::max(lane[0], values[i]);
    const double chunk_top = std::max(std::max(lane[0], lane[1]), std::max(lane[2], lane[3]));
    if (chunk_top > top) {
      top = chunk_top;
      for (int j = 0; j < m; ++j)
        if (values[j] == chunk_top) {
          best = begin + j;
          break;
        }
    }
  }
  return best;
}

// Checks a candidate point of the support set S (k terms): Newton-polishes it when the
// terms of S are nearly but not quite equal, then returns max over S and min over S.
template <int d>
[[gnu::always_inline]] inline void judge(const RingTerm<d>* terms, const int* S, int k, Candidate<d>& cand,
                                         double& hs, double& ls) {
  for (int attempt = 0;; ++attempt) {
    hs = 0, ls = std::numeric_limits<double>::infinity();
    for (int i = 0; i < k; ++i) {
      const double v = term_value(terms[S[i]], cand.q);
      hs = std::max(hs, v);
      ls = std::min(ls, v);
    }
    if (attempt == 2 || hs - ls <= kPolishedTol * hs || !(hs - ls <= kRefineTol * hs)) return;
    Candidate<d> polished = cand;
    if (!refine<d>(terms, S, k, polished) || !inside_hull(polished, k)) return;
    cand = polished;
  }
}

// The KKT point of the guessed support set, if it is one (a start for the pivoting).
template <int d>
[[gnu::always_inline]] inline bool start_from_guess(const RingTerm<d>* terms, int n, const int* guess,
                                                    int guess_size, int* basis, int& nb, Vec<d>& q, double& level) {
  if (guess_size < 1 || guess_size > d + 1) return false;
  int S[d + 1];
  for (int i = 0; i < guess_size; ++i) {
    if (guess[i] < 0 || guess[i] >= n) return false;
    for (int j = 0; j < i; ++j)
      if (guess[j] == guess[i]) return false;
    S[i] = guess[i];
  }
  Candidate<d> points[2];
  const int np = support_points<d>(terms, S, guess_size, points);
  for (int p = 0; p < np; ++p) {
    double hs, ls;
    judge<d>(terms, S, guess_size, points[p], hs, ls);
    if (hs - ls <= kValueTol * hs) {
      std::copy(S, S + guess_size, basis);
      nb = guess_size;
      q = points[p].q;
      level = hs;
      return true;
    }
  }
  return false;
}

// The pivoting (solve_one_ring below).
template <int d>
[[gnu::always_inline]] inline RingSolution<d> solve_ring(const RingTerm<d>* terms, int n, const int* guess,
                                                         int guess_size) {
  static constexpr SubsetOrder<d> kSubsets{};
  RingSolution<d> sol;
  sol.q.setZero();
  if (n <= 0) return sol;

  int basis[d + 1];
  int nb = 1;
  Vec<d> q;
  double level;  // max over the support set (and the last h) at q
  if (!start_from_guess<d>(terms, n, guess, guess_size, basis, nb, q, level)) {
    // Start from the term that is largest at the origin (for the relaxation: the vertex's
    // current position, so the current maximum is likely to stay in the support set).
    double start_value;
    const int start = most_violated<d>(terms, n, Vec<d>::Zero(), start_value);
    basis[0] = start;
    nb = 1;
    q = terms[start].centre;
    level = terms[start].b;
  }

  Vec<d> best_q = q;
  double best_value = std::numeric_limits<double>::infinity();
  int best_basis[d + 1], best_nb = nb;
  std::copy(basis, basis + nb, best_basis);
  const int max_pivots = 4 * n + 16;
  for (int pivot = 0;; ++pivot) {
    double top;
    const int h = most_violated<d>(terms, n, q, top);
    // Done: nothing above the support set's level (its KKT point is optimal), or give up
    // on rounding cycles and return the best point seen.
    if (top <= level * (1 + kValueTol) || top <= best_value) {
      best_value = top, best_q = q, best_nb = nb;
      std::copy(basis, basis + nb, best_basis);
    }
    if (top <= level * (1 + kValueTol) || pivot == max_pivots) break;

    // The support set of basis + {h}: a subset containing h.
    int U[d + 2];
    std::copy(basis, basis + nb, U);
    U[nb] = h;
    const int nu = nb + 1;
    bool accepted = false;
    double fallback_value = std::numeric_limits<double>::infinity();
    Vec<d> fallback_q = q;
    int fallback_set[d + 1] = {h}, fallback_size = 1;
    for (int c = 0; c < kSubsets.count[nb] && !accepted; ++c) {
      const unsigned mask = kSubsets.masks[nb][c];
      int S[d + 1], k = 0;
      for (int i = 0; i < nb; ++i)
        if (mask & (1u << i)) S[k++] = basis[i];
      S[k++] = h;
      Candidate<d> points[2];
      const int np = support_points<d>(terms, S, k, points);
      for (int p = 0; p < np && !accepted; ++p) {
        Candidate<d>& cand = points[p];
        double hs, lo;
        judge<d>(terms, S, k, cand, hs, lo);
        double hi = hs;
        for (int i = 0; i < nu; ++i) hi = std::max(hi, term_value(terms[U[i]], cand.q));
        if (hi - lo <= kValueTol * hi) {  // KKT point of basis + {h}
          std::copy(S, S + k, basis);
          nb = k;
          q = cand.q;
          level = hi;
          accepted = true;
        } else if (hi < fallback_value) {
          fallback_value = hi;
          fallback_q = cand.q;
          std::copy(S, S + k, fallback_set);
          fallback_size = k;
        }
      }
    }
    if (!accepted) {
      std::copy(fallback_set, fallback_set + fallback_size, basis);
      nb = fallback_size;
      q = fallback_q;
      level = fallback_value;
    }
  }
  sol.q = best_q;
  sol.value = best_value;
  sol.active = best_nb;
  std::copy(best_basis, best_basis + best_nb, sol.support.begin());
  return sol;
}

// The solver compiled for AVX2 as well as the baseline (socp/vector_clones.h): the VEX
// encoding's three operands spare register copies; without FMA every operation rounds as the
// baseline's, so the answers are bitwise the same.
STRICTMIN_VECTOR_CLONES
RingSolution<2> solve_clones(const RingTerm<2>* terms, int n, const int* guess, int guess_size) {
  return solve_ring<2>(terms, n, guess, guess_size);
}

STRICTMIN_VECTOR_CLONES
RingSolution<3> solve_clones(const RingTerm<3>* terms, int n, const int* guess, int guess_size) {
  return solve_ring<3>(terms, n, guess, guess_size);
}

}  // namespace

template <int d>
RingSolution<d> solve_one_ring(const RingTerm<d>* terms, int n, const int* guess, int guess_size) {
  return solve_clones(terms, n, guess, guess_size);
}

template <int d>
RingSolution<d> solve_one_ring(const RingTerm<d>* terms, int n) {
  return solve_one_ring<d>(terms, n, nullptr, 0);
}

template RingSolution<2> solve_one_ring<2>(const RingTerm<2>*, int);
template RingSolution<3> solve_one_ring<3>(const RingTerm<3>*, int);
template RingSolution<2> solve_one_ring<2>(const RingTerm<2>*, int, const int*, int);
template RingSolution<3> solve_one_ring<3>(const RingTerm<3>*, int, const int*, int);

}  // namespace strictmin
