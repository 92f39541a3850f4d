// Global parametrization of surfaces with boundary (docs/gparam.md, "Surfaces with
// boundary"): the field along the boundary, boundary indices and Poincare-Hopf, the cut
// between boundary loops, and every method, against known answers.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <filesystem>
#include <map>
#include <numbers>
#include <numeric>
#include <random>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

#include "expect_input_error.h"
#include "strictmin/field/cross_field.h"
#include "strictmin/field/cut_graph.h"
#include "strictmin/field/singularities.h"
#include "strictmin/field/surface_graph.h"
#include "strictmin/io/mesh_io.h"
#include "strictmin/mesh/polycube.h"
#include "strictmin/param/topology.h"
#include "strictmin/report/strict_order.h"
#include "strictmin/tasks/gparam.h"
#include "strictmin/tasks/seamless_problem.h"
#include "test_meshes.h"

using namespace strictmin;
using strictmin::test_support::expect_input_error;
using strictmin::test_support::expect_poincare_hopf;

namespace {

// The mesh without the faces `drop` selects, its unused vertices removed.
template <class Drop>
Mesh without_faces(const Mesh& m, Drop drop) {
  std::vector<char> dropped(static_cast<std::size_t>(m.num_elements()));
  for (int f = 0; f < m.num_elements(); ++f) dropped[static_cast<std::size_t>(f)] = drop(f) ? 1 : 0;
  return without_elements(m, dropped);
}

// The faces whose three corners have coordinate `axis` equal to `value`.
auto on_plane(const Mesh& m, int axis, double value) {
  return [&m, axis, value](int f) {
    for (int i = 0; i < 3; ++i)
      if (std::abs(m.V(m.F(f, i), axis) - value) > 1e-12) return false;
    return true;
  };
}

// A cube of side 5 without its top (z = 5): a disk whose 4 bottom corners are cones of +1/4.
Mesh open_box(int n = 3) {
  const Mesh cube = make_cube_surface(n);
  return without_faces(cube, on_plane(cube, 2, 5.0));
}

// The genus-1 frame (3 x 3 x 1 cubes less the centre) without its top (z = 1): an annulus
// in 3D, two boundary loops.
Mesh open_frame(int n = 2) {
  const Mesh frame = make_frame_surface(n);
  return without_faces(frame, on_plane(frame, 2, 1.0));
}

// The frame's top alone: a flat square annulus (outer corners +1/4, inner corners -1/4).
Mesh flat_annulus(int n = 2) {
  const Mesh frame = make_frame_surface(n);
  const auto top = on_plane(frame, 2, 1.0);
  return without_faces(frame, [&](int f) { return !top(f); });
}

// The frame less the faces of one outer side square (x = 0, 1 <= y <= 2): genus 1, one
// boundary loop.
Mesh frame_with_a_window(int n = 2) { return strictmin::frame_with_a_window(make_frame_surface(n)); }

GParamOptions options(Method m) {
  GParamOptions o;
  o.solver.method = m;
  o.edge_length = 0.7;
  return o;
}

std::map<int, int> index_counts(const std::vector<Singularity>& s, const SurfaceGraph& g, bool boundary) {
  std::map<int, int> counts;
  for (const auto& x : s)
    if (static_cast<bool>(g.boundary_vertex[x.vertex]) == boundary) ++counts[x.quarters];
  return counts;
}

// The cut mesh is one disk: one component, one boundary loop, chi 1; every interior
// singularity is on the cut (on a seam edge), boundary edges are never cut.
void expect_disk_cut(const Mesh& m, const GParamOutcome& g, const std::string& name) {
  const SurfaceTopology t = surface_topology(cut_mesh(m, g.cut));
  EXPECT_EQ(t.components, 1) << name;
  EXPECT_EQ(t.boundary_loops.size(), 1u) << name;
  EXPECT_EQ(t.euler_characteristic(), 1) << name;
  std::vector<char> on_cut(g.graph.num_vertices, 0);
  for (int e = 0; e < g.graph.num_edges(); ++e) {
    if (g.graph.is_boundary_edge(e)) {
      EXPECT_FALSE(g.cut.cut[e]) << name << ": boundary edge " << e << " cut";
    }
    if (g.cut.cut[e]) on_cut[g.graph.edges(e, 0)] = on_cut[g.graph.edges(e, 1)] = 1;
  }
  for (const auto& s : g.singular)
    if (!g.graph.boundary_vertex[s.vertex]) {
      EXPECT_TRUE(on_cut[s.vertex]) << name << ": singular vertex " << s.vertex;
    }
}

// Every interior vertex's UV angles (the corners' angles in the map, signed) add up to
// 2 pi (1 - index): the cones the map really has are the ones reported.
void expect_map_cones_match_indices(const Mesh& m, const GParamOutcome& g, const std::string& name) {
  std::vector<double> angle(m.num_vertices(), 0.0);
  for (int f = 0; f < m.num_elements(); ++f)
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector2d p = g.mapped.UV.row(g.cut.corner_wedge(f, i)).transpose();
      const Eigen::Vector2d a = g.mapped.UV.row(g.cut.corner_wedge(f, (i + 1) % 3)).transpose() - p;
      const Eigen::Vector2d b = g.mapped.UV.row(g.cut.corner_wedge(f, (i + 2) % 3)).transpose() - p;
      angle[m.F(f, i)] += std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
    }
  for (int v = 0; v < m.num_vertices(); ++v)
    if (!g.graph.boundary_vertex[v]) {
      EXPECT_NEAR(angle[v], 2 * std::numbers::pi * (1 - g.quarters[v] / 4.0), 1e-6) << name << ": vertex " << v;
    }
}

