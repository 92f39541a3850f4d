// Filling the holes of an extracted quad mesh (src/tasks/quad_hole_filling.h).
#include "tasks/quad_hole_filling.h"

#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <unordered_map>

namespace strictmin {
namespace {

using Point = Eigen::Matrix<long long, 2, 1>;

// p turned by `quarters` quarter turns counter-clockwise.
Point rotated(const Point& p, int quarters) {
  switch (((quarters % 4) + 4) % 4) {
    case 1: return {-p.y(), p.x()};
    case 2: return {-p.x(), -p.y()};
    case 3: return {p.y(), -p.x()};
    default: return p;
  }
}

class Filler {
 public:
  Filler(QuadMesh& q, const std::vector<int>& cone_quarters)
      : q_(q), cone_quarters_(cone_quarters), valence_(q.num_vertices(), 0) {
    for (int i = 0; i < q.num_quads(); ++i)
      for (int k = 0; k < 4; ++k) {
        owner_[directed_edge(q.Q(i, k), q.Q(i, (k + 1) % 4))] = i;
        ++valence_[q.Q(i, k)];
      }
  }

  HoleFilling run();

 private:
  // A hole edge runs from `from` to `to`, the reverse of one of quad's edges (to -> from); fan:
  // the kept quads around `to` from quad to the next hole edge's quad.
  struct HoleEdge {
    int from = -1, to = -1, quad = -1, fan = 0;
  };

  int corner_of(int quad, int vertex) const {
    for (int k = 0; k < 4; ++k)
      if (q_.Q(quad, k) == vertex) return k;
    return -1;
  }
  bool is_boundary(int a, int b) const { return !owner_.count(directed_edge(b, a)); }
  std::optional<HoleEdge> turn_to_next(HoleEdge& e) const;
  bool fill_loop(const std::vector<HoleEdge>& loop, HoleFilling& out);

