// The seams of a per-corner UV map read back from its UVs (src/tasks/uv_transitions.h).
#include "tasks/uv_transitions.h"

#include <cmath>
#include <limits>
#include <sstream>

#include "strictmin/field/cut_graph.h"
#include "strictmin/io/input_error.h"

namespace strictmin {
namespace {

std::string prefix(const std::string& source) { return source.empty() ? std::string() : source + ": "; }

std::string shown(const Eigen::Vector2d& x) {
  std::ostringstream s;
  s.precision(10);
  s << "(" << x.x() << ", " << x.y() << ")";
  return s.str();
}

std::string shown(double x) {
  std::ostringstream s;
  s.precision(3);
  s << x;
  return s.str();
}

// " by M (more than the tolerance T)" and `verdict`, or, when M is within the round-off of
// UVs of this magnitude, that the tolerance asks for more digits than the UVs have.
std::string missed_by(double miss, double tolerance, double magnitude, const std::string& verdict) {
  const std::string out = " by " + shown(miss) + " (more than the tolerance " + shown(tolerance) + ")";
  const double round_off = 64 * std::numeric_limits<double>::epsilon() * std::max(1.0, magnitude);
  if (miss > round_off) return out + " " + verdict;
  return out + "; that is the round-off of UVs near " + shown(magnitude) + " (about " + shown(round_off) +
         "): give a larger --tolerance";
}

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// The corner of face f at vertex v.
int corner_of(const Mesh& map, int f, int v) {
  for (int i = 0; i < 3; ++i)
    if (map.F(f, i) == v) return i;
  return -1;
}

double grid_distance(const Eigen::Vector2d& x) {
  return std::max(std::abs(x.x() - std::round(x.x())), std::abs(x.y() - std::round(x.y())));
}

UvTransition transition_of_edge(const Mesh& map, const SurfaceGraph& g, int e, double tolerance,
                                const std::string& source) {
  const int a = g.edges(e, 0), b = g.edges(e, 1), f0 = g.edge_faces(e, 0), f1 = g.edge_faces(e, 1);
  const int a0 = corner_of(map, f0, a), b0 = corner_of(map, f0, b), a1 = corner_of(map, f1, a), b1 = corner_of(map, f1, b);
  UvTransition t;
  if (map.FUV(f0, a0) == map.FUV(f1, a1) && map.FUV(f0, b0) == map.FUV(f1, b1)) return t;  // no seam
  const Eigen::Vector2d d0 = corner_uv(map, f0, b0) - corner_uv(map, f0, a0);
  const Eigen::Vector2d d1 = corner_uv(map, f1, b1) - corner_uv(map, f1, a1);
  const std::string edge = "edge " + std::to_string(a) + "-" + std::to_string(b) + " (vertices, 0-based)";
  if (d0.norm() <= tolerance && d1.norm() <= tolerance) {  // degenerate in UV: R cannot be read
    t.known = false;
    return t;
  }
  double best = INFINITY;
  for (int k = 0; k < 4; ++k) {
    const double miss = (quarter_rotation(k) * d1 - d0).norm();
    if (miss < best) best = miss, t.quarter_turns = k;
  }
  const double magnitude = corner_uv(map, f0, a0).cwiseAbs().maxCoeff();
  if (best > tolerance * (1 + d0.norm()))
    throw InputError(prefix(source) + edge + ": its UVs on the two sides, " + shown(d0) + " and " + shown(d1) +
                     ", differ from a quarter turn of each other" +
                     missed_by(best, tolerance * (1 + d0.norm()), magnitude, "(the map is not seamless)"));
  const Eigen::Matrix2d R = t.rotation();
  const Eigen::Vector2d ta = corner_uv(map, f0, a0) - R * corner_uv(map, f1, a1);
  const Eigen::Vector2d tb = corner_uv(map, f0, b0) - R * corner_uv(map, f1, b1);
  if (grid_distance(ta) > tolerance || grid_distance(tb) > tolerance)
    throw InputError(prefix(source) + edge + ": the seam's translation " + shown(ta) + " misses a pair of integers" +
                     missed_by(std::max(grid_distance(ta), grid_distance(tb)), tolerance, magnitude,
                               "(not an integer-grid map; gparam --integer-grid makes one)"));
  t.translation = {std::round(ta.x()), std::round(ta.y())};
  return t;
}

// The signed angle of face f's corner i in UV.
double corner_angle(const Mesh& map, int f, int i) {
  const Eigen::Vector2d p = corner_uv(map, f, i);
  const Eigen::Vector2d u = corner_uv(map, f, (i + 1) % 3) - p, w = corner_uv(map, f, (i + 2) % 3) - p;
  return std::atan2(cross(u, w), u.dot(w));
}

}  // namespace

Eigen::Matrix2d UvTransition::rotation() const { return quarter_rotation(quarter_turns); }
Eigen::Vector2d UvTransition::to_face1(const Eigen::Vector2d& x) const { return rotation().transpose() * (x - translation); }
Eigen::Vector2d UvTransition::to_face0(const Eigen::Vector2d& x) const { return rotation() * x + translation; }

double doubled_uv_area(const Mesh& map, int f) {
  const Eigen::Vector2d p = corner_uv(map, f, 0);
  return cross(corner_uv(map, f, 1) - p, corner_uv(map, f, 2) - p);
}

std::vector<UvTransition> integer_uv_transitions(const Mesh& map, const SurfaceGraph& g, double tolerance,
                                                 const std::string& source) {
  std::vector<UvTransition> transitions(g.num_edges());
  for (int e = 0; e < g.num_edges(); ++e) transitions[e] = transition_of_edge(map, g, e, tolerance, source);
  return transitions;
}

std::vector<int> cones_on_the_grid(const Mesh& map, const SurfaceGraph& g, double tolerance, const std::string& source) {
  std::vector<int> quarters(g.num_vertices, 0);
  for (int v = 0; v < g.num_vertices; ++v) {
    double angle = 0;
    bool degenerate = false;
    for (int k = g.fan_start[v]; k < g.fan_start[v + 1]; ++k) {
      const int f = g.fan_faces[k];
      degenerate = degenerate || !(doubled_uv_area(map, f) > 0);
      angle += corner_angle(map, f, g.fan_corners[k]);
    }
    if (degenerate) continue;
    quarters[v] = 4 - static_cast<int>(std::lround(angle / (M_PI / 2)));
    if (quarters[v] == 0) continue;
    const int f = g.fan_faces[g.fan_start[v]];
    const Eigen::Vector2d at = corner_uv(map, f, g.fan_corners[g.fan_start[v]]);
    if (grid_distance(at) > tolerance)
      throw InputError(prefix(source) + "vertex " + std::to_string(v) + " (0-based) is a cone of index " +
                       std::to_string(quarters[v]) + "/4 at UV " + shown(at) + ", off the nearest integer point" +
                       missed_by(grid_distance(at), tolerance, at.cwiseAbs().maxCoeff(),
                                 "(not an integer-grid map; gparam --integer-grid makes one)"));
  }
  return quarters;
}

}  // namespace strictmin