Mesh mesh_of(const std::vector<Eigen::Vector3d>& points, const std::vector<Eigen::Vector3i>& faces) {
  Mesh m;
  m.V.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (size_t v = 0; v < points.size(); ++v) m.V.row(static_cast<Eigen::Index>(v)) = points[v].transpose();
  m.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (size_t f = 0; f < faces.size(); ++f)
    m.F.row(static_cast<Eigen::Index>(f)) = (faces[f] - Eigen::Vector3i::Ones()).transpose();
  return m;
}

// A unit square with its corners cut at 45 degrees, 26 faces (a Delaunay triangulation of
// random inner points): where a boundary side is at 45 degrees to the field, the field's
// turns are pi/4 to rounding.
Mesh chamfered_square() {
  return mesh_of({{0.2, 0, 0}, {0.4, 0, 0}, {0.6, 0, 0}, {0.8, 0, 0}, {1, 0.2, 0}, {1, 0.4, 0}, {1, 0.6, 0},
                  {1, 0.8, 0}, {0.8, 1, 0}, {0.6, 1, 0}, {0.4, 1, 0}, {0.2, 1, 0}, {0, 0.8, 0}, {0, 0.6, 0},
                  {0, 0.4, 0}, {0, 0.2, 0}, {0.2616121342493164, 0.29849114341412331, 0},
                  {0.600100525965654, 0.72856052681179462, 0}, {0.2749693679060381, 0.65743301487559258, 0},
                  {0.562265662780428, 0.15006226330533612, 0}, {0.43263079080478717, 0.66929729857452025, 0},
                  {0.39162483308002616, 0.18725256972009807, 0}},
                 {{20, 4, 5},   {6, 20, 5},   {20, 3, 4},   {17, 16, 1},  {18, 8, 9},   {20, 18, 21}, {6, 18, 20},
                  {10, 18, 9},  {11, 18, 10}, {18, 11, 21}, {2, 3, 20},   {22, 20, 21}, {17, 22, 21}, {22, 2, 20},
                  {2, 22, 1},   {22, 17, 1},  {17, 15, 16}, {19, 17, 21}, {14, 19, 13}, {15, 19, 14}, {19, 15, 17},
                  {19, 12, 13}, {19, 11, 12}, {11, 19, 21}, {18, 7, 8},   {7, 18, 6}});
}

std::vector<std::filesystem::path> disk_meshes() {
  const std::filesystem::path dir = std::filesystem::path(STRICTMIN_SHARED_DATA) / "disk";
  std::vector<std::filesystem::path> out;
  for (const char* name : {"bimba_1k", "hand", "cow_disk", "fish", "dragon"})
    if (std::filesystem::exists(dir / (std::string(name) + ".obj"))) out.push_back(dir / (std::string(name) + ".obj"));
  return out;
}

}  // namespace

