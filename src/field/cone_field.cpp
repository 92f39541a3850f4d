// A cross field with prescribed cones (cone_field.h,
// docs/gparam.md "Fields from cones").
#include "strictmin/field/cone_field.h"

#include <Eigen/SparseCore>
#include <cmath>
#include <complex>
#include <numbers>

#include "strictmin/field/singularities.h"
#include "strictmin/io/input_error.h"
#include "strictmin/solvers/sparse_cholesky.h"

namespace strictmin {
namespace {

constexpr double kQuarter = std::numbers::pi / 2;
using SparseMatrix = Eigen::SparseMatrix<double>;

// a in (-pi/4, pi/4], a congruent to the input modulo a quarter turn.
double wrap_to_quarter(double a) {
  double r = std::remainder(a, kQuarter);
  if (r <= -kQuarter / 2) r += kQuarter;
  return r;
}

// A graph Laplacian sum_e c_e (p_j - p_i)^2 (PSD, constants in its kernel), factored with
// one node held: adding L(0,0) to L(0,0) makes it definite, and for a right-hand side that
// sums to zero the solution still solves L p = b exactly (summing the rows gives p_0 = 0).
class HeldLaplacian {
 public:
  HeldLaplacian(int n, const std::vector<Eigen::Triplet<double>>& edges_ij_c) : HeldLaplacian(laplacian(n, edges_ij_c)) {}
  explicit HeldLaplacian(SparseMatrix L) {
    const double held = L.coeff(0, 0);
    L.coeffRef(0, 0) += held > 0 ? held : 1.0;
    cholesky_.analyze(L);
    if (!cholesky_.factorize(L)) throw InputError("cone field: a Laplacian could not be factorized");
  }
  static SparseMatrix laplacian(int n, const std::vector<Eigen::Triplet<double>>& edges_ij_c) {
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(edges_ij_c.size() * 4);
    for (const auto& e : edges_ij_c) {
      const int i = e.row(), j = e.col();
      const double c = e.value();
      t.emplace_back(i, i, c);
      t.emplace_back(j, j, c);
      t.emplace_back(i, j, -c);
      t.emplace_back(j, i, -c);
    }
    SparseMatrix L(n, n);
    L.setFromTriplets(t.begin(), t.end());
    return L;
  }
  // b is first made to sum to zero.
  Eigen::VectorXd solve(Eigen::VectorXd b) const {
    b.array() -= b.mean();
    return cholesky_.solve(b).col(0);
  }

