// Quad meshes from integer-grid maps (include/strictmin/tasks/quad_extraction.h).
#include "strictmin/tasks/quad_extraction.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <Eigen/Geometry>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

#include "mesh/union_find.h"
#include "strictmin/field/surface_graph.h"
#include "strictmin/io/input_error.h"
#include "strictmin/param/topology.h"
#include "strictmin/solvers/interrupt.h"
#include "tasks/quad_hole_filling.h"
#include "tasks/square_flood.h"
#include "tasks/uv_transitions.h"

namespace strictmin {
namespace {

std::string prefix(const std::string& source) { return source.empty() ? std::string("quads: ") : source + ": "; }

// More unit squares under the triangles of positive UV area than this, more grid cells under
// their UV bounding boxes, or UVs further from 0, are refused: the UVs are then most likely
// not in grid units (and the work would not end: beyond kMaxUv a unit step is lost in a
// double's digits). The extraction holds about 0.55 KB a square at its peak (1.55 million
// squares: 0.83 GB, 16 s), so 1e7 squares take about 5.5 GB.
constexpr double kMaxCells = 4e8, kMaxUv = 1e9;
constexpr double kMaxSquares = kMaxQuadExtractionSquares;

// The work the extraction would do, added up over the triangles: the UV area of those of
// positive area (the squares flooded) and the grid cells under each one's UV bounding box
// (the enumeration of centres visits at most these), and the UVs' largest magnitude.
struct UvExtent {
  double positive_area = 0, cells = 0, max_uv = 0;
};

UvExtent uv_extent(const Mesh& map) {
  UvExtent x;
  for (int f = 0; f < map.num_elements(); ++f) {
    Eigen::Vector2d lo = Eigen::Vector2d::Constant(INFINITY), hi = -lo;
    for (int i = 0; i < 3; ++i) lo = lo.cwiseMin(corner_uv(map, f, i)), hi = hi.cwiseMax(corner_uv(map, f, i));
    x.positive_area += std::max(0.0, doubled_uv_area(map, f) / 2);
    x.cells += (hi.x() - lo.x() + 1) * (hi.y() - lo.y() + 1);
  }
  if (map.UV.size() > 0) x.max_uv = map.UV.cwiseAbs().maxCoeff();
  return x;
}

}  // namespace

double positive_uv_area(const Mesh& map) { return uv_extent(map).positive_area; }

namespace {

void check_extent(const Mesh& map, const std::string& source) {
  const UvExtent x = uv_extent(map);
  if (x.positive_area > kMaxSquares || x.cells > kMaxCells || x.max_uv > kMaxUv)
    throw InputError(prefix(source) + "the map's triangles cover " + std::to_string(std::llround(x.positive_area)) +
                     " unit squares and their bounding boxes " + std::to_string(std::llround(x.cells)) +
                     " grid cells, its UVs reach " + std::to_string(std::llround(x.max_uv)) +
                     " (at most 1e7, 4e8 and 1e9): are the UVs in grid units?");
}

void check_map(const Mesh& map, const std::string& source) {
  if (map.element_type() != ElementType::Triangle || map.dim() != 3)
    throw InputError(prefix(source) + "quad extraction needs a triangle surface in 3D");
  if (!map.has_uv())
    throw InputError(prefix(source) + "the mesh has no per-corner UVs (OBJ vt and f v/vt): nothing to extract");
  if (!map.UV.allFinite()) throw InputError(prefix(source) + "the UVs are not all finite");
  for (int f = 0; f < map.num_elements(); ++f)
    for (int i = 0; i < 3; ++i)
      if (map.FUV(f, i) < 0 || map.FUV(f, i) >= map.UV.rows())
        throw InputError(prefix(source) + "face " + std::to_string(f) + " (0-based) has a UV index out of range");
  const SurfaceTopology t = surface_topology(map);
  if (t.components != 1 && t.non_manifold_edge < 0 && t.non_manifold_vertex < 0)
    throw InputError(prefix(source) + "the mesh has " + std::to_string(t.components) +
                     " connected components; quad extraction takes one closed surface (extract each on its own)");
  if (!t.boundary_loops.empty())
    throw InputError(prefix(source) + "the surface has " + std::to_string(t.boundary_loops.size()) +
                     " boundary loop(s) (first at vertex " + std::to_string(t.boundary_loops.front().front()) +
                     ", 0-based); quad extraction takes closed surfaces");
}

struct Square {
  std::array<SquareCorner, 4> corners;
};

struct Squares {
  std::vector<Square> quads;
  int touching_flips = 0, wrapped = 0, not_covered_once = 0, overlapping = 0, inverted = 0;
};

Eigen::Vector3d corner_position(const Mesh& map, const SquareCorner& c) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i) p += c.barycentric(i) * map.V.row(map.F(c.face, i)).transpose();
  return p;
}

