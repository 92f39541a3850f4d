// Quad meshes from integer-grid maps (tasks/quad_extraction.h), against known answers: the
// polycubes' grids (every quad a square of side h at integer multiples of h), the cones'
// valences, Euler characteristics, and the holes a map's flips leave.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <optional>
#include <random>

#include <Eigen/Geometry>

#include "expect_input_error.h"
#include "strictmin/mesh/polycube.h"
#include "strictmin/tasks/gparam.h"
#include "strictmin/tasks/quad_extraction.h"
#include "test_meshes.h"

using namespace strictmin;
using strictmin::test_support::expect_input_error;
using strictmin::test_support::shared_closed_mesh;

namespace {

// An integer-grid map of a polycube at edge length h with its axis-aligned field (pinned
// on face 0), as gparam makes it.
GParamOutcome polycube_grid_map(const Mesh& mesh, double h) {
  GParamOptions o;
  o.field_options.pin_face = 0;
  o.field_options.pin_direction = Eigen::Vector3d::UnitX();
  o.solver.method = Method::L2;
  o.edge_length = h;
  o.integer_grid = true;
  return global_parametrize(mesh, o);
}

// Fertility (genus 4) at 10000 quads under the L-infinity guide and method: a flip-free
// integer-grid map, made once for the tests that use it; null without the shared data.
const GParamOutcome* fertility_on_a_fine_grid() {
  static const std::optional<GParamOutcome> map = []() -> std::optional<GParamOutcome> {
    const Mesh* m = shared_closed_mesh("fertility");
    if (!m) return std::nullopt;
    GParamOptions o;
    o.quads = 10000;
    o.integer_grid = true;
    o.grid_guide = GParamOptions::GridGuide::Linf;
    o.solver.method = Method::Linf;
    return global_parametrize(*m, o);
  }();
  return map ? &*map : nullptr;
}

// Every quad of side h, square (its diagonals sqrt(2) h), with its vertices at integer
// multiples of h and its normal (from the diagonals) pointing away from `inside`.
void expect_grid_of_squares(const QuadMesh& q, double h, const Eigen::Vector3d& inside) {
  for (int i = 0; i < q.num_quads(); ++i) {
    Eigen::Vector3d p[4];
    for (int k = 0; k < 4; ++k) p[k] = q.V.row(q.Q(i, k)).transpose();
    for (int k = 0; k < 4; ++k) {
      EXPECT_NEAR((p[(k + 1) % 4] - p[k]).norm(), h, 1e-9) << "quad " << i << " side " << k;
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(p[k](c) / h, std::round(p[k](c) / h), 1e-9) << "quad " << i;
    }
    EXPECT_NEAR((p[2] - p[0]).norm(), std::sqrt(2.0) * h, 1e-9) << "quad " << i;
    EXPECT_NEAR((p[3] - p[1]).norm(), std::sqrt(2.0) * h, 1e-9) << "quad " << i;
    const Eigen::Vector3d normal = (p[2] - p[0]).cross(p[3] - p[1]);
    const Eigen::Vector3d centre = (p[0] + p[1] + p[2] + p[3]) / 4;
    EXPECT_GT(normal.dot(centre - inside), 0) << "quad " << i << " faces inward";
  }
}

}  // namespace