TEST(BoundaryGraph, FansAreOpenAndLoopsCounted) {
  const Mesh box = open_box();
  const SurfaceGraph g = surface_graph(box, "box", true);
  EXPECT_EQ(g.num_boundary_loops, 1);
  EXPECT_EQ(g.euler_characteristic(), 1);
  int boundary_edges = 0;
  for (int e = 0; e < g.num_edges(); ++e)
    if (g.is_boundary_edge(e)) {
      ++boundary_edges;
      const int f = g.edge_faces(e, 0), i = g.edge_sides(e, 0);
      EXPECT_EQ(box.F(f, i), g.edges(e, 0));  // runs as in its face
      EXPECT_EQ(box.F(f, (i + 1) % 3), g.edges(e, 1));
    }
  EXPECT_EQ(boundary_edges, 4 * 3);  // the top rim: 4 sides of 3 cells
  for (int v = 0; v < g.num_vertices; ++v) {
    const int begin = g.fan_start[v], end = g.fan_start[v + 1];
    const bool on_rim = std::abs(box.V(v, 2) - 5.0) < 1e-12;
    EXPECT_EQ(static_cast<bool>(g.boundary_vertex[v]), on_rim) << v;
    if (!on_rim) continue;
    // An open fan: its first face leaves v along the boundary, its last reaches v along it.
    EXPECT_TRUE(g.is_boundary_edge(g.face_edges(g.fan_faces[begin], g.fan_corners[begin])));
    EXPECT_TRUE(g.is_boundary_edge(g.fan_edge(end - 1)));
    for (int k = begin; k + 1 < end; ++k) EXPECT_EQ(g.neighbour(g.fan_faces[k], (g.fan_corners[k] + 2) % 3), g.fan_faces[k + 1]);
  }
  const SurfaceGraph annulus = surface_graph(flat_annulus(), "annulus", true);
  EXPECT_EQ(annulus.num_boundary_loops, 2);
  EXPECT_EQ(annulus.euler_characteristic(), 0);
}

TEST(BoundaryGraph, RefusedUnlessAllowed) {
  expect_input_error([&] { surface_graph(open_box(), "box.obj"); }, {"box.obj", "1 boundary loop", "closed surfaces"});
}

// The smoothest field along the boundary is the axis-aligned field (zero energy) on the
// polycube pieces, without any pinning, and its indices are the corners': interior cones of
// the box's bottom, +1/4 at the annulus' outer corners, -1/4 at its inner ones.
TEST(BoundaryField, PolycubePiecesGetTheAxisAlignedField) {
  struct Case {
    const char* name;
    Mesh mesh;
    std::map<int, int> interior, boundary;
  };
  const std::vector<Case> cases = {
      {"open box", open_box(), {{1, 4}}, {}},
      {"flat annulus", flat_annulus(), {}, {{1, 4}, {-1, 4}}},
      {"open frame", open_frame(), {{1, 4}, {-1, 4}}, {}},
      // The window's corners: 3 pi / 2 of the surface around each (pi of the floor or roof, pi / 2 of the wall).
      {"frame with a window", frame_with_a_window(), {{1, 8}, {-1, 8}}, {{-1, 4}}},
  };
  for (const Case& c : cases) {
    const GParamOutcome g = global_parametrize(c.mesh, options(Method::L2), c.name);
    EXPECT_LT(g.field.energy, 1e-9) << c.name;
    EXPECT_EQ(index_counts(g.singular, g.graph, false), c.interior) << c.name;
    EXPECT_EQ(index_counts(g.singular, g.graph, true), c.boundary) << c.name;
    expect_poincare_hopf(c.mesh, g, c.name);
    expect_disk_cut(c.mesh, g, c.name);
  }
}