Eigen::Vector3d face_normal(const Mesh& map, int f) {
  const Eigen::Vector3d a = map.V.row(map.F(f, 0)).transpose(), b = map.V.row(map.F(f, 1)).transpose(),
                        c = map.V.row(map.F(f, 2)).transpose();
  return (b - a).cross(c - a).normalized();
}

// Drops the squares whose quad faces against the surface: its normal (the cross product of
// its diagonals) has a negative dot product with the sum of the unit normals of the triangles
// holding its corners. Such a square took a corner from another layer of a fold near a cone
// (its flood saw no flipped triangle), and overlaps its neighbours.
void drop_inverted_squares(const Mesh& map, Squares& squares) {
  size_t kept = 0;  // compacted in place: a copy would double the extraction's peak memory
  for (size_t i = 0; i < squares.quads.size(); ++i) {
    const Square& s = squares.quads[i];
    std::array<Eigen::Vector3d, 4> p;
    Eigen::Vector3d surface = Eigen::Vector3d::Zero();
    for (int k = 0; k < 4; ++k) {
      p[k] = corner_position(map, s.corners[k]);
      surface += face_normal(map, s.corners[k].face);
    }
    if ((p[2] - p[0]).cross(p[3] - p[1]).dot(surface) < 0)
      ++squares.inverted;
    else
      squares.quads[kept++] = s;
  }
  squares.quads.resize(kept);
}

// The half-integer points (square centres) in the closed UV triangle of face f, column by
// column (x = i + 1/2): the work is the columns the face spans and the centres it holds,
// however thin the face.
std::vector<Eigen::Vector2d> centres_in_face(const Mesh& map, int f, double tolerance) {
  const std::array<Eigen::Vector2d, 3> t = {corner_uv(map, f, 0), corner_uv(map, f, 1), corner_uv(map, f, 2)};
  const double x_lo = std::min({t[0].x(), t[1].x(), t[2].x()}), x_hi = std::max({t[0].x(), t[1].x(), t[2].x()});
  std::vector<Eigen::Vector2d> centres;
  for (double i = std::ceil(x_lo - 0.5 - tolerance); i <= std::floor(x_hi - 0.5 + tolerance); ++i) {
    const double x = i + 0.5;
    double y_lo = INFINITY, y_hi = -INFINITY;  // the face's y range on the line x (within tolerance)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d a = t[k], b = t[(k + 1) % 3];
      const double ax = std::min(a.x(), b.x()) - tolerance, bx = std::max(a.x(), b.x()) + tolerance;
      if (x < ax || x > bx) continue;
      const double s = b.x() != a.x() ? std::clamp((x - a.x()) / (b.x() - a.x()), 0.0, 1.0) : 0.0;
      const double y = a.y() + s * (b.y() - a.y());
      y_lo = std::min({y_lo, y, b.x() == a.x() ? std::min(a.y(), b.y()) : y});
      y_hi = std::max({y_hi, y, b.x() == a.x() ? std::max(a.y(), b.y()) : y});
    }
    for (double j = std::ceil(y_lo - 0.5 - tolerance); j <= std::floor(y_hi - 0.5 + tolerance); ++j)
      if (uv_face_contains(map, f, {x, j + 0.5}, tolerance)) centres.emplace_back(x, j + 0.5);
  }
  return centres;
}