// The cube of side 5 at h = 1 and 0.5: its 6 (5/h)^2 grid squares, 6 (5/h - 1)^2 + 12 (5/h - 1)
// + 8 vertices, the 8 corners of valence 3 (cones of index 1/4), Euler characteristic 2.
TEST(QuadExtraction, TheCubeGivesItsGrid) {
  for (double h : {1.0, 0.5}) {
    const GParamOutcome g = polycube_grid_map(make_cube_surface(3), h);
    ASSERT_TRUE(g.result.ok()) << g.result.message;
    const QuadExtraction x = extract_quads(g.mapped);
    const int n = static_cast<int>(std::lround(5 / h));
    EXPECT_TRUE(x.complete) << "h = " << h;
    EXPECT_EQ(x.mesh.num_quads(), 6 * n * n);
    EXPECT_EQ(x.mesh.num_vertices(), 6 * (n - 1) * (n - 1) + 12 * (n - 1) + 8);
    EXPECT_EQ(x.euler_characteristic, 2);
    EXPECT_EQ(x.cones, 8);
    EXPECT_EQ(x.valences.at(3), 8);
    EXPECT_EQ(x.valences.at(4), x.mesh.num_vertices() - 8);
    EXPECT_EQ(x.dropped_squares + x.boundary_edges + x.non_manifold_edges + x.flipped_triangles, 0);
    EXPECT_NEAR(x.uv_area, 6.0 * n * n, 1e-9);
    expect_grid_of_squares(x.mesh, h, Eigen::Vector3d(2.5, 2.5, 2.5));
    EXPECT_NEAR(x.quality.min_angle_deg, 90, 1e-6);
    EXPECT_NEAR(x.quality.max_angle_deg, 90, 1e-6);
    EXPECT_NEAR(x.quality.min_scaled_jacobian, 1, 1e-9);
    EXPECT_NEAR(x.quality.min_side, h, 1e-9);
    EXPECT_NEAR(x.quality.max_side, h, 1e-9);
    EXPECT_NEAR(x.quality.mean_side, h, 1e-9);
  }
}

// Quality figures against closed forms: a rhombus of side 1 with angles of 60 and 120 degrees
// (scaled Jacobian sin 60), and a dart whose reflex corner has a negative scaled Jacobian.
TEST(QuadExtraction, QualityOfARhombusAndADart) {
  QuadMesh q;
  const double s = std::sqrt(3.0) / 2;
  q.V.resize(8, 3);
  q.V << 0, 0, 0, 1, 0, 0, 1.5, s, 0, 0.5, s, 0,  // rhombus
      10, 0, 0, 12, 0, 0, 12, 2, 0, 11.5, 0.5, 0;  // dart, reflex at (11.5, 0.5)
  q.Q.resize(1, 4);
  q.Q << 0, 1, 2, 3;
  QuadQuality r = quad_quality(q);
  EXPECT_NEAR(r.min_angle_deg, 60, 1e-9);
  EXPECT_NEAR(r.max_angle_deg, 120, 1e-9);
  EXPECT_NEAR(r.min_scaled_jacobian, s, 1e-12);
  EXPECT_NEAR(r.min_side, 1, 1e-12);
  EXPECT_NEAR(r.max_side, 1, 1e-12);
  EXPECT_NEAR(r.mean_side, 1, 1e-12);
  q.Q << 4, 5, 6, 7;
  r = quad_quality(q);
  // At the reflex corner the side to the next corner, (10, 0), turns clockwise to the side to
  // the previous one, (12, 2): (-1.5, -0.5) x (0.5, 1.5) = -2 over |a| |b| = 2.5.
  EXPECT_NEAR(r.min_scaled_jacobian, -0.8, 1e-12);
  EXPECT_NEAR(r.min_side, std::sqrt(2.5), 1e-12);
  EXPECT_NEAR(r.max_side, 2, 1e-12);
  EXPECT_TRUE(std::isnan(quad_quality(QuadMesh{}).min_angle_deg));
}

// The frame of 8 unit cubes (genus 1) at h = 0.5: its area 32 in 128 squares, 8 convex
// corners of valence 3 and 8 saddle corners of valence 5, Euler characteristic 0.
TEST(QuadExtraction, TheFrameHasItsConvexAndSaddleCorners) {
  const GParamOutcome g = polycube_grid_map(make_frame_surface(2), 0.5);
  ASSERT_TRUE(g.result.ok()) << g.result.message;
  const QuadExtraction x = extract_quads(g.mapped);
  EXPECT_TRUE(x.complete);
  EXPECT_EQ(x.mesh.num_quads(), 128);
  EXPECT_EQ(x.euler_characteristic, 0);
  EXPECT_EQ(x.surface_euler_characteristic, 0);
  EXPECT_EQ(x.valences.at(3), 8);
  EXPECT_EQ(x.valences.at(5), 8);
  EXPECT_EQ(x.valences.size(), 3u);
  // Each quad is a square of side 0.5 at multiples of 0.5 (normals checked in the cube test).
  for (int i = 0; i < x.mesh.num_quads(); ++i)
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d a = x.mesh.V.row(x.mesh.Q(i, k)), b = x.mesh.V.row(x.mesh.Q(i, (k + 1) % 4));
      EXPECT_NEAR((b - a).norm(), 0.5, 1e-9);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(2 * a(c), std::round(2 * a(c)), 1e-9);
    }
}