// The field along the boundary against dense linear algebra: on a curved open surface (the
// open box bulged toward a sphere), E recovered by polarization of field_energy, u fixed on
// the boundary faces to their boundary side's direction (fourth power), the rest solving
// E_II u_I = -E_IB u_B; normalized per face it must be our field.
TEST(BoundaryField, MatchesTheDenseDirichletSolve) {
  Mesh m = open_box(2);
  const Eigen::RowVector3d c(2.5, 2.5, 2.5);
  for (int v = 0; v < m.num_vertices(); ++v) {
    const Eigen::RowVector3d d = m.V.row(v) - c;
    m.V.row(v) = c + d * (0.6 + 0.4 * 2.5 * std::sqrt(3.0) / d.norm());
  }
  const SurfaceGraph g = surface_graph(m, "", true);
  const FaceFrames fr = face_frames(m, g);
  const int F = g.num_faces;
  using C = std::complex<double>;
  Eigen::MatrixXcd H(F, F);
  const auto q = [&](const Eigen::VectorXcd& x) { return field_energy(x, m, g, fr); };
  for (int f = 0; f < F; ++f)
    for (int h = 0; h < F; ++h) {
      Eigen::VectorXcd a = Eigen::VectorXcd::Zero(F), b = a;
      a(f) = 1;
      b(h) = 1;
      H(f, h) = 0.25 * (q(a + b) - q(a - b)) + C(0, 0.25) * (q(a - C(0, 1) * b) - q(a + C(0, 1) * b));
    }
  Eigen::VectorXcd fixed = Eigen::VectorXcd::Zero(F);
  for (int f = 0; f < F; ++f)
    for (int i = 0; i < 3; ++i)
      if (g.is_boundary_edge(g.face_edges(f, i))) {
        const Eigen::Vector3d d = (m.V.row(m.F(f, (i + 1) % 3)) - m.V.row(m.F(f, i))).transpose();
        fixed(f) = std::polar(1.0, 4.0 * std::atan2(d.dot(fr.y.row(f)), d.dot(fr.x.row(f))));
      }
  std::vector<int> free;
  for (int f = 0; f < F; ++f)
    if (fixed(f) == C(0, 0)) free.push_back(f);
  const int n = static_cast<int>(free.size());
  Eigen::MatrixXcd A(n, n);
  Eigen::VectorXcd b = -H * fixed, rhs(n);
  for (int r = 0; r < n; ++r) {
    rhs(r) = b(free[r]);
    for (int s = 0; s < n; ++s) A(r, s) = H(free[r], free[s]);
  }
  const Eigen::VectorXcd x = A.llt().solve(rhs);
  Eigen::VectorXcd expected = fixed;
  for (int r = 0; r < n; ++r) expected(free[r]) = x(r) / std::abs(x(r));
  const CrossField ours = smoothest_cross_field(m, g, fr);
  EXPECT_LT((ours.u - expected).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_GT(ours.energy, 1e-3);  // curved: the field cannot be parallel
}

// With free translations every method maps the polycube pieces without distortion, and the
// seams hold.
TEST(BoundaryMap, EveryMethodMapsPolycubePiecesWithZeroDistortion) {
  const std::vector<std::pair<const char*, Mesh>> meshes = {
      {"open box", open_box(2)}, {"flat annulus", flat_annulus(2)}, {"frame with a window", frame_with_a_window(2)}};
  for (const auto& [name, m] : meshes)
    for (Method method : {Method::L2, Method::Linf, Method::Relax, Method::Direct, Method::Irls, Method::Lp}) {
      const GParamOutcome g = global_parametrize(m, options(method), name);
      EXPECT_EQ(g.result.status, SolveStatus::Solved) << name << " " << method_name(method) << ": " << g.result.message;
      EXPECT_LT(g.measured.stats.max, 1e-9) << name << " " << method_name(method);
      EXPECT_LT(g.seam_error, 1e-9) << name << " " << method_name(method);
      EXPECT_EQ(g.measured.stats.flipped, 0) << name << " " << method_name(method);
    }
}

// Turns of exactly pi/4 (to rounding): a right isosceles triangle (its 45-degree corners
// meet the field along the other side at 45 degrees) and the chamfered square. Each edge's
// turn is taken once for both its ends, and the cut's matchings from the same turns: the
// indices add up to 4 chi, the seams hold, and the map's cones are the ones reported (the
// indices summed to 5 and 7, and the chamfered square's seams were off by 24 to 28 units,
// each end of an edge rounding its pi/4 its own way).
TEST(BoundaryMap, TurnsOfAnEighthOfATurnAgreeEverywhere) {
  const std::vector<std::pair<const char*, Mesh>> meshes = {
      {"right triangle", mesh_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{1, 2, 3}})}, {"chamfered square", chamfered_square()}};
  for (const auto& [name, m] : meshes)
    for (Method method : {Method::L2, Method::Linf, Method::Relax, Method::Direct}) {
      const GParamOutcome g = global_parametrize(m, options(method), name);
      expect_poincare_hopf(m, g, name);
      EXPECT_LT(g.seam_error, 1e-9) << name << " " << method_name(method);
      EXPECT_EQ(g.result.status, SolveStatus::Solved) << name << " " << method_name(method);
      expect_map_cones_match_indices(m, g, std::string(name) + " " + method_name(method));
    }
}

