// The node relations of the integer-grid rounding's values (src/tasks/node_relations.h).
#include "tasks/node_relations.h"

#include <map>
#include <stdexcept>

namespace strictmin {
namespace {

using Matrix2i = Eigen::Matrix2i;

Matrix2i integer_rotation(int quarter_turns) { return quarter_rotation(quarter_turns).cast<int>(); }

// Per cut edge: its branch and the branch's left face there (the face in which the edge runs
// in the branch's direction, as branch_ends and branch_translations read it).
struct EdgeBranches {
  std::vector<int> branch, left_face;
};

EdgeBranches edge_branches(const SurfaceGraph& g, const CutGraph& c) {
  EdgeBranches out;
  out.branch.assign(static_cast<std::size_t>(g.num_edges()), -1);
  out.left_face.assign(static_cast<std::size_t>(g.num_edges()), -1);
  for (std::size_t b = 0; b < c.branches.size(); ++b) {
    const SeamBranch& s = c.branches[b];
    for (std::size_t k = 0; k < s.edges.size(); ++k) {
      const int e = s.edges[k];
      const bool forward = g.edges(e, 0) == s.vertices[k];
      out.branch[static_cast<std::size_t>(e)] = static_cast<int>(b);
      out.left_face[static_cast<std::size_t>(e)] = g.edge_faces(e, forward ? 0 : 1);
    }
  }
  return out;
}

// f_0 = P f_0 + sum_b Q_b t_b around v (the header), composed crossing by crossing.
struct Walk {
  Matrix2i P = Matrix2i::Identity();
  std::map<int, Matrix2i> Q;  // per branch crossed
  bool crossed = false;

  void apply(const Matrix2i& R) {  // f -> R f for everything so far
    P = R * P;
    for (auto& [b, q] : Q) q = R * q;
  }
  void cross(int branch, const Matrix2i& R, bool from_left) {
    crossed = true;
    Matrix2i& q = Q.try_emplace(branch, Matrix2i::Zero()).first->second;
    if (from_left) {  // f_next = R^T f_prev - R^T t
      apply(R.transpose());
      q -= R.transpose();
    } else {  // f_next = R f_prev + t
      apply(R);
      q += Matrix2i::Identity();
    }
  }
  bool trivial() const {
    if (!P.isIdentity()) return false;
    for (const auto& [b, q] : Q)
      if (!q.isZero()) return false;
    return true;
  }
};

Walk walk_around(const SurfaceGraph& g, const CutGraph& c, const EdgeBranches& eb, int v) {
  Walk walk;
  for (int k = g.fan_start[v]; k < g.fan_start[v + 1]; ++k) {
    const int f = g.fan_faces[k];
    const int e = g.face_edges(f, (g.fan_corners[k] + 2) % 3);  // to the next fan face
    if (!c.cut[e]) continue;
    const int b = eb.branch[static_cast<std::size_t>(e)];
    walk.cross(b, integer_rotation(c.branches[static_cast<std::size_t>(b)].quarter_turns),
               eb.left_face[static_cast<std::size_t>(e)] == f);
  }
  return walk;
}

}  // namespace

Eigen::VectorXd NodeRelations::residual(const Eigen::VectorXd& values) const {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(matrix.rows);
  for (int col = 0; col < matrix.cols(); ++col)
    for (int r = 0; r < matrix.rows; ++r)
      if (sgn(matrix(r, col)) != 0) out(r) += matrix(r, col).get_d() * values(col);
  return out;
}

NodeRelations node_relations(const SurfaceGraph& g, const CutGraph& c, const std::vector<Singularity>& singular) {
  NodeRelations out;
  out.num_singular = static_cast<int>(singular.size());
  out.num_branches = static_cast<int>(c.branches.size());
  std::vector<int> singular_of(static_cast<std::size_t>(g.num_vertices), -1);
  for (std::size_t i = 0; i < singular.size(); ++i) singular_of[static_cast<std::size_t>(singular[i].vertex)] = static_cast<int>(i);
  const EdgeBranches eb = edge_branches(g, c);
  // (I - P) f_0 - sum_b Q_b t_b = 0 per vertex, gathered as dense 2-row blocks.
  std::vector<std::vector<std::pair<int, Matrix2i>>> rows;  // per relation: (value, coefficient)
  for (int v = 0; v < g.num_vertices; ++v) {
    const Walk walk = walk_around(g, c, eb, v);
    if (!walk.crossed || walk.trivial()) continue;
    std::vector<std::pair<int, Matrix2i>> terms;
    const int s = singular_of[static_cast<std::size_t>(v)];
    if (s >= 0) {
      terms.emplace_back(out.singular_value(s), Matrix2i(Matrix2i::Identity() - walk.P));
    } else if (!walk.P.isIdentity()) {
      throw std::logic_error("node_relations: the transitions around a regular vertex do not close");
    }
    for (const auto& [b, q] : walk.Q) terms.emplace_back(out.branch_value(b), Matrix2i(-q));
    rows.push_back(std::move(terms));
    out.vertex.push_back(v);
  }
  out.matrix = IntegerMatrix(2 * static_cast<int>(rows.size()), 2 * out.num_values());
  for (std::size_t k = 0; k < rows.size(); ++k)
    for (const auto& [value, m] : rows[k])
      for (int r = 0; r < 2; ++r)
        for (int s = 0; s < 2; ++s) out.matrix(2 * static_cast<int>(k) + r, 2 * value + s) += m(r, s);
  return out;
}

}  // namespace strictmin
