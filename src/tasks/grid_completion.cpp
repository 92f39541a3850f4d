// The completable values of the integer-grid rounding (src/tasks/grid_completion.h).
#include "tasks/grid_completion.h"

#include <Eigen/LU>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace strictmin {
namespace {

mpz_class to_integer(double x) { return mpz_class(std::round(x)); }

// x - p in doubles, exact for an integer-valued x near p even when p is large.
double difference(double x, const mpz_class& p) {
  const double whole = std::round(x);
  return mpz_class(mpz_class(whole) - p).get_d() + (x - whole);
}

// The echelon basis of the lattice spanned by the columns (x_i, y_i).
void echelon(std::vector<IntegerVector> cols, GridCoset& out) {
  out.a = out.b = out.c = 0;
  int first = 0;
  if (eliminate_row(cols, nullptr, 0, 0)) {
    out.a = cols[0][0];
    out.b = cols[0][1];
    first = 1;
  }
  if (eliminate_row(cols, nullptr, 1, first)) out.c = cols[static_cast<std::size_t>(first)][1];
}

// Lagrange's reduction of a basis of a rank-2 lattice: afterwards |u| <= |v| and the nearest
// lattice point to any y is among the few around y's real coordinates in (u, v).
void reduce(mpz_class u[2], mpz_class v[2]) {
  while (true) {
    mpz_class uu = u[0] * u[0] + u[1] * u[1], vv = v[0] * v[0] + v[1] * v[1];
    if (uu > vv) {
      std::swap(u[0], v[0]);
      std::swap(u[1], v[1]);
      std::swap(uu, vv);
    }
    const mpz_class q = rounded_quotient(u[0] * v[0] + u[1] * v[1], uu);
    if (sgn(q) == 0) return;
    v[0] -= q * u[0];
    v[1] -= q * u[1];
  }
}

}  // namespace

bool GridCoset::contains(const Eigen::Vector2d& point) const {
  // point - p = w0 (a, b) + w1 (0, c): forward substitution, each step exact.
  const mpz_class d0 = to_integer(point.x()) - p0;
  mpz_class d1 = to_integer(point.y()) - p1;
  if (sgn(a) == 0) {
    if (sgn(d0) != 0) return false;
  } else {
    if (!mpz_divisible_p(d0.get_mpz_t(), a.get_mpz_t())) return false;
    d1 -= mpz_class(d0 / a) * b;
  }
  return sgn(c) == 0 ? sgn(d1) == 0 : mpz_divisible_p(d1.get_mpz_t(), c.get_mpz_t()) != 0;
}

Eigen::Vector2d GridCoset::nearest(const Eigen::Vector2d& y) const {
  mpz_class u[2] = {a, b}, v[2] = {0, c};
  if (sgn(u[0]) == 0 && sgn(u[1]) == 0) std::swap(u, v);  // a single generator in u
  const bool rank2 = sgn(v[0]) != 0 || sgn(v[1]) != 0;
  if (rank2) reduce(u, v);
  const Eigen::Vector2d delta(difference(y.x(), p0), difference(y.y(), p1));  // y - p
  const Eigen::Vector2d U(u[0].get_d(), u[1].get_d()), V(v[0].get_d(), v[1].get_d());
  long best_i = 0, best_j = 0;
  double best = std::numeric_limits<double>::infinity();
  auto consider = [&](long i, long j) {
    const double d = (static_cast<double>(i) * U + static_cast<double>(j) * V - delta).squaredNorm();
    if (d < best) {
      best = d;
      best_i = i;
      best_j = j;
    }
  };
  if (rank2) {  // y's coordinates in (u, v), rounded, and the points around (Babai, then a small search)
    Eigen::Matrix2d B;
    B << U, V;
    const Eigen::Vector2d w = B.inverse() * delta;
    for (long i = std::lround(w(0)) - 2; i <= std::lround(w(0)) + 2; ++i)
      for (long j = std::lround(w(1)) - 2; j <= std::lround(w(1)) + 2; ++j) consider(i, j);
  } else if (U.squaredNorm() > 0) {  // a line: the two multiples around y's projection
    const double s = delta.dot(U) / U.squaredNorm();
    consider(static_cast<long>(std::floor(s)), 0);
    consider(static_cast<long>(std::ceil(s)), 0);
  } else {
    consider(0, 0);  // a single point
  }
  const mpz_class x = p0 + best_i * u[0] + best_j * v[0], z = p1 + best_i * u[1] + best_j * v[1];
  return {x.get_d(), z.get_d()};
}