// A round disk of two rings of 12 around a centre, symmetric: the smoothest field along its
// boundary has one singularity of index +1 at the centre (a cone of angle 0: every method
// collapsed the whole map, 36 of 36 faces flipped, and said solved). Spread over the ring it
// becomes four +1/4, and the map is a proper one.
TEST(BoundaryField, AFullTurnSingularityIsSpread) {
  std::vector<Eigen::Vector3d> points{{0, 0, 0}};
  for (int ring = 1; ring <= 2; ++ring)
    for (int k = 0; k < 12; ++k)
      points.emplace_back(0.5 * ring * std::cos(k * std::numbers::pi / 6), 0.5 * ring * std::sin(k * std::numbers::pi / 6), 0);
  std::vector<Eigen::Vector3i> faces;
  for (int k = 0; k < 12; ++k) {
    const int a = 2 + k, b = 2 + (k + 1) % 12, c = 14 + k, d = 14 + (k + 1) % 12;  // 1-based
    faces.emplace_back(1, a, b);
    faces.emplace_back(a, c, d);
    faces.emplace_back(a, d, b);
  }
  const Mesh disk = mesh_of(points, faces);
  const GParamOutcome g = global_parametrize(disk, options(Method::Linf), "round disk");
  EXPECT_GE(g.spread_singularities, 1);
  EXPECT_EQ(g.full_turn_singularities, 0);
  EXPECT_TRUE(g.warnings.empty());
  EXPECT_EQ(index_counts(g.singular, g.graph, false), (std::map<int, int>{{1, 4}}));
  expect_poincare_hopf(disk, g, "round disk");
  EXPECT_EQ(g.measured.stats.flipped, 0);
  EXPECT_LT(g.measured.stats.max, 0.9);
  EXPECT_LT(g.seam_error, 1e-9);
  expect_map_cones_match_indices(disk, g, "round disk");

  // The same field given by the user (each face's direction along the circles) is kept as it
  // is: the +1 at the centre stays, the map folds there, and the outcome warns of it.
  Eigen::MatrixXd circles(disk.num_elements(), 3);
  for (int f = 0; f < disk.num_elements(); ++f) {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (int i = 0; i < 3; ++i) centre += disk.V.row(disk.F(f, i)).transpose() / 3.0;
    circles.row(f) = Eigen::Vector3d(-centre.y(), centre.x(), 0).normalized().transpose();
  }
  GParamOptions given = options(Method::Linf);
  given.field = circles;
  const GParamOutcome kept = global_parametrize(disk, given, "round disk");
  EXPECT_EQ(kept.spread_singularities, 0);
  EXPECT_EQ(kept.full_turn_singularities, 1);
  EXPECT_EQ(index_counts(kept.singular, kept.graph, false), (std::map<int, int>{{4, 1}}));
  expect_poincare_hopf(disk, kept, "round disk, given field");
  ASSERT_EQ(kept.warnings.size(), 1u);
  EXPECT_NE(kept.warnings[0].find("index +1 or more"), std::string::npos) << kept.warnings[0];
  EXPECT_GT(kept.measured.stats.flipped, 0);
}

// A disk with no interior singularity has no seam: the field's map is a free-boundary
// parametrization against the field's frames.
TEST(BoundaryMap, AFlatSquareHasNoSeam) {
  const Mesh cube = make_cube_surface(4);
  const Mesh square = without_faces(cube, [&](int f) { return !on_plane(cube, 2, 5.0)(f); });
  const GParamOutcome g = global_parametrize(square, options(Method::Linf), "square");
  EXPECT_EQ(g.cut.num_cut_edges, 0);
  EXPECT_EQ(index_counts(g.singular, g.graph, true), (std::map<int, int>{{1, 4}}));
  EXPECT_LT(g.measured.stats.max, 1e-9);
}