// Vertices a hair (1e-5, ten times the tolerance) from grid points: the grid point then lies
// in a face that meets its squares only in slivers thinner than the tolerance, which the
// squares' floods do not enter; each square still finds it as its corner (one vertex), and
// the quad mesh is the cube's.
TEST(QuadExtraction, VerticesAHairFromTheGridChangeNothing) {
  const GParamOutcome g = polycube_grid_map(make_cube_surface(3), 1.0);
  Mesh m = g.mapped;
  std::vector<char> on_cut(m.num_vertices(), 0);  // the seams' vertices (the cones among them)
  for (int e = 0; e < g.graph.num_edges(); ++e)
    if (g.cut.cut[e]) on_cut[g.graph.edges(e, 0)] = on_cut[g.graph.edges(e, 1)] = 1;
  const auto flip_free = [&] {
    for (int f = 0; f < m.num_elements(); ++f) {
      const Eigen::Vector2d a = m.UV.row(m.FUV(f, 0)), b = m.UV.row(m.FUV(f, 1)), c = m.UV.row(m.FUV(f, 2));
      const Eigen::Vector2d u = b - a, w = c - a;
      if (!(u.x() * w.y() - u.y() * w.x() > 0)) return false;
    }
    return true;
  };
  int moved = 0;
  for (int v = 0; v < m.num_vertices(); ++v) {
    if (on_cut[v]) continue;
    const int w = m.FUV(g.graph.fan_faces[g.graph.fan_start[v]], g.graph.fan_corners[g.graph.fan_start[v]]);
    const Eigen::RowVector2d before = m.UV.row(w);
    m.UV.row(w) << std::round(before.x()) + 1e-5, std::round(before.y()) - 7e-6;
    if (flip_free())
      ++moved;
    else
      m.UV.row(w) = before;
  }
  ASSERT_GT(moved, 10);
  const QuadExtraction x = extract_quads(m);
  EXPECT_TRUE(x.complete);
  EXPECT_EQ(x.mesh.num_quads(), 150);
  EXPECT_EQ(x.mesh.num_vertices(), 152);
  EXPECT_EQ(x.valences.at(3), 8);
  EXPECT_EQ(x.valences.at(4), 144);
}

// Folds made at random (vertices away from the seams moved by up to 1.5 grid units): the
// quads left are a manifold mesh of distinct corners, and a map with no flipped triangle
// left is extracted completely.
TEST(QuadExtraction, RandomFoldsLeaveAManifoldQuadMesh) {
  const GParamOutcome g = polycube_grid_map(make_frame_surface(2), 0.5);
  ASSERT_TRUE(g.result.ok());
  std::vector<int> movable;  // wedges of vertices off the cut
  std::vector<char> on_cut(g.mapped.num_vertices(), 0);
  for (int e = 0; e < g.graph.num_edges(); ++e)
    if (g.cut.cut[e]) on_cut[g.graph.edges(e, 0)] = on_cut[g.graph.edges(e, 1)] = 1;
  for (int v = 0; v < g.mapped.num_vertices(); ++v)
    if (!on_cut[v]) movable.push_back(g.mapped.FUV(g.graph.fan_faces[g.graph.fan_start[v]], g.graph.fan_corners[g.graph.fan_start[v]]));
  int with_holes = 0;
  for (unsigned seed = 1; seed <= 30; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> offset(-1.5, 1.5);
    Mesh m = g.mapped;
    for (int k = 0; k < 1 + static_cast<int>(seed % 5); ++k)
      m.UV.row(movable[rng() % movable.size()]) += Eigen::RowVector2d(offset(rng), offset(rng));
    const QuadExtraction x = extract_quads(m);
    EXPECT_EQ(x.non_manifold_edges, 0) << "seed " << seed;
    for (int i = 0; i < x.mesh.num_quads(); ++i)
      for (int a = 0; a < 4; ++a)
        for (int b = a + 1; b < 4; ++b) EXPECT_NE(x.mesh.Q(i, a), x.mesh.Q(i, b)) << "seed " << seed;
    if (x.flipped_triangles == 0) {
      EXPECT_TRUE(x.complete) << "seed " << seed;
    } else {
      EXPECT_FALSE(x.complete) << "seed " << seed;
      EXPECT_GT(x.dropped_squares, 0) << "seed " << seed;
      ++with_holes;
    }
    EXPECT_LE(x.mesh.num_quads(), 128) << "seed " << seed;
  }
  EXPECT_GT(with_holes, 10);
}

