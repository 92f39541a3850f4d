#include "strictmin/tasks/seamless_problem.h"

#include <cmath>

namespace strictmin {
namespace {


void add_targets(const CutGraph& c, Problem& p) {
  for (int f = 0; f < p.num_elements(); ++f) {
    const double a = c.combed(f);
    Eigen::Matrix2d R;  // rot(-a): the combed direction (cos a, sin a) to (1, 0)
    R << std::cos(a), std::sin(a), -std::sin(a), std::cos(a);
    p.set_target(f, R);
  }
}

// Two rows per cut edge: (w0_b - w0_a) - R (w1_b - w1_a) = 0, w0/w1 the wedges on the
// face-0/face-1 sides.
void add_transitions(const Mesh& mesh, const SurfaceGraph& g, const CutGraph& c, Problem& p) {
  std::vector<Eigen::Triplet<double>> t;
  int rows = 0;
  for (int e = 0; e < g.num_edges(); ++e) {
    if (!c.cut[e]) continue;
    const int a = g.edges(e, 0), b = g.edges(e, 1), f0 = g.edge_faces(e, 0), f1 = g.edge_faces(e, 1);
    const int a0 = corner_wedge_of(mesh, c, f0, a), b0 = corner_wedge_of(mesh, c, f0, b);
    const int a1 = corner_wedge_of(mesh, c, f1, a), b1 = corner_wedge_of(mesh, c, f1, b);
    const Eigen::Matrix2d R = quarter_rotation(c.matching[e]);
    for (int r = 0; r < 2; ++r) {
      t.emplace_back(rows, 2 * b0 + r, 1.0);
      t.emplace_back(rows, 2 * a0 + r, -1.0);
      for (int s = 0; s < 2; ++s)
        if (R(r, s) != 0) {
          t.emplace_back(rows, 2 * b1 + s, -R(r, s));
          t.emplace_back(rows, 2 * a1 + s, R(r, s));
        }
      ++rows;
    }
  }
  p.eq_matrix.resize(rows, 2 * p.num_vertices);
  p.eq_matrix.setFromTriplets(t.begin(), t.end());
  p.eq_rhs = Eigen::VectorXd::Zero(rows);
}

// The copies of each vertex relative to its first wedge, by walking its fan across the
// cut: crossing e from its face-0 side to its face-1 side maps uv by rot(-k) (up to t).
void add_copies(const SurfaceGraph& g, const CutGraph& c, Problem& p) {
  p.copy_base.assign(p.num_vertices, 0);
  p.copy_rotation.resize(2 * p.num_vertices, 2);
  for (int v = 0; v < g.num_vertices; ++v) {
    const int begin = g.fan_start[v], m = g.fan_start[v + 1] - begin;
    const int f_first = g.fan_faces[begin];
    const int base = c.corner_wedge(f_first, g.fan_corners[begin]);
    Eigen::Matrix2d R = Eigen::Matrix2d::Identity();
    for (int k = 0; k < m; ++k) {
      const int f = g.fan_faces[begin + k], w = c.corner_wedge(f, g.fan_corners[begin + k]);
      p.copy_base[w] = base;
      p.copy_rotation.middleRows(2 * w, 2) = R;
      const int e = g.face_edges(f, (g.fan_corners[begin + k] + 2) % 3);
      if (c.cut[e]) R = quarter_rotation(g.edge_faces(e, 0) == f ? -c.matching[e] : c.matching[e]) * R;
    }
    // The transitions around an interior v do not close: v holds still (a boundary vertex's
    // fan is open: its copies move together whatever rotation its last one has).
    if (!g.boundary_vertex[v] && !R.isIdentity(1e-12))
      for (int k = 0; k < m; ++k) p.copy_base[c.corner_wedge(g.fan_faces[begin + k], g.fan_corners[begin + k])] = -1;
  }
}

}  // namespace

int corner_wedge_of(const Mesh& mesh, const CutGraph& c, int f, int v) {
  for (int i = 0; i < 3; ++i)
    if (mesh.F(f, i) == v) return c.corner_wedge(f, i);
  return -1;
}

BranchEnds branch_ends(const Mesh& mesh, const SurfaceGraph& g, const CutGraph& c, const SeamBranch& b) {
  BranchEnds ends;
  const int e = b.edges[0], v = b.vertices[0];
  const bool forward = g.edges(e, 0) == v;  // runs as in face 0
  ends.left = corner_wedge_of(mesh, c, g.edge_faces(e, forward ? 0 : 1), v);
  ends.right = corner_wedge_of(mesh, c, g.edge_faces(e, forward ? 1 : 0), v);
  ends.rotation = quarter_rotation(b.quarter_turns);
  return ends;
}

Problem seamless_problem(const Mesh& mesh, const SurfaceGraph& g, const CutGraph& c) {
  Problem p = make_surface_problem(cut_mesh(mesh, c));  // face frames even on a flat surface: the targets'
  add_targets(c, p);
  add_transitions(mesh, g, c, p);
  add_copies(g, c, p);
  p.positions = Eigen::MatrixXd::Zero(p.num_vertices, 2);
  p.fix({Handle{0, Eigen::Vector2d::Zero()}});
  return p;
}

Eigen::MatrixXd branch_translations(const Mesh& mesh, const SurfaceGraph& g, const CutGraph& c,
                                    const Eigen::MatrixXd& X, double* error) {
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(c.branches.size()), 2);
  double worst = 0;
  for (size_t i = 0; i < c.branches.size(); ++i) {
    const SeamBranch& b = c.branches[i];
    const Eigen::Matrix2d R = quarter_rotation(b.quarter_turns);
    std::vector<Eigen::Vector2d> t;
    for (size_t k = 0; k < b.edges.size(); ++k) {
      const int e = b.edges[k];
      const bool forward = g.edges(e, 0) == b.vertices[k];  // runs as in face 0
      const int left = g.edge_faces(e, forward ? 0 : 1), right = g.edge_faces(e, forward ? 1 : 0);
      for (int v : {b.vertices[k], b.vertices[k + 1]})
        t.push_back(X.row(corner_wedge_of(mesh, c, left, v)).transpose() - R * X.row(corner_wedge_of(mesh, c, right, v)).transpose());
    }
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (const auto& x : t) mean += x;
    mean /= static_cast<double>(t.size());
    for (const auto& x : t) worst = std::max(worst, (x - mean).norm());
    T.row(static_cast<Eigen::Index>(i)) = mean.transpose();
  }
  if (error) *error = worst;
  return T;
}

}  // namespace strictmin