// Every unit square, flooded once: started from each face of positive UV area at each
// half-integer centre it holds, unless an earlier flood already passed that centre there.
Squares flood_every_square(const Mesh& map, const SurfaceGraph& graph, const std::vector<UvTransition>& transitions,
                           double tolerance) {
  Squares out;
  // About as many squares as the positive UV area (the vector's doubling would hold up to
  // three times as many at its peak).
  out.quads.reserve(static_cast<size_t>(uv_extent(map).positive_area * 1.02) + 16);
  SquareFlooder flooder(map, graph, transitions, tolerance);
  std::unordered_set<SurfacePointKey, SurfacePointKeyHash> started;  // (face, 2 x centre)
  started.reserve(out.quads.capacity() + out.quads.capacity() / 4);
  const auto start_key = [](int f, const Eigen::Vector2d& c) {
    return SurfacePointKey{SurfacePointKey::Face, f, std::llround(2 * c.x()), std::llround(2 * c.y())};
  };
  for (int f = 0; f < graph.num_faces; ++f) {
    if (!(doubled_uv_area(map, f) > 0)) continue;
    check_interrupt();  // solvers/interrupt.h: once per face (Ctrl-C, SIGTERM, Python's KeyboardInterrupt)
    for (const Eigen::Vector2d& c : centres_in_face(map, f, tolerance)) {
      check_interrupt();
      if (started.count(start_key(f, c))) continue;
      const SquareFlood s = flooder.flood(f, c);
      for (const auto& [g, centre] : s.centres) started.insert(start_key(g, centre));
      switch (s.outcome) {
        case SquareFlood::Outcome::Quad: out.quads.push_back({s.corners}); break;
        case SquareFlood::Outcome::TouchesFlip: ++out.touching_flips; break;
        case SquareFlood::Outcome::Wraps: ++out.wrapped; break;
        case SquareFlood::Outcome::NotCoveredOnce: ++out.not_covered_once; break;
      }
    }
  }
  return out;
}

// Per corner id, the quads having it (those `keep` marks, or all): the quads of corner v are
// at[start[v]] .. at[start[v + 1] - 1], in order.
struct QuadsAtCorners {
  std::vector<int> start, at;
};

QuadsAtCorners quads_at_corners(const std::vector<std::array<int, 4>>& quads, int num_corners,
                                const std::vector<char>* keep = nullptr) {
  QuadsAtCorners c;
  c.start.assign(static_cast<size_t>(num_corners) + 1, 0);
  for (size_t i = 0; i < quads.size(); ++i)
    if (!keep || (*keep)[i])
      for (int v : quads[i]) ++c.start[static_cast<size_t>(v) + 1];
  for (size_t v = 0; v + 1 < c.start.size(); ++v) c.start[v + 1] += c.start[v];
  c.at.resize(static_cast<size_t>(c.start.back()));
  std::vector<int> filled(c.start.begin(), c.start.end() - 1);
  for (size_t i = 0; i < quads.size(); ++i)
    if (!keep || (*keep)[i])
      for (int v : quads[i]) c.at[static_cast<size_t>(filled[static_cast<size_t>(v)]++)] = static_cast<int>(i);
  return c;
}

// One id per surface point (SquareCorner::key), per square its four corners' ids.
std::vector<std::array<int, 4>> corner_ids(const std::vector<Square>& squares) {
  std::unordered_map<SurfacePointKey, int, SurfacePointKeyHash> id_of;
  id_of.reserve(squares.size() + squares.size() / 4);  // about one surface point per square
  std::vector<std::array<int, 4>> ids(squares.size());
  for (size_t i = 0; i < squares.size(); ++i)
    for (int k = 0; k < 4; ++k)
      ids[i][k] = id_of.emplace(squares[i].corners[k].key, static_cast<int>(id_of.size())).first->second;
  return ids;
}

// Whether quads a and b (corner ids) share more than one side's worth of corners: three or
// four corners, or two that are not a side of both (a diagonal of one of them).
bool share_more_than_a_side(const std::array<int, 4>& a, const std::array<int, 4>& b) {
  std::array<int, 4> at_b{};  // per corner of a: its place in b (-1: none)
  int shared = 0;
  for (int i = 0; i < 4; ++i) {
    at_b[i] = static_cast<int>(std::find(b.begin(), b.end(), a[i]) - b.begin());
    if (at_b[i] == 4) at_b[i] = -1;
    shared += at_b[i] >= 0;
  }
  if (shared <= 1) return false;
  if (shared > 2) return true;
  for (int i = 0; i < 4; ++i)
    if (at_b[i] >= 0 && at_b[(i + 1) % 4] >= 0) return std::abs(at_b[i] - at_b[(i + 1) % 4]) % 2 == 0;  // not adjacent in b
  return true;  // the two are opposite corners of a
}

