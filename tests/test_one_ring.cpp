// The exact 1-ring solver (one_ring.h) against an independent dense solver (a log-barrier
// Newton method on (q, t): min t s.t. a_T ||q - c_T||^2 + b_T <= t) on thousands of random
// rings in 2D and 3D, including degenerate ones, plus a KKT certificate for every answer:
// multipliers l >= 0 on the active terms with q = sum l a c / sum l a, whose dual value
// min_q sum l_T f_T(q) (a lower bound on the optimum) matches the returned value.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "strictmin/solvers/one_ring.h"

using namespace strictmin;

namespace {

template <int d>
using Vec = Eigen::Matrix<double, d, 1>;
template <int d>
using Terms = std::vector<RingTerm<d>>;

template <int d>
double f(const RingTerm<d>& t, const Vec<d>& q) {
  return t.a * (q - t.centre).squaredNorm() + t.b;
}

template <int d>
double objective(const Terms<d>& terms, const Vec<d>& q) {
  double m = 0;
  for (const auto& t : terms) m = std::max(m, f(t, q));
  return m;
}

// min_q sum l_T f_T(q) for l >= 0 summing to 1: a lower bound on the optimum (weak duality).
template <int d>
double dual_value(const Terms<d>& terms, const std::vector<double>& l) {
  double la = 0, total = 0;
  Vec<d> lac = Vec<d>::Zero();
  for (size_t i = 0; i < terms.size(); ++i) {
    la += l[i] * terms[i].a;
    lac += l[i] * terms[i].a * terms[i].centre;
  }
  const Vec<d> q = lac / la;
  for (size_t i = 0; i < terms.size(); ++i) total += l[i] * f(terms[i], q);
  return total;
}

template <int d>
struct Reference {
  Vec<d> q;
  double upper = 0;  // objective at q
  double lower = 0;  // dual bound from the barrier multipliers
};

// Log-barrier Newton method: minimize tau t - sum log(t - f_T(q)), tau growing tenfold.
// Every outer step gives an upper bound F(q) and a lower bound min_q sum l_T f_T(q) with
// l_T proportional to 1 / (t - f_T(q)); the best of each is kept (at large tau rounding
// spoils the multipliers, while the iterate keeps improving).
// Newton's method on the KKT equations of the terms the barrier finds active (multiplier
// above threshold)
// (f_T(q) = t, sum l_T a_T (q - c_T) = 0, sum l_T = 1), least squares where they are
// degenerate. Keeps whichever bounds improve: both stay rigorous evaluations.
template <int d>
void polish(const Terms<d>& terms, const Eigen::Matrix<double, d + 1, 1>& z, double tau, double threshold,
            Reference<d>& ref) {
  const int n = static_cast<int>(terms.size());
  std::vector<int> active;
  std::vector<double> lam;
  for (int i = 0; i < n; ++i) {
    const double l = 1.0 / (tau * (z(d) - f(terms[i], Vec<d>(z.template head<d>()))));
    if (l > threshold) active.push_back(i), lam.push_back(l);
  }
  const int k = static_cast<int>(active.size());
  Eigen::VectorXd x(d + 1 + k);  // q, t, l
  x << z, Eigen::Map<Eigen::VectorXd>(lam.data(), k);
  for (int it = 0; it < 8; ++it) {
    const Vec<d> q = x.template head<d>();
    Eigen::VectorXd F = Eigen::VectorXd::Zero(k + d + 1);
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(k + d + 1, d + 1 + k);
    for (int r = 0; r < k; ++r) {
      const RingTerm<d>& t = terms[active[r]];
      F(r) = f(t, q) - x(d);
      J.block(r, 0, 1, d) = 2 * t.a * (q - t.centre).transpose();
      J(r, d) = -1;
      const double l = x(d + 1 + r);
      F.segment(k, d) += l * t.a * (q - t.centre);
      J.block(k, 0, d, d).diagonal().array() += l * t.a;
      J.block(k, d + 1 + r, d, 1) = t.a * (q - t.centre);
      F(k + d) += l;
      J(k + d, d + 1 + r) = 1;
    }
    F(k + d) -= 1;
    x -= J.completeOrthogonalDecomposition().solve(F);
    const Vec<d> qn = x.template head<d>();
    const double upper = objective(terms, qn);
    if (upper < ref.upper) ref.upper = upper, ref.q = qn;
    std::vector<double> l(n, 0.0);
    double sum = 0;
    for (int r = 0; r < k; ++r) sum += l[active[r]] = std::max(0.0, x(d + 1 + r));
    if (sum > 0) {
      for (double& v : l) v /= sum;
      ref.lower = std::max(ref.lower, dual_value(terms, l));
    }
  }
}

template <int d>
Reference<d> reference_solve_centred(const Terms<d>& terms) {
  using Z = Eigen::Matrix<double, d + 1, 1>;
  using H = Eigen::Matrix<double, d + 1, d + 1>;
  const int n = static_cast<int>(terms.size());
  Vec<d> q = Vec<d>::Zero();
  for (const auto& t : terms) q += t.centre / n;
  const double F0 = objective(terms, q);
  Reference<d> ref;
  ref.q = q;
  ref.upper = F0;
  if (F0 == 0) return ref;  // every term zero at the mean
  Z z;
  z << q, 1.5 * F0;
  const auto slacks_ok = [&](const Z& w) {
    for (const auto& t : terms)
      if (!(w(d) - f(t, Vec<d>(w.template head<d>())) > 0)) return false;
    return true;
  };
  double tau = n / F0;
  Z best_z = z;
  double best_tau = tau;
  for (int outer = 0; outer < 60 && n / tau > 1e-15 * z(d); ++outer, tau *= 10) {
    for (int it = 0; it < 60; ++it) {
      Z grad = Z::Zero();
      H hess = H::Zero();
      grad(d) = tau;
      const Vec<d> qq = z.template head<d>();
      for (const auto& t : terms) {
        const double s = z(d) - f(t, qq);
        Z ds;
        ds << -2 * t.a * (qq - t.centre), 1.0;
        grad -= ds / s;
        hess += ds * ds.transpose() / (s * s);
        hess.template topLeftCorner<d, d>().diagonal().array() += 2 * t.a / s;
      }
      const Z step = -hess.ldlt().solve(grad);
      const double decrement = -grad.dot(step);  // squared Newton decrement (scale-free)
      if (!(decrement > 1e-15)) break;
      // Damped Newton step of self-concordant barriers, then full steps; stay feasible.
      double alpha = decrement > 0.25 ? 1 / (1 + std::sqrt(decrement)) : 1.0;
      while (alpha > 1e-20 && !slacks_ok(z + alpha * step)) alpha *= 0.5;
      if (!slacks_ok(z + alpha * step)) break;
      z += alpha * step;
    }
    const Vec<d> qq = z.template head<d>();
    const double upper = objective(terms, qq);
    if (upper < ref.upper) ref.upper = upper, ref.q = qq;
    std::vector<double> l(n);
    double sum = 0;
    for (int i = 0; i < n; ++i) sum += l[i] = 1.0 / (z(d) - f(terms[i], qq));
    for (double& x : l) x /= sum;
    const double lower = dual_value(terms, l);
    if (lower > ref.lower) ref.lower = lower, best_z = z, best_tau = tau;
  }
  // Polish from the iterate whose multipliers were best.
  for (double threshold : {1e-2, 1e-4, 1e-6, 1e-8}) polish(terms, best_z, best_tau, threshold, ref);
  return ref;
}

// The same in coordinates centred at the mean of the centres.
template <int d>
Reference<d> reference_solve(Terms<d> terms) {
  Vec<d> mean = Vec<d>::Zero();
  for (const auto& t : terms) mean += t.centre / static_cast<double>(terms.size());
  for (auto& t : terms) t.centre -= mean;
  Reference<d> ref = reference_solve_centred(terms);
  ref.q += mean;
  return ref;
}

// KKT certificate for q: multipliers on the terms within 1e-9 of the maximum such that
// q = sum w_T c_T with w >= 0 (w_T proportional to l_T a_T), searched over the subsets of
// at most d+1 active terms. Returns the dual value of the best multipliers found (-1: none).
template <int d>
double kkt_lower_bound(const Terms<d>& terms, const Vec<d>& q, double value) {
  std::vector<int> active;
  for (int i = 0; i < static_cast<int>(terms.size()); ++i)
    if (f(terms[i], q) >= value * (1 - 1e-9)) active.push_back(i);
  double best = -1;
  const int na = static_cast<int>(active.size());
  std::vector<int> pick;
  std::function<void(int)> recurse = [&](int from) {
    if (!pick.empty()) {
      const int k = static_cast<int>(pick.size());
      Eigen::MatrixXd E(d, k - 1);
      for (int i = 1; i < k; ++i) E.col(i - 1) = terms[pick[i]].centre - terms[pick[0]].centre;
      Eigen::VectorXd mu = Eigen::VectorXd::Zero(k - 1);
      if (k > 1) mu = E.colPivHouseholderQr().solve(q - terms[pick[0]].centre);
      std::vector<double> l(terms.size(), 0.0);
      l[pick[0]] = std::max(0.0, 1 - mu.sum()) / terms[pick[0]].a;
      for (int i = 1; i < k; ++i) l[pick[i]] = std::max(0.0, mu(i - 1)) / terms[pick[i]].a;
      double sum = 0;
      for (double x : l) sum += x;
      if (sum > 0 && std::isfinite(sum)) {
        for (double& x : l) x /= sum;
        best = std::max(best, dual_value(terms, l));
      }
    }
    if (static_cast<int>(pick.size()) == d + 1) return;
    for (int i = from; i < na; ++i) {
      pick.push_back(active[i]);
      recurse(i + 1);
      pick.pop_back();
    }
  };
  recurse(0);
  return best;
}

struct Stats {
  int rings = 0;
  double worst_value = 0, worst_q = 0, worst_kkt = 0;
};

// Checks one ring against the reference and its own KKT certificate.
template <int d>
void check_ring(const Terms<d>& terms, Stats& stats, const char* family, int index) {
  const RingSolution<d> sol = solve_one_ring<d>(terms.data(), static_cast<int>(terms.size()));
  SCOPED_TRACE(::testing::Message() << family << " ring " << index << " (" << terms.size() << " terms)");
  ASSERT_TRUE(sol.q.allFinite());
  const double value = objective(terms, sol.q);
  EXPECT_NEAR(sol.value, value, 1e-14 * value) << "value reported is the objective at q";
  EXPECT_GE(sol.active, 1);
  EXPECT_LE(sol.active, d + 1);
  for (int i = 0; i < sol.active; ++i)
    EXPECT_GE(f(terms[sol.support[i]], sol.q), value * (1 - 1e-12)) << "support term " << sol.support[i];
  // Rounding of the values at q: 1e-14 relative, plus eps |q| in the coordinates.
  double amax = 0;
  for (const auto& t : terms) amax = std::max(amax, t.a);
  const double rounding = 1e-14 * value + 8 * std::sqrt(amax * value) * 2.3e-16 * sol.q.norm();

  // Started from a guess of the support (right: the support found; wrong: another set,
  // possibly invalid), the answer is the same.
  const int n = static_cast<int>(terms.size());
  const RingSolution<d> warm = solve_one_ring<d>(terms.data(), n, sol.support.data(), sol.active);
  EXPECT_NEAR(objective(terms, warm.q), value, 2 * rounding);
  const int wrong[4] = {n - 1, 0, n / 2, n};  // may repeat or run out of range: ignored then
  for (int size = 1; size <= d + 1; ++size) {
    const RingSolution<d> other = solve_one_ring<d>(terms.data(), n, wrong, size);
    EXPECT_NEAR(objective(terms, other.q), value, 2 * rounding) << "guess of size " << size;
  }

  // Ours is no worse than the reference's point, no better than its dual bound, and so
  // agrees with the optimum to the reference's gap.
  const Reference<d> ref = reference_solve(terms);
  ASSERT_LE(ref.upper - ref.lower, 1e-10 * ref.upper) << "the reference did not converge";
  EXPECT_LE(value, ref.upper + rounding);
  EXPECT_GE(value, ref.lower - rounding);
  const double rel = std::abs(value - ref.upper) / ref.upper;
  EXPECT_LE(rel, 1e-9) << "ours " << value << " reference " << ref.upper;
  // KKT: multipliers on the active terms certify the value.
  const double kkt = kkt_lower_bound(terms, sol.q, value);
  const double kkt_gap = (value - kkt) / value;
  EXPECT_LE(value - kkt, 100 * rounding) << "no KKT multipliers certify q";
  // The minimizer is unique (the max of min_a-strongly convex terms is): both points lie
  // within sqrt((F(q) - lower) / min_a) of it. Values carry rounding of ~1e-14 relative.
  const double lower = std::max(ref.lower, kkt);
  double amin = terms[0].a;
  for (const auto& t : terms) amin = std::min(amin, t.a);
  const double radius = std::sqrt(std::max(0.0, value - lower + rounding) / amin) +
                        std::sqrt(std::max(0.0, ref.upper - lower + rounding) / amin);
  const double dq = (sol.q - ref.q).norm();
  EXPECT_LE(dq, radius) << "q differs from the reference's";
  ++stats.rings;
  stats.worst_value = std::max(stats.worst_value, rel);
  stats.worst_q = std::max(stats.worst_q, dq);
  stats.worst_kkt = std::max(stats.worst_kkt, kkt_gap);
}

template <int d>
class Generator {
 public:
  explicit Generator(unsigned seed) : rng_(seed) {}
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
  Vec<d> point(double r = 1) {
    Vec<d> p;
    for (int i = 0; i < d; ++i) p(i) = uniform(-r, r);
    return p;
  }
  RingTerm<d> term(double amin = 0.2, double amax = 5, double bmax = 0.5) {
    RingTerm<d> t;
    t.centre = point();
    t.a = std::exp(uniform(std::log(amin), std::log(amax)));
    t.b = uniform(0, bmax);
    return t;
  }
  Terms<d> typical(int nmin, int nmax) {
    Terms<d> terms(integer(nmin, nmax));
    for (auto& t : terms) t = term();
    return terms;
  }
  // A vertex's ring as a relaxation sweep sees it: simplices around the origin (a fan of
  // triangles in 2D, random tets in 3D) under a perturbed map and rotated targets; the terms
  // follow docs/maths.md: M = sum_{j != v} q_j g_j^T - R, a = |g_v|^2, c = -M g_v / a,
  // b = ||M||^2 - ||M g_v||^2 / a.
  Terms<d> mesh_like(int n) {
    Terms<d> terms;
    Eigen::Matrix<double, d, d> R;
    if constexpr (d == 2)
      R = Eigen::Rotation2Dd(uniform(-0.5, 0.5)).toRotationMatrix();
    else
      R = Eigen::AngleAxisd(uniform(-0.5, 0.5), point().normalized()).toRotationMatrix();
    for (int i = 0; i < n; ++i) {
      Eigen::Matrix<double, d, d> E;  // edges from the vertex: columns
      if constexpr (d == 2) {
        const double a0 = 2 * M_PI * (i + 0.3 * uniform(-1, 1)) / n, a1 = 2 * M_PI * (i + 1 + 0.3 * uniform(-1, 1)) / n;
        E << std::cos(a0), std::cos(a1), std::sin(a0), std::sin(a1);
      } else {
        do {
          for (int c = 0; c < d; ++c) E.col(c) = point();
        } while (E.determinant() < 0.1);
      }
      const Eigen::Matrix<double, d, d> inv = E.inverse();  // rows: gradients of corners 1..d
      const Vec<d> g = -inv.colwise().sum().transpose();     // gradient at the vertex
      Eigen::Matrix<double, d, d> M = -R;
      for (int c = 0; c < d; ++c) M += (E.col(c) + 0.3 * point()) * inv.row(c);
      terms.push_back(ring_term<d>(M, g, 1.0 / g.squaredNorm()));
    }
    return terms;
  }

