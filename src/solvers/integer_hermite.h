#pragma once
// Integer linear algebra with GMP integers (nothing overflows): the column Hermite normal
// form of an integer matrix, and from it whether A x = b has an integer solution and a basis
// of the integer kernel {x in Z^n : A x = 0}. Private to the library; the integer-grid
// rounding's exact check is built on it (tasks/grid_completion.h).
//
// Column Hermite normal form: A U = H with U unimodular (integer, det +-1, so U^-1 is an
// integer matrix too) and H in column echelon form: its first `rank` columns have leading
// (first nonzero) entries in increasing rows, positive, with the entries to their left in
// that row reduced to 0 <= h < pivot; its other columns are zero. Since x = U y is a
// bijection of Z^n, A x = b has an integer solution iff H y = b has one, which forward
// substitution over the pivot rows decides (each pivot must divide what is left), and the
// integer kernel of A is spanned by U's last n - rank columns.
#include <gmpxx.h>

#include <optional>
#include <vector>

namespace strictmin {

using IntegerVector = std::vector<mpz_class>;

// An m by n integer matrix, stored by columns (the Hermite form works on columns).
struct IntegerMatrix {
  int rows = 0;
  std::vector<IntegerVector> columns;

  IntegerMatrix() = default;
  IntegerMatrix(int m, int n) : rows(m), columns(static_cast<std::size_t>(n), IntegerVector(static_cast<std::size_t>(m))) {}
  int cols() const { return static_cast<int>(columns.size()); }
  mpz_class& operator()(int r, int c) { return columns[static_cast<std::size_t>(c)][static_cast<std::size_t>(r)]; }
  const mpz_class& operator()(int r, int c) const { return columns[static_cast<std::size_t>(c)][static_cast<std::size_t>(r)]; }
};

struct ColumnHermiteForm {
  IntegerMatrix H;              // A U
  IntegerMatrix U;              // unimodular, n by n
  std::vector<int> pivot_rows;  // per column k < rank: the row of its leading entry (increasing)
  int rank() const { return static_cast<int>(pivot_rows.size()); }
};

ColumnHermiteForm column_hermite_form(const IntegerMatrix& A);

// An integer x with A x = b, or nothing when there is none.
std::optional<IntegerVector> integer_solution(const IntegerMatrix& A, const IntegerVector& b);

// n by (n - rank): its columns are a basis of {x in Z^n : A x = 0}.
IntegerMatrix integer_kernel(const IntegerMatrix& A);

// The column step both use (also on other column sets): col_target -= q col_source, from row
// `from` on (the rows above are zero in both, or not wanted).
void subtract_column(IntegerVector& target, const IntegerVector& source, const mpz_class& q, int from = 0);

// Unimodular column steps on cols[first..] (the same on companion's columns, when given):
// Euclid on the entries of `row` leaves one nonzero there, positive, in cols[first]. Rows
// above from_row are not touched (zero in these columns, or not wanted). False when the row
// is zero in these columns (then nothing changed).
bool eliminate_row(std::vector<IntegerVector>& cols, std::vector<IntegerVector>* companion, int row, int first,
                   int from_row = 0);

// Nearest-integer quotient round(a / b) (either on a tie), b != 0.
mpz_class rounded_quotient(const mpz_class& a, const mpz_class& b);

}  // namespace strictmin