// Drops the squares that share a directed edge with another square (both run along it the
// same way: they overlap, as next to a fold of the map, where the surface is covered twice
// by triangles that are not flipped), or share more than a side's corners with one (three
// corners, or a diagonal: folded onto each other), and counts them in `overlapping`. A square
// found twice (its centre on an edge, so started twice) is kept once.
void drop_overlapping_squares(Squares& squares) {
  // Arrays rather than node-based maps: at a million squares these hold the extraction's peak
  // memory (docs/gparam.md, "Quad meshes").
  const std::vector<std::array<int, 4>> ids = corner_ids(squares.quads);
  const size_t n = ids.size();
  std::vector<char> keep(n, 1);
  {  // a square found twice (the same corners from the same one on) is kept once, the first
    std::vector<std::pair<std::array<int, 4>, int>> canonical(n);
    for (size_t i = 0; i < n; ++i) {
      canonical[i] = {ids[i], static_cast<int>(i)};
      std::rotate(canonical[i].first.begin(), std::min_element(canonical[i].first.begin(), canonical[i].first.end()),
                  canonical[i].first.end());
    }
    std::sort(canonical.begin(), canonical.end());
    for (size_t i = 1; i < n; ++i)
      if (canonical[i].first == canonical[i - 1].first) keep[static_cast<size_t>(canonical[i].second)] = 0;
  }
  std::vector<std::uint64_t> edges;  // the kept squares' directed edges, sorted
  int num_ids = 0;
  for (size_t i = 0; i < n; ++i)
    for (int k = 0; k < 4; ++k) {
      num_ids = std::max(num_ids, ids[i][k] + 1);
      if (keep[i]) edges.push_back(directed_edge(ids[i][k], ids[i][(k + 1) % 4]));
    }
  std::sort(edges.begin(), edges.end());
  const auto runs_twice = [&](std::uint64_t e) {
    const auto range = std::equal_range(edges.begin(), edges.end(), e);
    return range.second - range.first > 1;
  };
  const QuadsAtCorners around = quads_at_corners(ids, num_ids, &keep);
  std::vector<char> overlaps(n, 0);
  for (size_t i = 0; i < n; ++i) {
    if (!keep[i]) continue;
    for (int k = 0; k < 4 && !overlaps[i]; ++k) {
      overlaps[i] = runs_twice(directed_edge(ids[i][k], ids[i][(k + 1) % 4]));
      const size_t v = static_cast<size_t>(ids[i][k]);
      for (int a = around.start[v]; a < around.start[v + 1] && !overlaps[i]; ++a) {
        const size_t j = static_cast<size_t>(around.at[static_cast<size_t>(a)]);
        overlaps[i] = j != i && share_more_than_a_side(ids[i], ids[j]);
      }
    }
  }
  size_t kept = 0;
  for (size_t i = 0; i < n; ++i) {
    if (!keep[i]) continue;
    if (overlaps[i])
      ++squares.overlapping;
    else
      squares.quads[kept++] = squares.quads[i];
  }
  squares.quads.resize(kept);
}