// Folds away from the cones on the cube (a vertex off the seams moved by a grid unit and a half
// along u) leave holes; filled, each hole takes the grid's squares inside its boundary: the
// cube's quad mesh again (150 quads, 152 vertices, the 8 corners of valence 3), its filled
// vertices off the input's triangles but near the cube's faces.
TEST(QuadExtraction, FilledHolesGiveTheCubesQuadMeshBack) {
  const GParamOutcome g = polycube_grid_map(make_cube_surface(3), 1.0);
  ASSERT_TRUE(g.result.ok());
  std::vector<char> on_cut(g.mapped.num_vertices(), 0);
  for (int e = 0; e < g.graph.num_edges(); ++e)
    if (g.cut.cut[e]) on_cut[g.graph.edges(e, 0)] = on_cut[g.graph.edges(e, 1)] = 1;
  int filled = 0, folded = 0;
  for (int v = 0; v < g.mapped.num_vertices(); ++v) {
    if (on_cut[v]) continue;
    Mesh m = g.mapped;
    m.UV.row(m.FUV(g.graph.fan_faces[g.graph.fan_start[v]], g.graph.fan_corners[g.graph.fan_start[v]])) +=
        Eigen::RowVector2d(1.5, 0.2);
    const QuadExtraction holes = extract_quads(m);
    if (holes.flipped_triangles == 0) continue;
    ++folded;
    EXPECT_FALSE(holes.complete);
    QuadExtractionOptions o;
    o.fill_holes = true;
    const QuadExtraction x = extract_quads(m, o);
    EXPECT_EQ(x.non_manifold_edges, 0) << "vertex " << v;
    if (!x.complete) continue;  // a hole that touches a cone or meets another stays
    ++filled;
    EXPECT_GT(x.filled_squares, 0);
    EXPECT_EQ(x.mesh.num_quads(), 150) << "vertex " << v;
    EXPECT_EQ(x.mesh.num_vertices(), 152) << "vertex " << v;
    EXPECT_EQ(x.valences.at(3), 8);
    EXPECT_EQ(x.holes, 0);
    EXPECT_EQ(x.euler_characteristic, 2);
    int placed = 0;  // the filled holes' inner vertices: off the surface's triangles
    for (int i = 0; i < x.mesh.num_vertices(); ++i) {
      if (x.mesh.vertex_face(i) >= 0) continue;
      ++placed;
      const Eigen::Vector3d p = x.mesh.V.row(i).transpose() - Eigen::Vector3d(2.5, 2.5, 2.5);
      EXPECT_NEAR(p.cwiseAbs().maxCoeff(), 2.5, 0.25) << "vertex " << v << ": filled vertex " << i;
    }
    EXPECT_EQ(placed, x.mesh.num_vertices() - holes.mesh.num_vertices()) << "vertex " << v;
    EXPECT_GT(x.quality.min_scaled_jacobian, 0) << "vertex " << v;
  }
  std::printf("%d folds, %d filled completely\n", folded, filled);
  EXPECT_GE(folded, 10);
  EXPECT_GE(filled, 3);
}

