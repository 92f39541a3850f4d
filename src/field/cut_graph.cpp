// Cut graph, combing, matchings and wedges (docs/gparam.md, "The cut").
#include "strictmin/field/cut_graph.h"
#include "strictmin/field/singularities.h"

#include <cmath>
#include <complex>
#include <deque>
#include <numbers>

namespace strictmin {
namespace {

constexpr double kQuarter = std::numbers::pi / 2;

// The dual spanning tree (surface_graph.h), its edges marked in c.tree.
std::vector<int> dual_tree(const SurfaceGraph& g, CutGraph& c, std::vector<int>& parent_edge) {
  const std::vector<int> order = dual_spanning_tree(g, parent_edge);
  c.tree.assign(g.num_edges(), 0);
  for (int f = 0; f < g.num_faces; ++f)
    if (parent_edge[f] >= 0) c.tree[parent_edge[f]] = 1;
  return order;
}

std::vector<std::vector<int>> cut_edges_at(const SurfaceGraph& g, const std::vector<char>& cut) {
  std::vector<std::vector<int>> at(g.num_vertices);
  for (int e = 0; e < g.num_edges(); ++e)
    if (cut[e]) {
      at[g.edges(e, 0)].push_back(e);
      at[g.edges(e, 1)].push_back(e);
    }
  return at;
}

// The interior edges no tree edge crosses, less every dangling branch that ends at a regular
// interior vertex (a branch that reaches the boundary stays: it cuts between boundary loops).
void prune_cut(const SurfaceGraph& g, const std::vector<int>& quarters, CutGraph& c) {
  c.cut.assign(g.num_edges(), 0);
  for (int e = 0; e < g.num_edges(); ++e) c.cut[e] = c.tree[e] || g.is_boundary_edge(e) ? 0 : 1;
  auto prunable = [&](int v) { return quarters[v] == 0 && !g.boundary_vertex[v]; };
  const auto at = cut_edges_at(g, c.cut);
  std::vector<int> degree(g.num_vertices);
  std::deque<int> queue;
  for (int v = 0; v < g.num_vertices; ++v) {
    degree[v] = static_cast<int>(at[v].size());
    if (degree[v] == 1 && prunable(v)) queue.push_back(v);
  }
  while (!queue.empty()) {
    const int v = queue.front();
    queue.pop_front();
    if (degree[v] != 1) continue;
    for (int e : at[v])
      if (c.cut[e]) {
        c.cut[e] = 0;
        const int w = g.edges(e, 0) == v ? g.edges(e, 1) : g.edges(e, 0);
        --degree[v];
        if (--degree[w] == 1 && prunable(w)) queue.push_back(w);
        break;
      }
  }
  c.num_cut_edges = 0;
  for (int e = 0; e < g.num_edges(); ++e) c.num_cut_edges += c.cut[e];
}

// Each face's direction closest to its tree parent's transported direction: the parent's
// combed direction moved across the edge and turned by the field's turn there
// (field_edge_turns, the turns the indices add up), so that the matchings, the combed turns
// less those same turns, agree with the indices even where a turn is pi/4 to rounding (a turn
// measured again here could round to the other side of pi/4 and put a quarter turn on an
// uncut edge).
void comb(const Mesh& mesh, const SurfaceGraph& g, const FaceFrames& fr, const Eigen::VectorXcd& u,
          const std::vector<int>& order, const std::vector<int>& parent_edge, CutGraph& c) {
  const std::vector<double> field_turns = field_edge_turns(mesh, g, fr, u);
  auto turn_from = [&](int e, int f) { return g.edge_faces(e, 0) == f ? field_turns[e] : -field_turns[e]; };
  c.combed.resize(g.num_faces);
  c.combed(order[0]) = std::arg(u(order[0])) / 4.0;
  for (size_t k = 1; k < order.size(); ++k) {
    const int h = order[k], e = parent_edge[h];
    const int f = g.edge_faces(e, 0) == h ? g.edge_faces(e, 1) : g.edge_faces(e, 0);
    c.combed(h) = c.combed(f) + fr.transport_from(g, e, f) + turn_from(e, f);
  }
  c.matching.assign(g.num_edges(), 0);
  for (int e = 0; e < g.num_edges(); ++e) {
    if (g.is_boundary_edge(e)) continue;
    const double turn = c.combed(g.edge_faces(e, 1)) - c.combed(g.edge_faces(e, 0)) - fr.transport(e);
    const long k = std::lround((turn - field_turns[e]) / kQuarter);
    c.matching[e] = static_cast<int>(((k % 4) + 4) % 4);
  }
}

// Wedges: the corners around each vertex between two consecutive cut edges of its fan (or
// between the boundary and a cut edge: a boundary vertex's fan is open and starts a wedge).
void wedges(const SurfaceGraph& g, CutGraph& c) {
  c.corner_wedge.resize(g.num_faces, 3);
  c.wedge_vertex.clear();
  for (int v = 0; v < g.num_vertices; ++v) {
    const int begin = g.fan_start[v], m = g.fan_start[v + 1] - begin;
    auto crossed = [&](int k) { return g.fan_edge(begin + k); };  // from fan face k to fan face k + 1
    int start = 0;
    for (int k = 0; k < m && !g.boundary_vertex[v]; ++k)
      if (c.cut[crossed(k)]) {
        start = (k + 1) % m;
        break;
      }
    c.wedge_vertex.push_back(v);
    for (int s = 0; s < m; ++s) {
      const int k = (start + s) % m;
      c.corner_wedge(g.fan_faces[begin + k], g.fan_corners[begin + k]) = c.num_wedges() - 1;
      if (s + 1 < m && c.cut[crossed(k)]) c.wedge_vertex.push_back(v);
    }
  }
}

// Splits the cut into branches between nodes (singular vertices, cut degree != 2, boundary
// vertices: the two sides of a seam through the boundary are not one transition).
void branches(const SurfaceGraph& g, const std::vector<int>& quarters, CutGraph& c) {
  const auto at = cut_edges_at(g, c.cut);
  std::vector<char> node(g.num_vertices, 0), used(g.num_edges(), 0);
  for (int v = 0; v < g.num_vertices; ++v)
    node[v] = !at[v].empty() && (at[v].size() != 2 || quarters[v] != 0 || g.boundary_vertex[v]);
  auto walk = [&](int v, int e) {
    SeamBranch b;
    b.vertices.push_back(v);
    const int a = v;
    b.quarter_turns = g.edges(e, 0) == v ? c.matching[e] : (4 - c.matching[e]) % 4;
    while (true) {
      used[e] = 1;
      b.edges.push_back(e);
      v = g.edges(e, 0) == v ? g.edges(e, 1) : g.edges(e, 0);
      b.vertices.push_back(v);
      if (node[v] || v == a) break;
      int next = -1;
      for (int f : at[v])
        if (!used[f]) next = f;
      if (next < 0) break;
      e = next;
    }
    c.branches.push_back(std::move(b));
  };
  c.branches.clear();
  for (int v = 0; v < g.num_vertices; ++v)
    if (node[v])
      for (int e : at[v])
        if (!used[e]) walk(v, e);
  for (int e = 0; e < g.num_edges(); ++e)  // loops without a node
    if (c.cut[e] && !used[e]) {
      node[g.edges(e, 0)] = 1;
      walk(g.edges(e, 0), e);
    }
}

}  // namespace

Eigen::Matrix2d quarter_rotation(int k) {
  k = ((k % 4) + 4) % 4;
  const double cs[4] = {1, 0, -1, 0}, sn[4] = {0, 1, 0, -1};
  Eigen::Matrix2d R;
  R << cs[k], -sn[k], sn[k], cs[k];
  return R;
}

CutGraph cut_graph(const Mesh& mesh, const SurfaceGraph& g, const FaceFrames& fr, const Eigen::VectorXcd& u,
                   const std::vector<int>& quarters) {
  CutGraph c;
  std::vector<int> parent_edge;
  const std::vector<int> order = dual_tree(g, c, parent_edge);
  prune_cut(g, quarters, c);
  comb(mesh, g, fr, u, order, parent_edge, c);
  wedges(g, c);
  branches(g, quarters, c);
  return c;
}

Mesh cut_mesh(const Mesh& mesh, const CutGraph& c) {
  Mesh out;
  out.V.resize(c.num_wedges(), mesh.V.cols());
  for (int w = 0; w < c.num_wedges(); ++w) out.V.row(w) = mesh.V.row(c.wedge_vertex[w]);
  out.F = c.corner_wedge;
  return out;
}

}  // namespace strictmin