// One vertex per surface point, one row of UV per (vertex, integer UV) pair.
QuadMesh assemble(const Mesh& map, const std::vector<Square>& squares, std::vector<SurfacePointKey>& keys) {
  QuadMesh q;
  const int m = static_cast<int>(squares.size());
  q.Q.resize(m, 4);
  q.QUV.resize(m, 4);
  std::vector<const SquareCorner*> first_seen;  // per vertex: the corner that made it
  std::vector<const SquareCorner*> uv_first_seen;  // per UV row: the same
  {  // the maps are freed before the vertices' rows are made (the extraction's peak memory)
    std::unordered_map<SurfacePointKey, int, SurfacePointKeyHash> vertex_of, uv_of;
    vertex_of.reserve(squares.size() + squares.size() / 4);
    uv_of.reserve(squares.size() + squares.size() / 4);
    for (int i = 0; i < m; ++i)
      for (int k = 0; k < 4; ++k) {
        const SquareCorner& c = squares[static_cast<size_t>(i)].corners[k];
        const auto [it, added] = vertex_of.emplace(c.key, static_cast<int>(first_seen.size()));
        if (added) {
          first_seen.push_back(&c);
          keys.push_back(c.key);
        }
        q.Q(i, k) = it->second;
        const SurfacePointKey uv_key{SurfacePointKey::Vertex, it->second, std::llround(c.uv.x()), std::llround(c.uv.y())};
        const auto [jt, uv_added] = uv_of.emplace(uv_key, static_cast<int>(uv_first_seen.size()));
        if (uv_added) uv_first_seen.push_back(&c);
        q.QUV(i, k) = jt->second;
      }
  }
  const int n = static_cast<int>(first_seen.size());
  q.V.resize(n, 3);
  q.vertex_face.resize(n);
  q.vertex_barycentric.resize(n, 3);
  for (int i = 0; i < n; ++i) {
    const SquareCorner& c = *first_seen[static_cast<size_t>(i)];
    q.V.row(i) = corner_position(map, c).transpose();
    q.vertex_face(i) = c.face;
    q.vertex_barycentric.row(i) = c.barycentric.transpose();
  }
  q.UV.resize(static_cast<int>(uv_first_seen.size()), 2);
  for (size_t i = 0; i < uv_first_seen.size(); ++i) q.UV.row(static_cast<int>(i)) = uv_first_seen[i]->uv.transpose();
  return q;
}

// The quads around each vertex, grouped into fans (joined through the quad edges at the
// vertex): several fans at a vertex are quads that touch there alone, as across a pinched hole.
struct VertexFans {
  std::vector<int> quad;  // per vertex, its quads (CSR by start)
  std::vector<int> fan;   // the fan of each, 0 .. fans - 1 in order of first appearance
  std::vector<int> start, fans;
};

VertexFans vertex_fans(const QuadMesh& q) {
  std::vector<std::array<int, 4>> quads(static_cast<size_t>(q.num_quads()));
  for (int i = 0; i < q.num_quads(); ++i)
    for (int k = 0; k < 4; ++k) quads[static_cast<size_t>(i)][static_cast<size_t>(k)] = q.Q(i, k);
  const QuadsAtCorners at = quads_at_corners(quads, q.num_vertices());
  VertexFans out;
  out.quad = at.at;
  out.start = at.start;
  out.fan.assign(at.at.size(), 0);
  out.fans.assign(static_cast<size_t>(q.num_vertices()), 0);
  for (int v = 0; v < q.num_vertices(); ++v) {
    const int first = at.start[static_cast<size_t>(v)];
    const std::vector<int> around(at.at.begin() + first, at.at.begin() + at.start[static_cast<size_t>(v) + 1]);
    UnionFind fans(static_cast<int>(around.size()));
    // Per neighbour w of v along a quad edge: the first quad seen with the edge v-w.
    std::unordered_map<int, int> first_with;
    for (size_t a = 0; a < around.size(); ++a) {
      const int i = around[a];
      int k = 0;
      while (q.Q(i, k) != v) ++k;
      for (int w : {q.Q(i, (k + 1) % 4), q.Q(i, (k + 3) % 4)}) {
        const auto [it, added] = first_with.emplace(w, static_cast<int>(a));
        if (!added) fans.unite(it->second, static_cast<int>(a));
      }
    }
    std::unordered_map<int, int> fan_of_root;
    for (size_t a = 0; a < around.size(); ++a) {
      const auto [it, added] = fan_of_root.emplace(fans.find(static_cast<int>(a)), static_cast<int>(fan_of_root.size()));
      out.fan[static_cast<size_t>(first) + a] = it->second;
    }
    out.fans[static_cast<size_t>(v)] = static_cast<int>(fan_of_root.size());
  }
  return out;
}

int count_non_manifold_vertices(const QuadMesh& q) {
  const VertexFans f = vertex_fans(q);
  return static_cast<int>(std::count_if(f.fans.begin(), f.fans.end(), [](int n) { return n > 1; }));
}