// Relabelling the vertices, the faces and each face's corners gives the same quad mesh (the
// same vertex positions, the same counts).
TEST(QuadExtraction, RelabellingChangesNothing) {
  const GParamOutcome g = polycube_grid_map(make_frame_surface(2), 0.5);
  ASSERT_TRUE(g.result.ok());
  const Mesh& m = g.mapped;
  std::mt19937 rng(7);
  std::vector<int> vertex_order(m.num_vertices()), face_order(m.num_elements());
  std::iota(vertex_order.begin(), vertex_order.end(), 0);
  std::iota(face_order.begin(), face_order.end(), 0);
  std::shuffle(vertex_order.begin(), vertex_order.end(), rng);
  std::shuffle(face_order.begin(), face_order.end(), rng);
  Mesh r = m;
  for (int v = 0; v < m.num_vertices(); ++v) r.V.row(vertex_order[v]) = m.V.row(v);
  for (int f = 0; f < m.num_elements(); ++f) {
    const int shift = f % 3;
    for (int i = 0; i < 3; ++i) {
      r.F(face_order[f], i) = vertex_order[m.F(f, (i + shift) % 3)];
      r.FUV(face_order[f], i) = m.FUV(f, (i + shift) % 3);
    }
  }
  const QuadExtraction a = extract_quads(m), b = extract_quads(r);
  ASSERT_TRUE(a.complete && b.complete);
  ASSERT_EQ(a.mesh.num_vertices(), b.mesh.num_vertices());
  EXPECT_EQ(a.mesh.num_quads(), b.mesh.num_quads());
  EXPECT_EQ(a.valences, b.valences);
  const auto sorted_rows = [](const Eigen::MatrixXd& V) {
    std::vector<std::array<double, 3>> rows;
    for (int i = 0; i < V.rows(); ++i)
      rows.push_back({std::round(V(i, 0) * 1e6), std::round(V(i, 1) * 1e6), std::round(V(i, 2) * 1e6)});
    std::sort(rows.begin(), rows.end());
    return rows;
  };
  EXPECT_EQ(sorted_rows(a.mesh.V), sorted_rows(b.mesh.V));
}

// A real surface of genus 4 on a fine grid (flip-free with the L-infinity guide): complete,
// Euler characteristic -6, one vertex of valence 3 per cone of index 1/4 and of valence 5
// per cone of index -1/4, one quad per unit of UV area, sides near h.
TEST(QuadExtraction, FertilityOnAFineGridIsComplete) {
  const GParamOutcome* fine = fertility_on_a_fine_grid();
  if (!fine) GTEST_SKIP() << "../shared/data/closed/fertility.obj not available";
  const GParamOutcome& g = *fine;
  ASSERT_EQ(g.measured.stats.flipped, 0);
  const QuadExtraction x = extract_quads(g.mapped);
  EXPECT_TRUE(x.complete);
  EXPECT_EQ(x.euler_characteristic, -6);
  int convex = 0, saddle = 0;
  for (const Singularity& s : g.singular) (s.quarters == 1 ? convex : saddle) += 1;
  EXPECT_EQ(x.valences.at(3), convex);
  EXPECT_EQ(x.valences.at(5), saddle);
  EXPECT_EQ(x.mesh.num_quads(), std::lround(x.uv_area));
  std::vector<double> sides;
  for (int i = 0; i < x.mesh.num_quads(); ++i)
    for (int k = 0; k < 4; ++k)
      sides.push_back((x.mesh.V.row(x.mesh.Q(i, k)) - x.mesh.V.row(x.mesh.Q(i, (k + 1) % 4))).norm() / g.edge_length);
  std::nth_element(sides.begin(), sides.begin() + sides.size() / 2, sides.end());
  EXPECT_NEAR(sides[sides.size() / 2], 1.0, 0.1);
}

// A coarse grid whose map flips triangles: the squares next to them are left out, and what
// is left is a manifold quad mesh with holes.
TEST(QuadExtraction, FlipsLeaveHolesInAManifoldQuadMesh) {
  const Mesh* m = shared_closed_mesh("cow");
  if (!m) GTEST_SKIP() << "../shared/data/closed/cow.obj not available";
  GParamOptions o;
  o.integer_grid = true;
  o.solver.method = Method::L2;
  const GParamOutcome g = global_parametrize(*m, o);
  ASSERT_GT(g.measured.stats.flipped, 0);
  const QuadExtraction x = extract_quads(g.mapped);
  EXPECT_FALSE(x.complete);
  EXPECT_EQ(x.flipped_triangles, g.measured.stats.flipped);
  EXPECT_GT(x.squares_touching_flips, 0);
  EXPECT_GT(x.holes, 0);
  EXPECT_GT(x.boundary_edges, 0);
  EXPECT_EQ(x.non_manifold_edges, 0);
  // Squares away from the folds are all there: those kept and those left out together make
  // up the UV area (to within the folds' double cover).
  EXPECT_LE(x.mesh.num_quads() + x.dropped_squares, x.uv_area + 1e-6);
  EXPECT_GE(x.mesh.num_quads() + x.dropped_squares, 0.98 * x.uv_area);
}

