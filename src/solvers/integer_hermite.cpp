// Column Hermite normal form over the integers (src/solvers/integer_hermite.h).
#include "solvers/integer_hermite.h"

#include <stdexcept>
#include <utility>

namespace strictmin {
namespace {

using Columns = std::vector<IntegerVector>;

void negate(IntegerVector& column) {
  for (mpz_class& x : column) x = -x;
}

// The column among cols[first..] whose entry in `row` is the smallest nonzero one, -1 if none.
int smallest_entry(const Columns& cols, int row, int first) {
  int best = -1;
  for (int c = first; c < static_cast<int>(cols.size()); ++c) {
    const mpz_class& x = cols[static_cast<std::size_t>(c)][static_cast<std::size_t>(row)];
    if (sgn(x) != 0 && (best < 0 || mpz_cmpabs(x.get_mpz_t(), cols[static_cast<std::size_t>(best)][static_cast<std::size_t>(row)].get_mpz_t()) < 0))
      best = c;
  }
  return best;
}

// Applies col_c -= q col_p to cols and to the companion's columns (U, when given).
void combine(Columns& cols, Columns* companion, int c, int p, const mpz_class& q, int from_row) {
  subtract_column(cols[static_cast<std::size_t>(c)], cols[static_cast<std::size_t>(p)], q, from_row);
  if (companion) subtract_column((*companion)[static_cast<std::size_t>(c)], (*companion)[static_cast<std::size_t>(p)], q);
}

}  // namespace

void subtract_column(IntegerVector& target, const IntegerVector& source, const mpz_class& q, int from) {
  if (sgn(q) == 0) return;
  for (std::size_t r = static_cast<std::size_t>(from); r < source.size(); ++r)
    if (sgn(source[r]) != 0) mpz_submul(target[r].get_mpz_t(), q.get_mpz_t(), source[r].get_mpz_t());
}

mpz_class rounded_quotient(const mpz_class& a, const mpz_class& b) {
  // floor((2a + |b|) / (2|b|)) * sign(b): the integer nearest a / b.
  mpz_class abs_b = abs(b), q;
  mpz_class twice = 2 * a + abs_b;
  mpz_fdiv_q(q.get_mpz_t(), twice.get_mpz_t(), mpz_class(2 * abs_b).get_mpz_t());
  return sgn(b) < 0 ? mpz_class(-q) : q;
}

// Euclid's algorithm on the columns: the smallest nonzero entry of `row` among cols[first..]
// reduces the others to their remainders (|r| <= |pivot| / 2) until one is left; it is moved
// to cols[first] and made positive. Every step is unimodular. False when the row is zero.
bool eliminate_row(Columns& cols, Columns* companion, int row, int first, int from_row) {
  const std::size_t r = static_cast<std::size_t>(row);
  while (true) {
    const int p = smallest_entry(cols, row, first);
    if (p < 0) return false;
    bool others = false;
    for (int c = first; c < static_cast<int>(cols.size()); ++c) {
      if (c == p || sgn(cols[static_cast<std::size_t>(c)][r]) == 0) continue;
      combine(cols, companion, c, p, rounded_quotient(cols[static_cast<std::size_t>(c)][r], cols[static_cast<std::size_t>(p)][r]),
              from_row);
      others = others || sgn(cols[static_cast<std::size_t>(c)][r]) != 0;
    }
    if (others) continue;
    std::swap(cols[static_cast<std::size_t>(p)], cols[static_cast<std::size_t>(first)]);
    if (companion) std::swap((*companion)[static_cast<std::size_t>(p)], (*companion)[static_cast<std::size_t>(first)]);
    if (sgn(cols[static_cast<std::size_t>(first)][r]) < 0) {
      negate(cols[static_cast<std::size_t>(first)]);
      if (companion) negate((*companion)[static_cast<std::size_t>(first)]);
    }
    return true;
  }
}

ColumnHermiteForm column_hermite_form(const IntegerMatrix& A) {
  const int n = A.cols();
  ColumnHermiteForm out;
  out.H = A;
  out.U = IntegerMatrix(n, n);
  for (int k = 0; k < n; ++k) out.U(k, k) = 1;
  int next = 0;  // the next pivot column; columns next.. are zero in the rows above `row`
  for (int row = 0; row < A.rows && next < n; ++row) {
    if (!eliminate_row(out.H.columns, &out.U.columns, row, next, row)) continue;
    // The entries left of the pivot reduced to 0 <= h < pivot (the normal form's uniqueness).
    const mpz_class& pivot = out.H(row, next);
    for (int c = 0; c < next; ++c) {
      mpz_class q;
      mpz_fdiv_q(q.get_mpz_t(), out.H(row, c).get_mpz_t(), pivot.get_mpz_t());
      combine(out.H.columns, &out.U.columns, c, next, q, row);
    }
    out.pivot_rows.push_back(row);
    ++next;
  }
  return out;
}

std::optional<IntegerVector> integer_solution(const IntegerMatrix& A, const IntegerVector& b) {
  if (static_cast<int>(b.size()) != A.rows) throw std::invalid_argument("integer_solution: b has the wrong size");
  const ColumnHermiteForm f = column_hermite_form(A);
  // H y = b by forward substitution over the pivot rows: y_k = (b - sum_{j<k} H y_j) / pivot_k.
  IntegerVector rest = b, y(static_cast<std::size_t>(f.rank()));
  for (int k = 0; k < f.rank(); ++k) {
    const std::size_t row = static_cast<std::size_t>(f.pivot_rows[static_cast<std::size_t>(k)]);
    const mpz_class& pivot = f.H(static_cast<int>(row), k);
    if (!mpz_divisible_p(rest[row].get_mpz_t(), pivot.get_mpz_t())) return std::nullopt;
    mpz_divexact(y[static_cast<std::size_t>(k)].get_mpz_t(), rest[row].get_mpz_t(), pivot.get_mpz_t());
    subtract_column(rest, f.H.columns[static_cast<std::size_t>(k)], y[static_cast<std::size_t>(k)]);
  }
  for (const mpz_class& r : rest)  // the rows without a pivot: H's columns span nothing there
    if (sgn(r) != 0) return std::nullopt;
  IntegerVector x(static_cast<std::size_t>(A.cols()));  // x = U y
  for (int k = 0; k < f.rank(); ++k) subtract_column(x, f.U.columns[static_cast<std::size_t>(k)], -y[static_cast<std::size_t>(k)]);
  return x;
}

IntegerMatrix integer_kernel(const IntegerMatrix& A) {
  ColumnHermiteForm f = column_hermite_form(A);
  IntegerMatrix K;
  K.rows = A.cols();
  for (int k = f.rank(); k < A.cols(); ++k) K.columns.push_back(std::move(f.U.columns[static_cast<std::size_t>(k)]));
  return K;
}

}  // namespace strictmin