// Gives each fan after the first at a vertex its own copy of the vertex (the same position
// and surface point), so that a quad mesh with holes pinched at a vertex is a manifold with
// boundary. Returns the copies added.
int split_pinched_vertices(QuadMesh& q) {
  const VertexFans f = vertex_fans(q);
  const int n = q.num_vertices();
  std::vector<int> copy_of;  // the original of each copy
  for (int v = 0; v < n; ++v) {
    if (f.fans[static_cast<size_t>(v)] < 2) continue;
    const int first_copy = n + static_cast<int>(copy_of.size());
    for (int k = 1; k < f.fans[static_cast<size_t>(v)]; ++k) copy_of.push_back(v);
    for (int a = f.start[static_cast<size_t>(v)]; a < f.start[static_cast<size_t>(v) + 1]; ++a) {
      const int fan = f.fan[static_cast<size_t>(a)];
      if (fan == 0) continue;
      const int i = f.quad[static_cast<size_t>(a)];
      for (int k = 0; k < 4; ++k)
        if (q.Q(i, k) == v) q.Q(i, k) = first_copy + fan - 1;
    }
  }
  if (copy_of.empty()) return 0;
  const int total = n + static_cast<int>(copy_of.size());
  q.V.conservativeResize(total, Eigen::NoChange);
  q.vertex_face.conservativeResize(total);
  q.vertex_barycentric.conservativeResize(total, Eigen::NoChange);
  for (size_t c = 0; c < copy_of.size(); ++c) {
    const int row = n + static_cast<int>(c);
    q.V.row(row) = q.V.row(copy_of[c]);
    q.vertex_face(row) = q.vertex_face(copy_of[c]);
    q.vertex_barycentric.row(row) = q.vertex_barycentric.row(copy_of[c]);
  }
  return static_cast<int>(copy_of.size());
}

// Edges, boundary, manifoldness, holes, Euler characteristic and valences of the quad mesh.
void check_topology(QuadExtraction& x) {
  const QuadMesh& q = x.mesh;
  std::vector<std::uint64_t> directed;  // sorted, with repeats (a map's nodes cost 5 times the memory)
  directed.reserve(4 * static_cast<size_t>(q.num_quads()));
  std::vector<int> valence(q.num_vertices(), 0);
  for (int i = 0; i < q.num_quads(); ++i)
    for (int k = 0; k < 4; ++k) {
      directed.push_back(directed_edge(q.Q(i, k), q.Q(i, (k + 1) % 4)));
      ++valence[q.Q(i, k)];
    }
  std::sort(directed.begin(), directed.end());
  UnionFind boundary(q.num_vertices());
  std::vector<char> on_boundary(q.num_vertices(), 0);
  int undirected_twice = 0;
  for (size_t first = 0, next = 0; first < directed.size(); first = next) {
    while (next < directed.size() && directed[next] == directed[first]) ++next;
    const std::uint64_t key = directed[first];
    const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
    if (next - first > 1) ++x.non_manifold_edges;
    if (std::binary_search(directed.begin(), directed.end(), directed_edge(b, a))) {
      ++undirected_twice;
      continue;
    }
    ++x.boundary_edges;
    boundary.unite(a, b);
    on_boundary[a] = on_boundary[b] = 1;
  }
  x.edges = undirected_twice / 2 + x.boundary_edges;
  x.non_manifold_vertices = count_non_manifold_vertices(q);
  for (int v = 0; v < q.num_vertices(); ++v)
    if (on_boundary[v] && boundary.find(v) == v) ++x.holes;
  for (int v : valence) ++x.valences[v];
  x.euler_characteristic = q.num_vertices() - x.edges + q.num_quads();
}

}  // namespace