TEST(QuadExtraction, MapsThatAreNotIntegerGridMapsAreRefused) {
  const Mesh cube = make_cube_surface(3);
  expect_input_error([&] { extract_quads(cube, {}, "cube.obj"); }, {"cube.obj", "no per-corner UVs"});

  // A seamless map at h = 0.7 without rounding: the seams' translations are not integers.
  GParamOptions o;
  o.field_options.pin_face = 0;
  o.field_options.pin_direction = Eigen::Vector3d::UnitX();
  o.edge_length = 0.7;
  o.solver.method = Method::L2;
  const GParamOutcome free_map = global_parametrize(cube, o);
  expect_input_error([&] { extract_quads(free_map.mapped, {}, "free.obj"); },
                     {"free.obj", "translation", "misses a pair of integers"});

  // The integer-grid map moved by (1/2, 1/2): the translations stay integers (I - R moves
  // (1/2, 1/2) to an integer vector for every quarter turn R), the cones go half-way.
  GParamOutcome grid = polycube_grid_map(cube, 1.0);
  grid.mapped.UV.rowwise() += Eigen::RowVector2d(0.5, 0.5);
  expect_input_error([&] { extract_quads(grid.mapped, {}, "half.obj"); },
                     {"half.obj", "cone of index 1/4", "off the nearest integer point"});

  // Two sides of an edge that no quarter turn relates.
  Mesh torn = polycube_grid_map(cube, 1.0).mapped;
  torn.UV.conservativeResize(torn.UV.rows() + 1, 2);
  torn.UV.row(torn.UV.rows() - 1) << 100.25, -3;
  torn.FUV(0, 0) = static_cast<int>(torn.UV.rows() - 1);
  expect_input_error([&] { extract_quads(torn, {}, "torn.obj"); }, {"torn.obj", "edge", "not seamless"});

  // An integer-grid map whose UVs (near 40) are off the grid by 1e-13, within their round-off
  // (about 5.7e-13), checked with a tolerance of 1e-16: refused, and the message says that the
  // tolerance asks for more digits than the UVs have (it said "(2, 1) and (2, 1) differ by more
  // than a quarter turn", or showed the tolerance as 0.000000).
  Mesh hair = polycube_grid_map(cube, 1.0).mapped;
  for (Eigen::Index i = 0; i < hair.UV.rows(); ++i) hair.UV.row(i) += Eigen::RowVector2d(40 + 1e-13 * (i % 3), 40);
  EXPECT_NO_THROW(extract_quads(hair, {}, "hair.obj"));
  QuadExtractionOptions strict;
  strict.tolerance = 1e-16;
  expect_input_error([&] { extract_quads(hair, strict, "hair.obj"); },
                     {"hair.obj", "round-off of UVs near", "give a larger --tolerance"});

  // A surface with a boundary (one face removed).
  Mesh open = polycube_grid_map(cube, 1.0).mapped;
  open.F = open.F.bottomRows(open.F.rows() - 1).eval();
  open.FUV = open.FUV.bottomRows(open.FUV.rows() - 1).eval();
  expect_input_error([&] { extract_quads(open, {}, "open.obj"); }, {"open.obj", "boundary loop", "closed surfaces"});

  // UVs not in grid units (the cube's map scaled by 1e5: still an integer-grid map, of 1.5e12
  // squares) are refused before any work.
  Mesh huge = polycube_grid_map(cube, 1.0).mapped;
  huge.UV *= 1e5;
  expect_input_error([&] { extract_quads(huge, {}, "huge.obj"); }, {"huge.obj", "grid units"});

  // Two cubes in one file: each surface is extracted on its own.
  Mesh two = polycube_grid_map(cube, 1.0).mapped;
  const int n = two.num_vertices(), m = two.num_elements(), u = static_cast<int>(two.UV.rows());
  two.V.conservativeResize(2 * n, 3);
  two.V.bottomRows(n) = two.V.topRows(n).rowwise() + Eigen::RowVector3d(10, 0, 0);
  two.F.conservativeResize(2 * m, 3);
  two.F.bottomRows(m) = two.F.topRows(m).array() + n;
  two.UV.conservativeResize(2 * u, 2);
  two.UV.bottomRows(u) = two.UV.topRows(u);
  two.FUV.conservativeResize(2 * m, 3);
  two.FUV.bottomRows(m) = two.FUV.topRows(m).array() + u;
  expect_input_error([&] { extract_quads(two, {}, "two.obj"); }, {"two.obj", "2 connected components", "quad extraction"});

  QuadExtractionOptions bad;
  bad.tolerance = 0;
  expect_input_error([&] { extract_quads(grid.mapped, bad); }, {"tolerance"});
}