 private:
  std::mt19937 rng_;
};

constexpr int kMaxTerms2 = 10;
constexpr int kMaxTerms3 = 26;

template <int d>
int max_terms() {
  return d == 2 ? kMaxTerms2 : kMaxTerms3;
}

template <int d>
void run_family(const char* family, int count, unsigned seed, const std::function<Terms<d>(Generator<d>&)>& make) {
  Generator<d> gen(seed);
  Stats stats;
  for (int i = 0; i < count; ++i) {
    check_ring<d>(make(gen), stats, family, i);
    if (::testing::Test::HasFatalFailure()) return;
  }
  std::printf("[ %dD %-18s] %d rings, worst relative value difference %.1e, |dq| %.1e, KKT gap %.1e\n", d, family,
              stats.rings, stats.worst_value, stats.worst_q, stats.worst_kkt);
}

template <int d>
void run_all_families(unsigned seed) {
  const int nmax = max_terms<d>();
  run_family<d>("typical", 1500, seed + 1, [&](Generator<d>& g) { return g.typical(2, nmax); });
  run_family<d>("mesh-like", 1000, seed + 9, [&](Generator<d>& g) { return g.mesh_like(g.integer(3, nmax)); });
  run_family<d>("single", 100, seed + 2, [&](Generator<d>& g) { return g.typical(1, 1); });
  run_family<d>("equal-a, b = 0", 300, seed + 3, [&](Generator<d>& g) {
    Terms<d> terms = g.typical(2, nmax);
    for (auto& t : terms) t.a = 1, t.b = 0;
    return terms;
  });
  run_family<d>("coincident centres", 400, seed + 4, [&](Generator<d>& g) {
    Terms<d> terms = g.typical(2, nmax);
    for (size_t i = 1; i < terms.size(); ++i) {
      const int r = g.integer(0, 2);
      const size_t j = g.integer(0, static_cast<int>(i) - 1);
      if (r == 0) terms[i].centre = terms[j].centre;  // same centre, other a and b
      if (r == 1) terms[i] = terms[j];                 // exact duplicate
    }
    return terms;
  });
  run_family<d>("nearly collinear", 400, seed + 5, [&](Generator<d>& g) {
    Terms<d> terms = g.typical(3, nmax);
    const double eps = std::pow(10.0, g.uniform(-14, -4));
    const Vec<d> dir = g.point().normalized();
    for (auto& t : terms) t.centre = g.uniform(-1, 1) * dir + eps * g.point();
    if (g.integer(0, 1)) terms[0].b = terms[1].b = terms[2].b = 0.3;
    return terms;
  });
  run_family<d>("slivers (a ratio 1e6)", 500, seed + 6, [&](Generator<d>& g) {
    Terms<d> terms = g.typical(2, nmax);
    for (auto& t : terms) t.a = g.integer(0, 1) ? 1.0 : 1e6;
    if (g.integer(0, 1))
      for (auto& t : terms) t.a = std::pow(10.0, g.uniform(-3, 3));
    return terms;
  });
  run_family<d>("far from the origin", 300, seed + 7, [&](Generator<d>& g) {
    Terms<d> terms = g.typical(2, nmax);
    const Vec<d> shift = 1e3 * g.point();
    for (auto& t : terms) t.centre += shift;
    return terms;
  });
  run_family<d>("tiny scale", 200, seed + 8, [&](Generator<d>& g) {
    Terms<d> terms = g.typical(2, nmax);
    for (auto& t : terms) t.centre *= 1e-6, t.b *= 1e-12;
    return terms;
  });
}

TEST(OneRing, MatchesReferenceOnRandomRings2D) { run_all_families<2>(100); }
TEST(OneRing, MatchesReferenceOnRandomRings3D) { run_all_families<3>(200); }

// One term far above the others at its own centre: that centre is the answer, exactly.
template <int d>
void dominating(unsigned seed) {
  Generator<d> g(seed);
  for (int i = 0; i < 200; ++i) {
    Terms<d> terms = g.typical(2, max_terms<d>());
    const int k = g.integer(0, static_cast<int>(terms.size()) - 1);
    terms[k].b = 1e3;
    const RingSolution<d> sol = solve_one_ring<d>(terms.data(), static_cast<int>(terms.size()));
    EXPECT_LE((sol.q - terms[k].centre).norm(), 1e-12);
    EXPECT_NEAR(sol.value, 1e3, 1e-12 * 1e3);
    EXPECT_EQ(sol.active, 1);
  }
}
TEST(OneRing, DominatingElementStaysAtItsCentre) {
  dominating<2>(5);
  dominating<3>(6);
}

// Equal terms on a circle / sphere around p: p is optimal with every term active, more
// than d+1 of them (a degenerate basis).
TEST(OneRing, SymmetricRingsHaveTheCentreAsOptimum) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int n = 3; n <= 12; ++n) {
    Terms<2> terms(n);
    const Eigen::Vector2d p(u(rng), u(rng));
    const double phase = u(rng), radius = 0.7, a = 2.5, b = 0.1;
    for (int i = 0; i < n; ++i) {
      const double angle = phase + 2 * M_PI * i / n;
      terms[i].centre = p + radius * Eigen::Vector2d(std::cos(angle), std::sin(angle));
      terms[i].a = a;
      terms[i].b = b;
    }
    const RingSolution<2> sol = solve_one_ring<2>(terms.data(), n);
    EXPECT_LE((sol.q - p).norm(), 1e-12) << n;
    EXPECT_NEAR(sol.value, a * radius * radius + b, 1e-13);
  }
  // Octahedron and cube vertices, randomly rotated.
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Matrix3d rot = Eigen::Quaterniond(Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
    const Eigen::Vector3d p(u(rng), u(rng), u(rng));
    Terms<3> terms;
    for (int axis = 0; axis < 3; ++axis)
      for (int sign : {-1, 1}) terms.push_back({p + rot * (sign * Eigen::Vector3d::Unit(axis)), 3.0, 0.2});
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3d c((corner & 1) ? 1 : -1, (corner & 2) ? 1 : -1, (corner & 4) ? 1 : -1);
      terms.push_back({p + rot * (c / std::sqrt(3.0)), 3.0, 0.2});
    }
    const RingSolution<3> sol = solve_one_ring<3>(terms.data(), static_cast<int>(terms.size()));
    EXPECT_LE((sol.q - p).norm(), 1e-12);
    EXPECT_NEAR(sol.value, 3.2, 1e-13 * 3.2);
  }
}