 private:
  SparseCholesky cholesky_;
};

// The vertex Laplacian C diag(1/w) C^T of the header (edge e joins its two vertices with 1/w_e).
HeldLaplacian vertex_laplacian(const SurfaceGraph& g, const Eigen::VectorXd& w) {
  std::vector<Eigen::Triplet<double>> e;
  e.reserve(g.num_edges());
  for (int k = 0; k < g.num_edges(); ++k) e.emplace_back(g.edges(k, 0), g.edges(k, 1), 1.0 / w(k));
  return HeldLaplacian(g.num_vertices, e);
}

// Per-face field angles, parallel for the connection transport + omega along the dual tree.
Eigen::VectorXd propagate(const SurfaceGraph& g, const FaceFrames& fr, const Eigen::VectorXd& omega,
                          const std::vector<int>& order, const std::vector<int>& parent_edge) {
  Eigen::VectorXd phi = Eigen::VectorXd::Zero(g.num_faces);
  for (size_t k = 1; k < order.size(); ++k) {
    const int h = order[k], e = parent_edge[h];
    const int f = g.edge_faces(e, 0) == h ? g.edge_faces(e, 1) : g.edge_faces(e, 0);
    const double step = fr.transport(e) + omega(e);
    phi(h) = phi(f) + (g.edge_faces(e, 0) == f ? step : -step);
  }
  return phi;
}

// The field's jump across e beyond the connection, modulo quarter turns.
double mismatch(const SurfaceGraph& g, const FaceFrames& fr, const Eigen::VectorXd& omega, const Eigen::VectorXd& phi,
                int e) {
  return wrap_to_quarter(phi(g.edge_faces(e, 1)) - phi(g.edge_faces(e, 0)) - fr.transport(e) - omega(e));
}

// Tree-cotree loops for genus > 0: a spanning tree of the edges the dual tree does not cross;
// each remaining such edge closes a primal loop (edge + tree path). A 1-form equal to r on
// a loop's edges (signed by the direction it runs them) is closed and turns the holonomy of
// the dual loop through that edge (and no other generator's) by r. Returns, on every edge,
// the closed form that removes the generators' mismatches.
Eigen::VectorXd generator_correction(const SurfaceGraph& g, const FaceFrames& fr, const Eigen::VectorXd& omega,
                                     const Eigen::VectorXd& phi, const std::vector<int>& parent_edge) {
  const int V = g.num_vertices, E = g.num_edges();
  std::vector<char> in_dual_tree(E, 0);
  for (int f = 0; f < g.num_faces; ++f)
    if (parent_edge[f] >= 0) in_dual_tree[parent_edge[f]] = 1;
  std::vector<std::vector<int>> cotree_at(V);
  for (int e = 0; e < E; ++e)
    if (!in_dual_tree[e]) {
      cotree_at[g.edges(e, 0)].push_back(e);
      cotree_at[g.edges(e, 1)].push_back(e);
    }
  std::vector<int> up_edge(V, -1), depth(V, -1), queue{0};
  std::vector<char> in_tree(E, 0);
  depth[0] = 0;
  for (size_t k = 0; k < queue.size(); ++k)
    for (int e : cotree_at[queue[k]]) {
      const int v = queue[k], w = g.edges(e, 0) == v ? g.edges(e, 1) : g.edges(e, 0);
      if (depth[w] >= 0) continue;
      depth[w] = depth[v] + 1;
      up_edge[w] = e;
      in_tree[e] = 1;
      queue.push_back(w);
    }
  auto parent = [&](int v) { return g.edges(up_edge[v], 0) == v ? g.edges(up_edge[v], 1) : g.edges(up_edge[v], 0); };
  // +1 when running e from p to its other end goes edges(e,0) -> edges(e,1).
  auto along = [&](int e, int p) { return g.edges(e, 0) == p ? 1.0 : -1.0; };

  Eigen::VectorXd z = Eigen::VectorXd::Zero(E);
  for (int e = 0; e < E; ++e) {
    if (in_dual_tree[e] || in_tree[e]) continue;
    const double r = mismatch(g, fr, omega, phi, e);
    // The loop runs e from a = edges(e,0) to b, then the tree path from b back to a.
    z(e) += r;
    int b = g.edges(e, 1), a = g.edges(e, 0);
    while (depth[b] > depth[a]) { z(up_edge[b]) += r * along(up_edge[b], b); b = parent(b); }
    while (depth[a] > depth[b]) { z(up_edge[a]) -= r * along(up_edge[a], a); a = parent(a); }
    while (a != b) {
      z(up_edge[b]) += r * along(up_edge[b], b);
      b = parent(b);
      z(up_edge[a]) -= r * along(up_edge[a], a);
      a = parent(a);
    }
  }
  return z;
}

// The harmonic representative h = z - D p of a closed form z (D p: p's difference across
// each edge, face 1 minus face 0), smallest in sum_e w_e h_e^2.
Eigen::VectorXd harmonic_part(const SurfaceGraph& g, const Eigen::VectorXd& w, const Eigen::VectorXd& z) {
  std::vector<Eigen::Triplet<double>> edges;
  edges.reserve(g.num_edges());
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(g.num_faces);
  for (int e = 0; e < g.num_edges(); ++e) {
    const int f0 = g.edge_faces(e, 0), f1 = g.edge_faces(e, 1);
    edges.emplace_back(f0, f1, w(e));
    rhs(f1) += w(e) * z(e);
    rhs(f0) -= w(e) * z(e);
  }
  const Eigen::VectorXd p = HeldLaplacian(g.num_faces, edges).solve(rhs);
  Eigen::VectorXd h = z;
  for (int e = 0; e < g.num_edges(); ++e) h(e) -= p(g.edge_faces(e, 1)) - p(g.edge_faces(e, 0));
  return h;
}

Eigen::VectorXd edge_weights(const Mesh& mesh, const SurfaceGraph& g, const FaceFrames& fr) {
  Eigen::VectorXd w(g.num_edges());
  for (int e = 0; e < g.num_edges(); ++e) w(e) = field_edge_weight(mesh, g, fr, e);
  return w;
}

// The right-hand side q pi/2 - K of the potential's equation.
Eigen::VectorXd holonomy_defect(const std::vector<int>& quarters, const Eigen::VectorXd& K) {
  Eigen::VectorXd b(K.size());
  for (Eigen::Index v = 0; v < K.size(); ++v) b(v) = quarters[v] * kQuarter - K(v);
  return b;
}

void check_cone_sum(const SurfaceGraph& g, const std::vector<int>& quarters, const std::string& source) {
  const std::string where = source.empty() ? "cone field" : source;
  if (static_cast<int>(quarters.size()) != g.num_vertices)
    throw InputError(where + ": " + std::to_string(quarters.size()) + " cone indices for " +
                     std::to_string(g.num_vertices) + " vertices");
  long sum = 0;
  for (int q : quarters) sum += q;
  if (sum != 4L * g.euler_characteristic())
    throw InputError(where + ": the cones' indices add up to " + std::to_string(sum) +
                     "/4, but a cross field's add up to the Euler characteristic " +
                     std::to_string(g.euler_characteristic()) + " (Poincare-Hopf)");
}

}  // namespace

void check_cone_indices(const std::vector<int>& quarters, const std::string& where) {
  for (size_t v = 0; v < quarters.size(); ++v)
    if (quarters[v] >= 4 || quarters[v] < -kMostConeQuarters)
      throw InputError(where + ": vertex " + std::to_string(v) + ": the index " + std::to_string(quarters[v]) +
                       "/4 is not a cone's (its total angle 2 pi - q pi/2 must be positive and at most 2 pi + " +
                       std::to_string(kMostConeQuarters) + " quarter turns: -" + std::to_string(kMostConeQuarters) +
                       " <= q <= 3)");
}

CrossField cone_cross_field(const Mesh& mesh, const SurfaceGraph& g, const FaceFrames& fr,
                            const std::vector<int>& quarters, const CrossFieldOptions& options,
                            const std::string& source) {
  std::string why;
  if (!options.is_valid(&why)) throw InputError("cross field options: " + why);
  if (g.has_boundary())  // gparam refuses --cones and --parallel by name first
    throw InputError("cross field: fields from cones take closed surfaces only (the surface has " +
                     std::to_string(g.num_boundary_loops) + " boundary loop(s))");
  if (options.pin_face >= g.num_faces)  // as smoothest_cross_field (it was ignored here)
    throw InputError("cross field: pin_face " + std::to_string(options.pin_face) + " is beyond the mesh's " +
                     std::to_string(g.num_faces) + " faces");
  check_cone_sum(g, quarters, source);
  const Eigen::VectorXd w = edge_weights(mesh, g, fr);
  // 1. The exact part: the potential's rotated gradient sets every vertex's holonomy.
  const Eigen::VectorXd lambda = vertex_laplacian(g, w).solve(holonomy_defect(quarters, angle_defects(mesh, g)));
  Eigen::VectorXd omega(g.num_edges());
  for (int e = 0; e < g.num_edges(); ++e) omega(e) = (lambda(g.edges(e, 1)) - lambda(g.edges(e, 0))) / w(e);
  // 2. The harmonic part: the generators' holonomy to whole quarter turns (genus > 0).
  std::vector<int> parent_edge;
  const std::vector<int> order = dual_spanning_tree(g, parent_edge);
  Eigen::VectorXd phi = propagate(g, fr, omega, order, parent_edge);
  if (g.euler_characteristic() != 2) {
    omega += harmonic_part(g, w, generator_correction(g, fr, omega, phi, parent_edge));
    phi = propagate(g, fr, omega, order, parent_edge);
  }
  // 3. The field, its global rotation pinned.
  CrossField out;
  out.u.resize(g.num_faces);
  for (int f = 0; f < g.num_faces; ++f) out.u(f) = std::polar(1.0, 4.0 * phi(f));
  if (options.pin_face >= 0) pin_field_rotation(out.u, options.pin_face, options.pin_direction, fr);
  out.energy = field_energy(out.u, mesh, g, fr);
  return out;
}

}  // namespace strictmin
