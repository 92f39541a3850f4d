// One unit square of an integer-grid map, followed over the surface (src/tasks/square_flood.h).
#include "tasks/square_flood.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace strictmin {
namespace {

// The square's corners about its centre, counter-clockwise in its own frame.
const std::array<Eigen::Vector2d, 4> kCornerOffsets = {Eigen::Vector2d(-0.5, -0.5), Eigen::Vector2d(0.5, -0.5),
                                                       Eigen::Vector2d(0.5, 0.5), Eigen::Vector2d(-0.5, 0.5)};

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// Whether the segment a-b meets the closed square of centre c (grown by tol) over a length of
// more than 3 tol: an edge through the square or along one of its sides, but not one that
// only touches a corner (around a cone at the corner the flood would otherwise go all the
// way round and meet its start in another chart). Clipped to the box one axis at a time
// (Liang-Barsky).
bool meets_square(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c, double tol) {
  const Eigen::Vector2d d = b - a;
  double t0 = 0, t1 = 1;
  for (int k = 0; k < 2; ++k) {
    const double lo = c(k) - 0.5 - tol, hi = c(k) + 0.5 + tol;
    if (d(k) == 0) {
      if (a(k) <= lo || a(k) >= hi) return false;
      continue;
    }
    double ta = (lo - a(k)) / d(k), tb = (hi - a(k)) / d(k);
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t1 > t0 && (t1 - t0) * d.norm() > 3 * tol;
}

// The signed area of triangle (p0, p1, p2) inside the closed square of centre c
// (Sutherland-Hodgman against the square's four sides, then the shoelace formula). Worked
// about c: the shoelace's products of absolute UVs would lose the area's digits far from 0.
double clipped_area(const std::array<Eigen::Vector2d, 3>& triangle, const Eigen::Vector2d& c) {
  std::vector<Eigen::Vector2d> poly, next;
  for (const Eigen::Vector2d& p : triangle) poly.push_back(p - c);
  for (int side = 0; side < 4 && !poly.empty(); ++side) {
    const int axis = side / 2;
    const double sign = side % 2 == 0 ? 1.0 : -1.0;  // keep x >= lo, then x <= hi
    const double bound = -0.5 * sign;
    const auto inside = [&](const Eigen::Vector2d& p) { return sign * (p(axis) - bound) >= 0; };
    next.clear();
    for (size_t i = 0; i < poly.size(); ++i) {
      const Eigen::Vector2d& p = poly[i];
      const Eigen::Vector2d& q = poly[(i + 1) % poly.size()];
      if (inside(p)) next.push_back(p);
      if (inside(p) != inside(q)) next.push_back(p + (q - p) * ((bound - p(axis)) / (q(axis) - p(axis))));
    }
    poly.swap(next);
  }
  double area = 0;
  for (size_t i = 0; i < poly.size(); ++i) area += cross(poly[i], poly[(i + 1) % poly.size()]);
  return area / 2;
}

std::array<Eigen::Vector2d, 3> face_uvs(const Mesh& map, int f) {
  return {corner_uv(map, f, 0), corner_uv(map, f, 1), corner_uv(map, f, 2)};
}

// The distance of p from the line of side i (corner i to i + 1), positive inside a
// counter-clockwise triangle.
double side_distance(const std::array<Eigen::Vector2d, 3>& t, int i, const Eigen::Vector2d& p) {
  const Eigen::Vector2d a = t[i], b = t[(i + 1) % 3];
  const double length = (b - a).norm();
  return length > 0 ? cross(b - a, p - a) / length : 0.0;
}

Eigen::Vector3d barycentric(const std::array<Eigen::Vector2d, 3>& t, const Eigen::Vector2d& p) {
  Eigen::Vector3d l;
  for (int i = 0; i < 3; ++i) l(i) = std::max(0.0, cross(t[(i + 1) % 3] - p, t[(i + 2) % 3] - p));
  const double sum = l.sum();
  return sum > 0 ? Eigen::Vector3d(l / sum) : Eigen::Vector3d(1.0 / 3, 1.0 / 3, 1.0 / 3);
}

// The distance from p to the segment a-b.
double segment_distance(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
  const Eigen::Vector2d d = b - a;
  const double length2 = d.squaredNorm();
  const double s = length2 > 0 ? std::clamp((p - a).dot(d) / length2, 0.0, 1.0) : 0.0;
  return (a + s * d - p).norm();
}

SurfacePointKey key_at(const Eigen::Vector2d& p, int kind, int element) {
  return {kind, element, static_cast<std::int64_t>(std::llround(p.x())), static_cast<std::int64_t>(std::llround(p.y()))};
}

}  // namespace

bool uv_face_contains(const Mesh& map, int f, const Eigen::Vector2d& p, double tolerance) {
  const auto t = face_uvs(map, f);
  for (int i = 0; i < 3; ++i)
    if (side_distance(t, i, p) < -tolerance) return false;
  return true;
}

SquareFlooder::SquareFlooder(const Mesh& map, const SurfaceGraph& graph, const std::vector<UvTransition>& transitions,
                             double tolerance)
    : map_(map), graph_(graph), transitions_(transitions), tolerance_(tolerance), visits_(graph.num_faces) {}

SquareFlood SquareFlooder::flood(int face, const Eigen::Vector2d& centre) {
  ++stamp_;
  SquareFlood out;
  visits_[face] = {stamp_, centre, Eigen::Matrix2d::Identity()};
  std::vector<int> queue{face};
  std::array<bool, 4> found{};
  bool flips = false;
  wraps_ = false;
  for (size_t next = 0; next < queue.size(); ++next) {
    const int g = queue[next];
    const Visit here = visits_[g];
    flips = flips || !(doubled_uv_area(map_, g) > 0);
    out.covered += clipped_area(face_uvs(map_, g), here.centre);
    if (uv_face_contains(map_, g, here.centre, tolerance_)) out.centres.emplace_back(g, here.centre);
    find_corners(g, here, centre, found, out);
    const auto t = face_uvs(map_, g);
    for (int side = 0; side < 3; ++side) flips = !cross_to_neighbour(g, side, t, here, queue) || flips;
  }
  for (int k = 0; k < 4; ++k)
    if (!found[k]) find_corner_nearby(k, queue, centre, found, out);
  out.outcome = outcome_of(flips, std::all_of(found.begin(), found.end(), [](bool b) { return b; }), out);
  return out;
}

// What the flood found makes the square a quad unless it touched a fold, came back to a face in
// another chart or has two corners at one surface point (it wraps onto itself), or misses a
// corner or is not covered exactly once.
SquareFlood::Outcome SquareFlooder::outcome_of(bool flips, bool all_corners_found, const SquareFlood& s) const {
  bool distinct = all_corners_found;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) distinct = distinct && !(s.corners[i].key == s.corners[j].key);
  if (flips) return SquareFlood::Outcome::TouchesFlip;
  if (wraps_ || (all_corners_found && !distinct)) return SquareFlood::Outcome::Wraps;
  if (!distinct || std::abs(s.covered - 1) > std::max(1e-6, 100 * tolerance_)) return SquareFlood::Outcome::NotCoveredOnce;
  return SquareFlood::Outcome::Quad;
}