// The cube's map moved by large integers: the same 150 quads (the squares' coverage is
// measured about each square's centre, so the UVs' magnitude does not eat its digits).
TEST(QuadExtraction, LargeIntegerTranslationsChangeNothing) {
  const GParamOutcome g = polycube_grid_map(make_cube_surface(3), 1.0);
  for (double offset : {1e6, 1e7, 1e8}) {
    Mesh m = g.mapped;
    m.UV.rowwise() += Eigen::RowVector2d(offset, -offset);
    const QuadExtraction x = extract_quads(m);
    EXPECT_TRUE(x.complete) << "offset " << offset;
    EXPECT_EQ(x.mesh.num_quads(), 150) << "offset " << offset;
    EXPECT_EQ(x.squares_not_covered_once, 0) << "offset " << offset;
  }
}

// A tetrahedron in one chart (no seams, its four vertices' UVs shared), one face flipped
// under the other three: its signed UV area is 0 whatever the spike's height.
Mesh spiked_tetrahedron(const Eigen::Matrix<double, 4, 2>& uv) {
  Mesh m;
  m.V.resize(4, 3);
  m.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  m.F.resize(4, 3);
  m.F << 0, 2, 1, 0, 1, 3, 1, 2, 3, 2, 0, 3;
  m.UV = uv;
  m.FUV = m.F;
  return m;
}

// UVs far from grid units are refused before any work, also when the triangles' signed
// areas cancel (a double cover of a tall, thin spike of 1e9 rows) and when the UVs are so
// large that a unit step is lost in their digits.
TEST(QuadExtraction, SpikesAndHugeUvsAreRefusedQuickly) {
  Eigen::Matrix<double, 4, 2> spike;
  spike << 0.49, 0, 0.51, 0, 0.5, 1e9, 0.5, 5e8;
  expect_input_error([&] { extract_quads(spiked_tetrahedron(spike), {}, "spike.obj"); }, {"spike.obj", "grid units"});
  Eigen::Matrix<double, 4, 2> far;
  far << 1e17, 0, 1e17 + 64, 0, 1e17 + 32, 64, 1e17 + 32, 16;
  expect_input_error([&] { extract_quads(spiked_tetrahedron(far), {}, "far.obj"); }, {"far.obj", "grid units"});
}

// A coarser tolerance keeps a complete map complete: a grid point a few tolerances from a
// vertex, within the tolerance of several edges of the vertex's fan, is the same quad-mesh
// vertex whichever square finds it (keyed in the triangle that holds it).
TEST(QuadExtraction, CoarseTolerancesKeepTheQuadMeshClosed) {
  const GParamOutcome* map = fertility_on_a_fine_grid();
  if (!map) GTEST_SKIP() << "../shared/data/closed/fertility.obj not available";
  const GParamOutcome& g = *map;
  ASSERT_EQ(g.measured.stats.flipped, 0);
  const QuadExtraction fine = extract_quads(g.mapped);
  ASSERT_TRUE(fine.complete);
  for (double tolerance : {1e-3, 1e-2, 5e-2}) {
    QuadExtractionOptions coarse;
    coarse.tolerance = tolerance;
    const QuadExtraction x = extract_quads(g.mapped, coarse);
    EXPECT_TRUE(x.complete) << "tolerance " << tolerance;
    EXPECT_EQ(x.boundary_edges, 0) << "tolerance " << tolerance;
    EXPECT_EQ(x.mesh.num_quads(), fine.mesh.num_quads()) << "tolerance " << tolerance;
    EXPECT_EQ(x.valences, fine.valences) << "tolerance " << tolerance;
  }
}