TEST(OneRing, SingleElementAndZeroRing) {
  const RingTerm<2> t{Eigen::Vector2d(0.3, -0.2), 4.0, 0.25};
  const RingSolution<2> sol = solve_one_ring<2>(&t, 1);
  EXPECT_EQ(sol.q, t.centre);
  EXPECT_EQ(sol.value, 0.25);
  EXPECT_EQ(sol.active, 1);
  // Every term zero at one common centre (an undistorted ring).
  std::vector<RingTerm<3>> zero(5, RingTerm<3>{Eigen::Vector3d(1, 2, 3), 1.0, 0.0});
  for (int i = 0; i < 5; ++i) zero[i].a = 1 + i;
  const RingSolution<3> sol3 = solve_one_ring<3>(zero.data(), 5);
  EXPECT_EQ(sol3.value, 0.0);
  EXPECT_EQ(sol3.q, Eigen::Vector3d(1, 2, 3));
}

// Two terms, closed form: on the segment where a0 mu^2 L^2 + b0 = a1 (1 - mu)^2 L^2 + b1.
TEST(OneRing, TwoTermsMatchTheClosedForm) {
  const RingTerm<2> terms[2] = {{Eigen::Vector2d(0, 0), 1.0, 0.0}, {Eigen::Vector2d(3, 0), 4.0, 0.0}};
  // mu^2 9 = 4 (1 - mu)^2 9  =>  mu = 2 (1 - mu)  =>  mu = 2/3.
  const RingSolution<2> sol = solve_one_ring<2>(terms, 2);
  EXPECT_NEAR(sol.q.x(), 2.0, 1e-15);
  EXPECT_NEAR(sol.q.y(), 0.0, 1e-15);
  EXPECT_NEAR(sol.value, 4.0, 1e-14);
  EXPECT_EQ(sol.active, 2);
}

}  // namespace