// The shared disk meshes: Poincare-Hopf with boundary indices, a disk cut, every index a
// multiple of 1/4, seams holding, and the strict order (linf below l2, relax never above linf).
TEST(BoundarySharedMeshes, PoincareHopfSeamsAndStrictOrder) {
  const auto files = disk_meshes();
  if (files.empty()) GTEST_SKIP() << "no disk meshes under " << STRICTMIN_SHARED_DATA;
  for (const auto& file : files) {
    const Mesh m = read_mesh(file.string());
    std::map<Method, double> top;
    for (Method method : {Method::L2, Method::Linf, Method::Relax}) {
      GParamOptions o;
      o.solver.method = method;
      o.solver.relax.sweeps = 10;
      const GParamOutcome g = global_parametrize(m, o, file.string());
      top[method] = g.measured.stats.max;
      EXPECT_EQ(g.result.status, SolveStatus::Solved) << file << " " << method_name(method) << ": " << g.result.message;
      EXPECT_LT(g.seam_error, 1e-9) << file << " " << method_name(method);
      EXPECT_TRUE(g.mapped.UV.allFinite()) << file;
      if (method == Method::L2) {
        EXPECT_EQ(g.graph.num_boundary_loops, 1) << file;
        expect_poincare_hopf(m, g, file.string());
        expect_disk_cut(m, g, file.string());
      }
      if (method == Method::Linf) {
        EXPECT_LE(g.result.lower_bound, g.measured.stats.max + 1e-12) << file;
        expect_map_cones_match_indices(m, g, file.string());
      }
    }
    EXPECT_LT(top[Method::Linf], top[Method::L2]) << file;
    EXPECT_LE(top[Method::Relax], top[Method::Linf] + 1e-4) << file;
  }
}

// Relabelling the vertices, reordering the faces (another dual tree, so another cut) and
// moving the surface rigidly change no figure.
TEST(BoundaryMap, InvariantUnderRelabellingAndRigidMotion) {
  const Mesh m = frame_with_a_window(2);
  Mesh bumped = m;  // curved, so the optimum is not zero
  for (int v = 0; v < m.num_vertices(); ++v) bumped.V(v, 2) += 0.1 * std::sin(3.0 * m.V(v, 0)) * std::cos(2.0 * m.V(v, 1));
  const GParamOutcome a = global_parametrize(bumped, options(Method::Linf));
  std::vector<int> perm(bumped.num_vertices());
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), std::mt19937(7));
  Mesh moved = bumped;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (int v = 0; v < bumped.num_vertices(); ++v)
    moved.V.row(perm[v]) = (R * bumped.V.row(v).transpose() + Eigen::Vector3d(3, -1, 2)).transpose();
  std::vector<int> order(bumped.num_elements());
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937(8));
  for (int f = 0; f < bumped.num_elements(); ++f)
    for (int i = 0; i < 3; ++i) moved.F(order[f], i) = perm[bumped.F(f, (i + f) % 3)];
  const GParamOutcome b = global_parametrize(moved, options(Method::Linf));
  EXPECT_GT(a.measured.stats.max, 1e-3);
  EXPECT_NEAR(a.measured.stats.max, b.measured.stats.max, 1e-6);
  EXPECT_EQ(a.singular.size(), b.singular.size());
  EXPECT_LT(b.seam_error, 1e-9);
}

TEST(BoundaryOptions, ClosedOnlyOptionsAreRefusedByName) {
  const Mesh box = open_box(2);
  GParamOptions o = options(Method::L2);
  o.integer_grid = true;
  expect_input_error([&] { global_parametrize(box, o, "box.obj"); }, {"box.obj", "1 boundary loop", "--integer-grid"});
  o = options(Method::L2);
  o.parallel_field = true;
  expect_input_error([&] { global_parametrize(box, o, "box.obj"); }, {"--parallel", "closed surfaces"});
  o = options(Method::L2);
  o.field_options.unit = true;
  expect_input_error([&] { global_parametrize(box, o, "box.obj"); }, {"--field unit", "closed surfaces"});
  o = options(Method::L2);
  o.cones = std::vector<int>(static_cast<size_t>(box.num_vertices()), 0);
  expect_input_error([&] { global_parametrize(box, o, "box.obj"); }, {"--cones", "closed surfaces"});
}