QuadQuality quad_quality(const QuadMesh& q) {
  QuadQuality r;
  if (q.num_quads() == 0) return r;
  r.min_angle_deg = r.min_scaled_jacobian = r.min_side = INFINITY;
  r.max_angle_deg = r.max_side = -INFINITY;
  double total_side = 0;
  for (int i = 0; i < q.num_quads(); ++i) {
    Eigen::Vector3d p[4];
    for (int k = 0; k < 4; ++k) p[k] = q.V.row(q.Q(i, k)).transpose();
    const Eigen::Vector3d n = (p[2] - p[0]).cross(p[3] - p[1]);
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d a = p[(k + 1) % 4] - p[k], b = p[(k + 3) % 4] - p[k];
      const double la = a.norm(), lb = b.norm();
      r.min_side = std::min(r.min_side, la);
      r.max_side = std::max(r.max_side, la);
      total_side += la;
      const double angle = la > 0 && lb > 0 ? std::acos(std::clamp(a.dot(b) / (la * lb), -1.0, 1.0)) * 180 / M_PI : 0.0;
      r.min_angle_deg = std::min(r.min_angle_deg, angle);
      r.max_angle_deg = std::max(r.max_angle_deg, angle);
      const double scale = la * lb * n.norm();
      r.min_scaled_jacobian = std::min(r.min_scaled_jacobian, scale > 0 ? a.cross(b).dot(n) / scale : 0.0);
    }
  }
  r.mean_side = total_side / (4.0 * q.num_quads());
  return r;
}

std::string QuadExtractionOptions::invalid_reason() const {
  if (!(tolerance > 0 && tolerance < 0.1)) return "the tolerance must be in (0, 0.1) UV units";
  return "";
}

QuadExtraction extract_quads(const Mesh& map, const QuadExtractionOptions& options, const std::string& source) {
  const auto t0 = std::chrono::steady_clock::now();
  if (const std::string why = options.invalid_reason(); !why.empty()) throw InputError(prefix(source) + why);
  check_map(map, source);
  check_extent(map, source);
  const SurfaceGraph graph = surface_graph(map, source);
  const std::vector<UvTransition> transitions = integer_uv_transitions(map, graph, options.tolerance, source);
  const std::vector<int> quarters = cones_on_the_grid(map, graph, options.tolerance, source);

  QuadExtraction x;
  x.surface_euler_characteristic = graph.euler_characteristic();
  x.cones = static_cast<int>(std::count_if(quarters.begin(), quarters.end(), [](int k) { return k != 0; }));
  for (int f = 0; f < graph.num_faces; ++f) {
    const double area2 = doubled_uv_area(map, f);
    x.uv_area += area2 / 2;
    if (!(area2 > 0)) ++x.flipped_triangles;
  }

  Squares squares = flood_every_square(map, graph, transitions, options.tolerance);
  drop_inverted_squares(map, squares);
  drop_overlapping_squares(squares);
  x.squares_touching_flips = squares.touching_flips;
  x.squares_wrapped = squares.wrapped;
  x.squares_not_covered_once = squares.not_covered_once;
  x.squares_overlapping = squares.overlapping;
  x.squares_inverted = squares.inverted;
  x.dropped_squares =
      squares.touching_flips + squares.wrapped + squares.not_covered_once + squares.overlapping + squares.inverted;
  std::vector<SurfacePointKey> keys;  // each quad-mesh vertex's surface point
  x.mesh = assemble(map, squares.quads, keys);
  std::vector<Square>().swap(squares.quads);  // not needed any more: the rest of the peak memory
  if (options.fill_holes) {
    std::vector<int> cone_quarters(keys.size(), 0);
    for (size_t v = 0; v < keys.size(); ++v)
      if (keys[v].kind == SurfacePointKey::Vertex) cone_quarters[v] = quarters[keys[v].element];
    const HoleFilling filling = fill_quad_holes(x.mesh, cone_quarters);
    x.filled_holes = filling.filled_holes;
    x.filled_squares = filling.filled_squares;
  }
  x.split_vertices = split_pinched_vertices(x.mesh);
  check_topology(x);
  x.quality = quad_quality(x.mesh);
  // Closed, manifold, the surface's topology, one quad per unit of UV area, and no square left
  // out or fold unless holes were filled (then the status says "filled").
  x.complete = x.boundary_edges == 0 && x.non_manifold_edges == 0 && x.non_manifold_vertices == 0 &&
               x.euler_characteristic == x.surface_euler_characteristic &&
               std::abs(x.mesh.num_quads() - x.uv_area) <= 1e-6 * std::max(1.0, x.uv_area) &&
               ((x.dropped_squares == 0 && x.flipped_triangles == 0) || x.filled_squares > 0);
  x.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return x;
}

}  // namespace strictmin