// Crosses side `side` of face when it runs through the square or along one of its sides (so
// that a fold hanging from a side of the square is reached: a flipped triangle next to the
// square, across an edge on the grid line, leaves the square out); false when the edge is
// degenerate in UV (its transition unknown). A face reached again in another chart sets wraps_.
bool SquareFlooder::cross_to_neighbour(int face, int side, const std::array<Eigen::Vector2d, 3>& t, const Visit& here,
                                       std::vector<int>& queue) {
  if (!meets_square(t[side], t[(side + 1) % 3], here.centre, tolerance_)) return true;
  const int e = graph_.face_edges(face, side), h = graph_.neighbour(face, side);
  if (!transitions_[e].known) return false;
  const Visit carried = carried_across(face, side, here);
  Visit& there = visits_[h];
  if (there.stamp == stamp_) {
    if ((there.centre - carried.centre).norm() > 1e-6 || (there.frame - carried.frame).norm() > 1e-9) wraps_ = true;
    return true;
  }
  there = carried;
  queue.push_back(h);
  return true;
}

// Whether side `side` of face is its edge's face-0 side (uv there = R uv(face 1) + t).
bool SquareFlooder::is_face0_side(int face, int side) const {
  const int e = graph_.face_edges(face, side);
  return graph_.edge_faces(e, 0) == face && graph_.edge_sides(e, 0) == side;
}

// Point p of face's chart in the chart of the face across side `side`.
Eigen::Vector2d SquareFlooder::across(int face, int side, const Eigen::Vector2d& p) const {
  const UvTransition& T = transitions_[graph_.face_edges(face, side)];
  return is_face0_side(face, side) ? T.to_face1(p) : T.to_face0(p);
}

// The square as seen from the face across side `side` of `face` (its transition applied).
SquareFlooder::Visit SquareFlooder::carried_across(int face, int side, const Visit& here) const {
  const Eigen::Matrix2d R = transitions_[graph_.face_edges(face, side)].rotation();
  Visit v;
  v.stamp = stamp_;
  v.centre = across(face, side, here.centre);
  v.frame = is_face0_side(face, side) ? Eigen::Matrix2d(R.transpose() * here.frame) : Eigen::Matrix2d(R * here.frame);
  return v;
}