  QuadMesh& q_;
  const std::vector<int>& cone_quarters_;
  std::vector<int> valence_;  // kept quads at each vertex
  std::unordered_map<std::uint64_t, int> owner_;  // directed edge -> its quad
  // Added by the filling (appended to q_ at the end).
  std::vector<Eigen::Vector3d> new_vertices_;
  std::vector<std::array<int, 4>> new_quads_;
  std::vector<std::array<Point, 4>> new_quad_uvs_;
};

// The loop (hole edges in order, the hole on their left) unfolded into the plane by its
// corners' angles on the hole's side: a unit step along each edge, and at each vertex a turn of
// 2 - (4 - k - fan) quarter turns, fan the kept quads around it and k its cone index (the hole
// is flat inside when no cone is in it, so this is the hole's own shape; a cone inside shows as
// a total turn other than one full turn). Its squares are added when it closes up as a simple
// counter-clockwise polygon.
bool Filler::fill_loop(const std::vector<HoleEdge>& loop, HoleFilling& out) {
  const size_t m = loop.size();
  std::vector<Point> polygon(m);
  std::map<std::pair<long long, long long>, int> on_loop;  // grid point -> vertex
  Point at = Point::Zero(), step(1, 0);
  int total_turn = 0;
  for (size_t t = 0; t < m; ++t) {
    polygon[t] = at;
    if (!on_loop.emplace(std::make_pair(at.x(), at.y()), loop[t].from).second) return false;  // not simple
    at += step;
    const int v = loop[t].to, fan = loop[t].fan;
    if (fan != valence_[v]) return false;  // v's quads make more than one fan (holes meet there)
    const int hole_quarters = 4 - cone_quarters_[v] - fan;
    if (hole_quarters < 1) return false;
    const int turn = 2 - hole_quarters;
    total_turn += turn;
    step = rotated(step, turn);
  }
  if (at != Point::Zero() || total_turn != 4) return false;  // a cone inside, or not closed
  long long area2 = 0;
  Point lo = polygon[0], hi = polygon[0];
  for (size_t t = 0; t < m; ++t) {
    const Point& a = polygon[t];
    const Point& b = polygon[(t + 1) % m];
    area2 += a.x() * b.y() - a.y() * b.x();
    lo = lo.cwiseMin(a);
    hi = hi.cwiseMax(a);
  }
  if (area2 <= 0) return false;
  // The unit squares whose centres the polygon holds (even-odd rule; no centre is on an edge).
  const auto inside = [&](double x, double y) {
    bool in = false;
    for (size_t t = 0; t < m; ++t) {
      const Point& a = polygon[t];
      const Point& b = polygon[(t + 1) % m];
      if ((a.y() > y) != (b.y() > y) && x < a.x() + (y - a.y()) * double(b.x() - a.x()) / double(b.y() - a.y()))
        in = !in;
    }
    return in;
  };
  std::vector<Point> squares;
  for (long long i = lo.x(); i < hi.x(); ++i)
    for (long long j = lo.y(); j < hi.y(); ++j)
      if (inside(i + 0.5, j + 0.5)) squares.emplace_back(i, j);
  if (2 * static_cast<long long>(squares.size()) != area2) return false;
  // Grid points inside get new vertices, placed by averaging their four grid neighbours.
  std::map<std::pair<long long, long long>, int> inner;  // grid point -> index into new_vertices_
  const int base = q_.num_vertices() + static_cast<int>(new_vertices_.size());
  const auto vertex_at = [&](long long x, long long y) {
    if (const auto it = on_loop.find({x, y}); it != on_loop.end()) return it->second;
    const auto [it, added] = inner.emplace(std::make_pair(x, y), static_cast<int>(inner.size()));
    return base + it->second;
  };
  const Point corner[4] = {Point(0, 0), Point(1, 0), Point(1, 1), Point(0, 1)};
  for (const Point& s : squares) {
    std::array<int, 4> quad{};
    std::array<Point, 4> uvs;
    for (int k = 0; k < 4; ++k) {
      uvs[k] = s + corner[k];
      quad[k] = vertex_at(uvs[k].x(), uvs[k].y());
    }
    new_quads_.push_back(quad);
    new_quad_uvs_.push_back(uvs);
  }
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const HoleEdge& e : loop) mean += q_.V.row(e.from).transpose();
  mean /= static_cast<double>(m);
  std::vector<Eigen::Vector3d> position(inner.size(), mean);
  const auto position_of = [&](long long x, long long y) -> Eigen::Vector3d {
    if (const auto it = on_loop.find({x, y}); it != on_loop.end()) return q_.V.row(it->second).transpose();
    return position[inner.at({x, y})];
  };
  for (int sweep = 0; sweep < 200; ++sweep)
    for (const auto& [p, index] : inner)
      position[index] = (position_of(p.first + 1, p.second) + position_of(p.first - 1, p.second) +
                         position_of(p.first, p.second + 1) + position_of(p.first, p.second - 1)) / 4;
  new_vertices_.insert(new_vertices_.end(), position.begin(), position.end());
  ++out.filled_holes;
  out.filled_squares += static_cast<int>(squares.size());
  return true;
}

// The hole edge after e: turning around e.to from e's quad through the kept quads to the
// first edge into e.to on the boundary (where two holes touch at a vertex, this picks the
// one of e's hole); e.fan gets the quads turned through. None when the turn does not end.
std::optional<Filler::HoleEdge> Filler::turn_to_next(HoleEdge& e) const {
  const int v = e.to;
  int c = e.quad;
  for (e.fan = 1; e.fan <= 64; ++e.fan) {
    const int x = q_.Q(c, (corner_of(c, v) + 3) % 4);  // the edge x -> v
    if (is_boundary(x, v)) return HoleEdge{v, x, c, 0};
    c = owner_.at(directed_edge(v, x));
  }
  return std::nullopt;
}

HoleFilling Filler::run() {
  HoleFilling out;
  std::vector<HoleEdge> hole_edges;
  for (const auto& [key, quad] : owner_) {
    const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
    if (is_boundary(a, b)) hole_edges.push_back({b, a, quad, 0});
  }
  std::unordered_map<std::uint64_t, char> used;
  for (const HoleEdge& first : hole_edges) {
    if (used[directed_edge(first.from, first.to)]) continue;
    std::vector<HoleEdge> loop;
    bool closed = false;
    for (std::optional<HoleEdge> e = first; e && !used[directed_edge(e->from, e->to)];) {
      used[directed_edge(e->from, e->to)] = 1;
      const std::optional<HoleEdge> next = turn_to_next(*e);
      loop.push_back(*e);
      closed = next && next->from == first.from && next->to == first.to;
      e = next;
    }
    if (closed) fill_loop(loop, out);
  }
  // Append what was added.
  const int n0 = q_.num_vertices(), m0 = q_.num_quads(), u0 = static_cast<int>(q_.UV.rows());
  const int n = static_cast<int>(new_vertices_.size()), m = static_cast<int>(new_quads_.size());
  q_.V.conservativeResize(n0 + n, 3);
  q_.vertex_face.conservativeResize(n0 + n);
  q_.vertex_barycentric.conservativeResize(n0 + n, 3);
  for (int i = 0; i < n; ++i) {
    q_.V.row(n0 + i) = new_vertices_[i].transpose();
    q_.vertex_face(n0 + i) = -1;
    q_.vertex_barycentric.row(n0 + i).setConstant(NAN);
  }
  q_.Q.conservativeResize(m0 + m, 4);
  q_.QUV.conservativeResize(m0 + m, 4);
  q_.UV.conservativeResize(u0 + 4 * m, 2);
  for (int i = 0; i < m; ++i)
    for (int k = 0; k < 4; ++k) {
      q_.Q(m0 + i, k) = new_quads_[i][k];
      q_.QUV(m0 + i, k) = u0 + 4 * i + k;
      q_.UV.row(u0 + 4 * i + k) << static_cast<double>(new_quad_uvs_[i][k].x()),
          static_cast<double>(new_quad_uvs_[i][k].y());
    }
  return out;
}

}  // namespace

HoleFilling fill_quad_holes(QuadMesh& q, const std::vector<int>& cone_quarters) { return Filler(q, cone_quarters).run(); }

}  // namespace strictmin
