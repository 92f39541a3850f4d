// Global seamless parametrization (docs/gparam.md): cross field, singularities, cut,
// seamless problem and every method, against known answers.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "expect_input_error.h"
#include "strictmin/field/cross_field.h"
#include "strictmin/field/cut_graph.h"
#include "strictmin/field/singularities.h"
#include "strictmin/field/surface_graph.h"
#include "strictmin/io/mesh_io.h"
#include "strictmin/mesh/polycube.h"
#include "strictmin/param/topology.h"
#include "strictmin/problem/equality_basis.h"
#include "strictmin/tasks/gparam.h"
#include "strictmin/tasks/seamless_problem.h"

using namespace strictmin;

namespace {

// The polycube's axis-aligned field: pinned to the x axis on face 0 (its squares' edges are
// axis-aligned, so the smoothest field is parallel to them up to a global angle).
GParamOptions polycube_options(Method m) {
  GParamOptions o;
  o.field_options.pin_face = 0;
  o.field_options.pin_direction = Eigen::Vector3d::UnitX();
  o.solver.method = m;
  o.edge_length = 0.7;
  return o;
}

std::map<int, int> index_counts(const std::vector<Singularity>& s) {
  std::map<int, int> counts;
  for (const auto& x : s) ++counts[x.quarters];
  return counts;
}

// Checks that every transition around every vertex composes to the identity exactly at
// regular vertices, and to the index's quarter turns at singular ones.
void expect_rotations_compose(const GParamOutcome& g) {
  const Problem& p = g.problem;
  for (int w = 0; w < p.num_vertices; ++w) {
    const int v = g.cut.wedge_vertex[w];
    if (g.quarters[v] == 0) {
      EXPECT_GE(p.copy_base[w], 0) << "regular vertex " << v << " has no closed loop";
    } else {
      EXPECT_EQ(p.copy_base[w], -1) << "singular vertex " << v;
    }
  }
}

std::vector<std::filesystem::path> closed_meshes() {
  const std::filesystem::path dir = std::filesystem::path(STRICTMIN_SHARED_DATA) / "closed";
  std::vector<std::filesystem::path> out;
  if (!std::filesystem::is_directory(dir)) return out;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().extension() == ".obj") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

TEST(Polycube, CubeFieldHasZeroEnergyAndEightConvexCorners) {
  const Mesh cube = make_cube_surface(4);
  const SurfaceGraph g = surface_graph(cube);
  EXPECT_EQ(g.euler_characteristic(), 2);
  const FaceFrames fr = face_frames(cube, g);
  CrossFieldOptions o;
  o.pin_face = 0;
  const CrossField f = smoothest_cross_field(cube, g, fr, o);
  EXPECT_LT(f.energy, 1e-9);
  const auto s = singularities(vertex_indices(cube, g, fr, f.u));
  EXPECT_EQ(s.size(), 8u);
  for (const auto& x : s) {
    EXPECT_EQ(x.quarters, 1);
    const Eigen::Vector3d p = cube.V.row(x.vertex).transpose();
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(std::abs(p[k]) < 1e-12 || std::abs(p[k] - 5.0) < 1e-12) << p.transpose();
  }
}

TEST(Polycube, FrameHasEightConvexAndEightSaddleCorners) {
  const Mesh frame = make_frame_surface(3);
  const SurfaceGraph g = surface_graph(frame);
  EXPECT_EQ(g.euler_characteristic(), 0);
  const FaceFrames fr = face_frames(frame, g);
  CrossFieldOptions o;
  o.pin_face = 0;
  const CrossField f = smoothest_cross_field(frame, g, fr, o);
  EXPECT_LT(f.energy, 1e-9);
  const auto counts = index_counts(singularities(vertex_indices(frame, g, fr, f.u)));
  EXPECT_EQ(counts.size(), 2u);
  EXPECT_EQ(counts.at(1), 8);
  EXPECT_EQ(counts.at(-1), 8);
}

TEST(Polycube, EveryMethodMapsWithZeroDistortion) {
  for (const Mesh& m : {make_cube_surface(3), make_frame_surface(2)}) {
    for (Method method : {Method::L2, Method::Linf, Method::Relax, Method::Direct, Method::Irls}) {
      const GParamOutcome g = global_parametrize(m, polycube_options(method));
      EXPECT_LT(g.measured.stats.max, 1e-9) << method_name(method);
      EXPECT_LT(g.seam_error, 1e-9) << method_name(method);
      EXPECT_EQ(g.measured.stats.flipped, 0);
    }
  }
}

TEST(Cut, CutMeshIsADiskThroughEverySingularity) {
  const Mesh frame = make_frame_surface(3);
  const GParamOutcome g = global_parametrize(frame, polycube_options(Method::L2));
  const Mesh cm = cut_mesh(frame, g.cut);
  const SurfaceTopology t = surface_topology(cm);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.boundary_loops.size(), 1u);
  EXPECT_EQ(t.euler_characteristic(), 1);
  std::set<int> on_cut;
  for (int e = 0; e < g.graph.num_edges(); ++e)
    if (g.cut.cut[e]) on_cut.insert({g.graph.edges(e, 0), g.graph.edges(e, 1)});
  for (const auto& s : g.singular) EXPECT_TRUE(on_cut.count(s.vertex)) << s.vertex;
  expect_rotations_compose(g);
  // Across every uncut edge the combed field matches without a turn.
  for (int e = 0; e < g.graph.num_edges(); ++e)
    if (!g.cut.cut[e]) EXPECT_EQ(g.cut.matching[e], 0) << e;
}

TEST(PoincareHopf, IndicesSumToEulerCharacteristicOnSharedMeshes) {
  const auto files = closed_meshes();
  if (files.empty()) GTEST_SKIP() << "no closed meshes under " << STRICTMIN_SHARED_DATA;
  for (const auto& file : files) {
    const Mesh m = read_mesh(file.string());
    const SurfaceGraph g = surface_graph(m, file.string());
    const FaceFrames fr = face_frames(m, g);
    const CrossField f = smoothest_cross_field(m, g, fr);
    std::vector<double> raw;
    const std::vector<int> q = vertex_indices(m, g, fr, f.u, &raw);
    int sum = 0;
    double off = 0;
    for (size_t v = 0; v < q.size(); ++v) {
      sum += q[v];
      off = std::max(off, std::abs(raw[v] - q[v]));
    }
    EXPECT_EQ(sum, 4 * g.euler_characteristic()) << file;
    EXPECT_LT(off, 1e-9 * 4) << file;  // indices are multiples of 1/4 to 1e-9
    EXPECT_TRUE(f.u.allFinite()) << file;
  }
}
