#pragma once
// The second-order cone program solved by the interior-point method, specialised to
// per-element cones of a mesh map (paper Section 5.1):
//
//   minimize    1/2 x^T P x + q^T x + c_k k
//   subject to  s_i = (a_i k + b_i,  G_i x - h_i)  in Q^{t+1},   i = 0 .. #element cones-1
//               s_scalar = a k + b  >= 0                        (optional 1-dimensional cone)
//               A x = beq
//
// x are the free vertex coordinates (vertex-major, Problem::free_index), k is one scalar
// (the L-infinity bound; absent when has_k is false), G_i x - h_i = vec(J_T - R_T) of the
// cone's element T (t = n*m entries, row-major), and P = 2 sum_i quad_weight_i G_i^T G_i,
// q = -2 sum_i quad_weight_i G_i^T h_i (a weighted least-squares objective; empty when
// there is none). M denotes the linear map (x, k) -> (a_i k, G_i x) of all cones.
//
// G_i is never stored as a sparse matrix: element i keeps its corners' first free dof (or -1
// for a fixed corner) and its barycentric gradients, so that G x and G^T y are computed per
// element in parallel (the transpose gathers through a vertex -> (cone, corner) incidence).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <vector>

namespace strictmin::socp {

struct ConeProgram {
  int n = 2, m = 2;       // image and domain dimension
  int num_x = 0;          // free dofs
  bool has_k = true;
  double c_k = 1.0;

  // Element cones.
  std::vector<int> element;     // #cones: the problem's element index
  std::vector<int> dof_base;    // #cones * (m+1): free dof of corner j's first coordinate, or -1
  std::vector<double> grad;     // #cones * (m+1) * m: gradient of corner j (row-major)
  Eigen::VectorXd h;            // #cones * t
  Eigen::VectorXd weight;       // #cones: area / volume (weighted least squares)
  Eigen::VectorXd quad_weight;  // #cones or empty: the objective's P, q
  Eigen::VectorXd head_a, head_b;  // #cones + (has_scalar ? 1 : 0)
  bool has_scalar = false;      // the 1-dimensional cone a k + b >= 0 (last cone)

  // Equalities on x (empty: none).
  Eigen::SparseMatrix<double, Eigen::RowMajor> A;
  Eigen::VectorXd beq;

  // Vertex incidence for G^T: free vertex f has entries incidence[offset[f] .. offset[f+1]),
  // each cone * (m+1) + corner.
  std::vector<int> incidence_offset, incidence;

  // --- sizes -------------------------------------------------------------------------
  int t() const { return n * m; }
  int corners() const { return m + 1; }
  int local_dofs() const { return n * (m + 1); }
  int num_element_cones() const { return static_cast<int>(element.size()); }
  int num_cones() const { return num_element_cones() + (has_scalar ? 1 : 0); }
  int cone_dim(int i) const { return i < num_element_cones() ? t() + 1 : 1; }
  Eigen::Index cone_offset(int i) const { return static_cast<Eigen::Index>(i) * (t() + 1); }
  Eigen::Index cone_size() const {
    return cone_offset(num_element_cones()) + (has_scalar ? 1 : 0);
  }
  int num_eq() const { return static_cast<int>(A.rows()); }
  bool has_quad() const { return quad_weight.size() > 0; }

  // Builds the incidence from dof_base; call once after filling the element data.
  void finalize();

  // --- operators ---------------------------------------------------------------------
  // tails.segment(i*t, t) = G_i x (no h).
  void apply_g(const Eigen::VectorXd& x, Eigen::VectorXd& tails) const;
  // x = sum_i G_i^T tails_i, with tails read at stride `stride` starting at `first`
  // (so that the tails of a full cone vector can be read in place: stride t+1, first 1).
  void apply_gt(const double* tails, Eigen::Index stride, Eigen::Index first, Eigen::VectorXd& x) const;
  // out = M (x, k) + o: heads a_i k + b_i and tails G_i x - h_i (with_offset) or M (x, k).
  void apply_m(const Eigen::VectorXd& x, double k, bool with_offset, Eigen::VectorXd& out) const;
  // (gx, gk) = M^T u.
  void apply_mt(const Eigen::VectorXd& u, Eigen::VectorXd& gx, double& gk) const;
  // P x (zero when there is no quadratic objective).
  void apply_p(const Eigen::VectorXd& x, Eigen::VectorXd& out) const;
  // q of the objective and the constant sum_i quad_weight_i ||h_i||^2.
  Eigen::VectorXd linear_term() const;
  double constant_term() const;
};

// Element cone i of M (x, k), or of M (x, k) + o with_offset: out[0] = a_i k (+ b_i),
// out[1 .. t] = G_i x (- h_i). n_c and m_c are the element sizes, as compile-time constants
// where with_element_sizes (fixed_sizes.h) provides them, so that the loops unroll.
template <class NC, class MC>
inline void element_m(const ConeProgram& p, NC n_c, MC m_c, int i, const double* x, double k, bool with_offset,
                      double* out) {
  const int nn = n_c, mm = m_c, c = mm + 1, tt = nn * mm;
  out[0] = p.head_a[i] * k + (with_offset ? p.head_b[i] : 0.0);
  double* tail = out + 1;
  const double* hi = p.h.data() + static_cast<Eigen::Index>(i) * tt;
  for (int a = 0; a < tt; ++a) tail[a] = with_offset ? -hi[a] : 0.0;
  for (int j = 0; j < c; ++j) {
    const int base = p.dof_base[static_cast<size_t>(i) * c + j];
    if (base < 0) continue;
    const double* g = p.grad.data() + (static_cast<size_t>(i) * c + j) * mm;
    for (int r = 0; r < nn; ++r) {
      const double xr = x[base + r];
      for (int col = 0; col < mm; ++col) tail[r * mm + col] += xr * g[col];
    }
  }
}

// Calls body(begin, end) on blocks of [0, count) of at least `grain` indices, on TBB threads.
void parallel_for_index(int count, int grain, const std::function<void(int, int)>& body);

}  // namespace strictmin::socp