GridCompletion::GridCompletion(const IntegerMatrix& relations) : kernel_(integer_kernel(relations).columns) {
  x0_.assign(static_cast<std::size_t>(relations.cols()), 0);
  m_ = kernel_;
}

GridCoset GridCompletion::coset(int value) const {
  const std::size_t r0 = 2 * static_cast<std::size_t>(value), r1 = r0 + 1;
  std::vector<IntegerVector> rows;  // M's columns on the value's two rows
  for (const IntegerVector& col : m_)
    if (sgn(col[r0]) != 0 || sgn(col[r1]) != 0) rows.push_back({col[r0], col[r1]});
  GridCoset out;
  out.p0 = x0_[r0];
  out.p1 = x0_[r1];
  echelon(std::move(rows), out);
  return out;
}

bool GridCompletion::fix(int value, const Eigen::Vector2d& point) {
  if (!coset(value).contains(point)) return false;
  const int r0 = 2 * value, r1 = r0 + 1;
  // M's two rows in echelon form by column steps on all of M: [a 0 ...; b c 0 ...].
  const bool has_a = eliminate_row(m_, nullptr, r0, 0);
  const int second = has_a ? 1 : 0;
  const bool has_c = eliminate_row(m_, nullptr, r1, second);
  // z's pivot part by forward substitution (contains() said it divides), x0 += M z.
  mpz_class d0 = to_integer(point.x()) - x0_[static_cast<std::size_t>(r0)];
  mpz_class d1 = to_integer(point.y()) - x0_[static_cast<std::size_t>(r1)];
  mpz_class w0 = 0, w1 = 0;
  if (has_a) {
    mpz_divexact(w0.get_mpz_t(), d0.get_mpz_t(), m_[0][static_cast<std::size_t>(r0)].get_mpz_t());
    d1 -= w0 * m_[0][static_cast<std::size_t>(r1)];
  }
  if (has_c) mpz_divexact(w1.get_mpz_t(), d1.get_mpz_t(), m_[static_cast<std::size_t>(second)][static_cast<std::size_t>(r1)].get_mpz_t());
  if (has_a) subtract_column(x0_, m_[0], -w0);
  if (has_c) subtract_column(x0_, m_[static_cast<std::size_t>(second)], -w1);
  if (x0_[static_cast<std::size_t>(r0)] != to_integer(point.x()) || x0_[static_cast<std::size_t>(r1)] != to_integer(point.y()))
    throw std::logic_error("GridCompletion: a completable value was not reached");
  m_.erase(m_.begin(), m_.begin() + second + (has_c ? 1 : 0));  // the rest is zero on value's rows
  fixed_.emplace_back(value, point);
  return true;
}

void GridCompletion::truncate(std::size_t count) {
  if (count >= fixed_.size()) return;
  std::vector<std::pair<int, Eigen::Vector2d>> keep(fixed_.begin(), fixed_.begin() + static_cast<std::ptrdiff_t>(count));
  fixed_.clear();
  x0_.assign(x0_.size(), 0);
  m_ = kernel_;
  for (const auto& [value, point] : keep)
    if (!fix(value, point)) throw std::logic_error("GridCompletion: a value fixed before no longer fits");
}

}  // namespace strictmin
