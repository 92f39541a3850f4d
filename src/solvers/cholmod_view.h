#pragma once
// A cholmod_sparse that views an Eigen compressed column-major matrix without copying: CHOLMOD
// reads (and, for the values, may be given to write) Eigen's own arrays. The matrix must stay
// alive and compressed, with sorted indices, while the view is used.
#include <Eigen/SparseCore>
#include <cholmod.h>
#include <cstring>

namespace strictmin {

// stype: 1 the upper triangle is stored, -1 the lower, 0 unsymmetric.
inline cholmod_sparse cholmod_view(Eigen::SparseMatrix<double>& M, int stype) {
  cholmod_sparse A;
  std::memset(&A, 0, sizeof A);
  A.nrow = static_cast<size_t>(M.rows());
  A.ncol = static_cast<size_t>(M.cols());
  A.nzmax = static_cast<size_t>(M.nonZeros());
  A.p = M.outerIndexPtr();
  A.i = M.innerIndexPtr();
  A.x = M.valuePtr();
  A.stype = stype;
  A.itype = CHOLMOD_INT;
  A.xtype = CHOLMOD_REAL;
  A.dtype = CHOLMOD_DOUBLE;
  A.sorted = 1;
  A.packed = 1;
  return A;
}

}  // namespace strictmin