// The square's corners (integer points) that lie in the closed face, each with its key.
void SquareFlooder::find_corners(int face, const Visit& here, const Eigen::Vector2d& start_centre,
                                 std::array<bool, 4>& found, SquareFlood& out) const {
  for (int k = 0; k < 4; ++k) {
    if (found[k]) continue;
    const Eigen::Vector2d p = corner_point(here, k);
    if (!uv_face_contains(map_, face, p, tolerance_)) continue;
    SquareCorner& c = out.corners[k];
    c.uv = start_centre + kCornerOffsets[k];
    found[k] = true;
    const auto [g, q] = holding_face(face, p);
    key_corner(g, q, c);
  }
}

// The face that holds p (in face's chart) without tolerance, stepped to across the side p is
// furthest beyond (its transition applied), at most a few steps and never into a flipped
// face: a grid point a few tolerances from a vertex may be within the tolerance of several
// triangles of its fan and of several of their sides, and is keyed where it lies, the same
// from every square.
std::pair<int, Eigen::Vector2d> SquareFlooder::holding_face(int face, Eigen::Vector2d p) const {
  for (int step = 0, previous = -1; step < 8; ++step) {
    const auto t = face_uvs(map_, face);
    int beyond = -1;
    double furthest = 0;
    for (int i = 0; i < 3; ++i)
      if (side_distance(t, i, p) < furthest) furthest = side_distance(t, i, p), beyond = i;
    if (beyond < 0) break;
    const int e = graph_.face_edges(face, beyond), h = graph_.neighbour(face, beyond);
    if (!transitions_[e].known || h == previous || !(doubled_uv_area(map_, h) > 0)) break;
    p = across(face, beyond, p);
    previous = face;
    face = h;
  }
  return {face, p};
}

// The key of grid point p of face's chart: a vertex of face within the tolerance, else a side
// within the tolerance (the nearest), else the face.
void SquareFlooder::key_corner(int face, const Eigen::Vector2d& p, SquareCorner& c) const {
  const auto t = face_uvs(map_, face);
  c.face = face;
  c.barycentric = barycentric(t, p);
  int at_vertex = -1;
  for (int i = 0; i < 3; ++i)
    if ((t[i] - p).norm() <= tolerance_) at_vertex = i;
  if (at_vertex >= 0) {
    c.key = {SurfacePointKey::Vertex, map_.F(face, at_vertex), 0, 0};
    c.barycentric = Eigen::Vector3d::Unit(at_vertex);
    return;
  }
  int on_side = -1;
  double nearest = tolerance_;
  for (int i = 0; i < 3; ++i)
    if (std::abs(side_distance(t, i, p)) <= nearest) nearest = std::abs(side_distance(t, i, p)), on_side = i;
  if (on_side < 0) {
    c.key = key_at(p, SurfacePointKey::Face, face);
    return;
  }
  const int e = graph_.face_edges(face, on_side);
  const bool keep = is_face0_side(face, on_side) || !transitions_[e].known;  // keyed in face 0's chart
  c.key = key_at(keep ? p : across(face, on_side, p), SurfacePointKey::Edge, e);
}

Eigen::Vector2d SquareFlooder::corner_point(const Visit& here, int k) {
  const Eigen::Vector2d q = here.centre + here.frame * kCornerOffsets[k];
  return {std::round(q.x()), std::round(q.y())};
}

// A corner that no face of the square holds: it lies (by less than the tolerance of the
// edges' crossings) in a face that touches the square only in a sliver, as next to a vertex a
// hair from the grid point. Searched from the square's faces across the edges that pass
// within half a unit of the corner, each seam's transition applied, up to kNearbyFaces faces.
void SquareFlooder::find_corner_nearby(int k, const std::vector<int>& square_faces, const Eigen::Vector2d& start_centre,
                                       std::array<bool, 4>& found, SquareFlood& out) {
  constexpr size_t kNearbyFaces = 1000;
  std::unordered_map<int, Visit> seen;
  std::vector<int> queue;
  for (int f : square_faces) seen.emplace(f, visits_[f]), queue.push_back(f);
  for (size_t next = 0; next < queue.size() && queue.size() < kNearbyFaces && !found[k]; ++next) {
    const int g = queue[next];
    const Visit here = seen.at(g);
    const auto t = face_uvs(map_, g);
    const Eigen::Vector2d p = corner_point(here, k);
    for (int side = 0; side < 3; ++side) {
      const int e = graph_.face_edges(g, side), h = graph_.neighbour(g, side);
      if (!transitions_[e].known || seen.count(h) || segment_distance(t[side], t[(side + 1) % 3], p) > 0.5) continue;
      seen.emplace(h, carried_across(g, side, here));
      queue.push_back(h);
    }
    std::array<bool, 4> others_done;  // find_corners looks for corner k alone
    others_done.fill(true);
    others_done[k] = false;
    find_corners(g, here, start_centre, others_done, out);
    found[k] = others_done[k];
  }
}

}  // namespace strictmin
