// Fields with prescribed cones (cone_field.h, docs/gparam.md "Fields from cones"): they have
// exactly their cones, are critical for the linearized smoothness energy among fields with
// those cones, reduce to the axis-aligned field on polycubes, and --parallel lowers the
// energy and the maximum distortion on the shared meshes.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>

#include "expect_input_error.h"
#include "strictmin/field/cone_field.h"
#include "strictmin/field/cross_field.h"
#include "strictmin/field/singularities.h"
#include "strictmin/field/surface_graph.h"
#include "strictmin/io/mesh_io.h"
#include "strictmin/mesh/polycube.h"
#include "strictmin/tasks/gparam.h"
#include "test_meshes.h"

using namespace strictmin;
using strictmin::test_support::expect_input_error;
using strictmin::test_support::shared_closed_mesh;

namespace {

// A cube of side 2 pushed halfway to its circumscribed sphere, with an uneven bump: curved
// everywhere, so no field is parallel without a correction.
Mesh bumpy_bulged_cube() {
  Mesh m = make_cube_surface(4, 2.0);
  const Eigen::RowVector3d c(1.0, 1.0, 1.0);
  for (int v = 0; v < m.num_vertices(); ++v) {
    const Eigen::RowVector3d d = m.V.row(v) - c;
    const double bump = 0.1 * std::sin(7.0 * v);
    m.V.row(v) = c + d * (0.6 + bump + 0.4 * std::sqrt(3.0) / d.norm());
  }
  return m;
}

struct Surface {
  Mesh mesh;
  SurfaceGraph graph;
  FaceFrames frames;
  explicit Surface(Mesh m) : mesh(std::move(m)), graph(surface_graph(mesh)), frames(face_frames(mesh, graph)) {}
};

// The field's turn across each edge beyond the transport, in (-pi/4, pi/4].
Eigen::VectorXd turns(const Surface& s, const Eigen::VectorXcd& u) {
  const SurfaceGraph& g = s.graph;
  Eigen::VectorXd d(g.num_edges());
  for (int e = 0; e < g.num_edges(); ++e) {
    const int f = g.edge_faces(e, 0), h = g.edge_faces(e, 1);
    d(e) = std::arg(u(h) / (std::polar(1.0, 4.0 * s.frames.transport(e)) * u(f))) / 4.0;
  }
  return d;
}

// Checks the optimality of a parallel field: rotating one face f by a small angle changes
// the linearized energy sum_e w_e turn_e^2 by 2 eps sum_{e in f} (+-) w_e turn_e, which must
// vanish at every face (the correction is orthogonal to every face rotation).
void expect_critical(const Surface& s, const Eigen::VectorXcd& u) {
  const SurfaceGraph& g = s.graph;
  const Eigen::VectorXd d = turns(s, u);
  Eigen::VectorXd divergence = Eigen::VectorXd::Zero(g.num_faces);
  double scale = 0;
  for (int e = 0; e < g.num_edges(); ++e) {
    const double w = field_edge_weight(s.mesh, g, s.frames, e);
    divergence(g.edge_faces(e, 1)) += w * d(e);
    divergence(g.edge_faces(e, 0)) -= w * d(e);
    scale = std::max(scale, std::abs(w * d(e)));
  }
  EXPECT_GT(scale, 1e-3);  // a real correction, not a parallel field to begin with
  EXPECT_LT(divergence.cwiseAbs().maxCoeff(), 1e-9 * scale);
}

std::vector<int> quarters_of_smoothest(const Surface& s) {
  return vertex_indices(s.mesh, s.graph, s.frames, smoothest_cross_field(s.mesh, s.graph, s.frames).u);
}

TEST(ConeField, PolycubeCornersGiveTheAxisAlignedField) {
  for (const Mesh& m : {make_cube_surface(4), make_frame_surface(3)}) {
    const Surface s(m);
    CrossFieldOptions o;
    o.pin_face = 0;
    const CrossField smooth = smoothest_cross_field(s.mesh, s.graph, s.frames, o);
    const std::vector<int> corners = vertex_indices(s.mesh, s.graph, s.frames, smooth.u);
    const CrossField cones = cone_cross_field(s.mesh, s.graph, s.frames, corners, o);
    EXPECT_LT(cones.energy, 1e-9);
    EXPECT_LT((cones.u - smooth.u).cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_EQ(vertex_indices(s.mesh, s.graph, s.frames, cones.u), corners);
  }
}

// On curved surfaces of genus 0 and 1 (the frame's loops need the harmonic part), the field
// built from the smoothest field's singularities has exactly them, is critical, and is smoother.
TEST(ConeField, HasItsConesAndIsCritical) {
  for (const Mesh& m : {bumpy_bulged_cube(), make_bulged_frame_surface(3)}) {
    const Surface s(m);
    const CrossField smooth = smoothest_cross_field(s.mesh, s.graph, s.frames);
    const std::vector<int> q = vertex_indices(s.mesh, s.graph, s.frames, smooth.u);
    const CrossField cones = cone_cross_field(s.mesh, s.graph, s.frames, q);
    EXPECT_EQ(vertex_indices(s.mesh, s.graph, s.frames, cones.u), q);
    expect_critical(s, cones.u);
    EXPECT_LT(cones.energy, smooth.energy);
  }
}

// Cones anywhere: 8 + k of index 1/4 and k of index -1/4 at random vertices (adding up to
// 4 chi). Cones of index +-1/2 or beyond can need turns over pi/4 between two faces of their
// fan, which a face-based field cannot have; those are reported (GParamOutcome::cones_missed).
TEST(ConeField, ArbitraryConesAreReproduced) {
  const Surface s(bumpy_bulged_cube());
  std::mt19937 random(7);
  std::uniform_int_distribution<int> vertex(0, s.graph.num_vertices - 1);
  for (int trial = 0; trial < 5; ++trial) {
    std::vector<int> q(s.graph.num_vertices, 0);
    auto place = [&](int quarters) {
      int v;
      do v = vertex(random);
      while (q[v] != 0);
      q[v] = quarters;
    };
    for (int k = 0; k < 8; ++k) place(1);
    for (int k = 0; k < trial; ++k) {
      place(1);
      place(-1);
    }
    const CrossField f = cone_cross_field(s.mesh, s.graph, s.frames, q);
    EXPECT_EQ(vertex_indices(s.mesh, s.graph, s.frames, f.u), q) << "trial " << trial;
    expect_critical(s, f.u);
  }
}

// A cone of index -3/4 at a vertex of the bumpy cube (6 faces or fewer) needs turns over
// pi/4 in its fan: global_parametrize reports the vertices whose index differs, and the
// field's own singularities (which the cut and the map use) still add up to chi.
TEST(ConeField, UnrealizableConesAreReported) {
  const Mesh m = bumpy_bulged_cube();
  const SurfaceGraph g = surface_graph(m);
  std::vector<int> q(g.num_vertices, 0);
  q[10] = -3;
  for (int k = 0; k < 11; ++k) q[20 + 5 * k] = 1;
  ASSERT_LE(g.fan_start[11] - g.fan_start[10], 6);
  GParamOptions o;
  o.cones = q;
  const GParamOutcome out = global_parametrize(m, o);
  int differ = 0, sum = 0;
  for (int v = 0; v < g.num_vertices; ++v) {
    differ += out.quarters[v] != q[v];
    sum += out.quarters[v];
  }
  EXPECT_GT(differ, 0);
  EXPECT_EQ(out.cones_missed, differ);
  EXPECT_EQ(sum, 8);
  EXPECT_LT(out.seam_error, 1e-9);
}

TEST(ConeField, RefusesConesThatBreakPoincareHopf) {
  const Surface s(make_cube_surface(2));
  std::vector<int> q = quarters_of_smoothest(s);
  q[0] += 1;
  expect_input_error([&] { cone_cross_field(s.mesh, s.graph, s.frames, q, {}, "cones.txt"); },
                     {"cones.txt", "add up to 9/4", "Euler characteristic 2"});
  q.pop_back();
  expect_input_error([&] { cone_cross_field(s.mesh, s.graph, s.frames, q); }, {"cone indices for"});
  // Options are checked as by the smoothest field: a non-finite pin direction would make every
  // face's field NaN.
  CrossFieldOptions nan_pin;
  nan_pin.pin_face = 0;
  nan_pin.pin_direction = Eigen::Vector3d(NAN, 0, 0);
  expect_input_error([&] { cone_cross_field(s.mesh, s.graph, s.frames, quarters_of_smoothest(s), nan_pin); },
                     {"cross field options", "pin_direction"});
  // A pin face beyond the faces (ignored here, refused by the smoothest field) or below -1
  // (taken as "no pinning").
  CrossFieldOptions far_pin;
  far_pin.pin_face = s.mesh.num_elements();
  expect_input_error([&] { cone_cross_field(s.mesh, s.graph, s.frames, quarters_of_smoothest(s), far_pin); },
                     {"pin_face", "beyond the mesh's"});
  far_pin.pin_face = -7;
  expect_input_error([&] { cone_cross_field(s.mesh, s.graph, s.frames, quarters_of_smoothest(s), far_pin); },
                     {"cross field options", "pin_face must be >= -1"});
}

TEST(ConeFile, RoundTripAndErrorsNameTheLine) {
  const auto dir = std::filesystem::temp_directory_path() / "strictmin_cone_file";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "cones.txt").string();
  const std::vector<int> q{0, 1, -1, 2, -3, 0};
  write_cone_file(path, q);
  EXPECT_EQ(read_cone_file(path, 6), q);
  auto write = [&](const std::string& text) {
    std::ofstream(path) << text;
    return path;
  };
  expect_input_error([&] { read_cone_file(write("6.283185307179586\n1.0\n"), 2); }, {"line 2", "1.0", "quarter"});
  expect_input_error([&] { read_cone_file(write("6.283185307179586\nx\n"), 2); }, {"line 2", "'x' is not a number"});
  expect_input_error([&] { read_cone_file(write("6.283185307179586\n"), 2); }, {"1 angles for 2 vertices"});
  expect_input_error([&] { read_cone_file(write("0\n"), 1); }, {"line 1"});
  expect_input_error([&] { read_cone_file(write("nan\n"), 1); }, {"line 1", "nan"});
  expect_input_error([&] { read_cone_file(write("1e300\n"), 1); }, {"line 1", "too large"});
  expect_input_error([&] { read_cone_file(write("3.14159265358979 1\n"), 1); }, {"line 1", "one number"});
  EXPECT_EQ(read_cone_file(write("# a comment\n4.71238898038469  # index 1/4\n\n"), 1), std::vector<int>{1});
  // Carriage returns alone end lines (the file read as one line: "found more").
  EXPECT_EQ(read_cone_file(write("# cones\r6.283185307179586\r4.71238898038469\r"), 2), (std::vector<int>{0, 1}));
  expect_input_error([&] { read_cone_file(write("6.283185307179586\r\nx\r"), 2); }, {"line 2", "'x' is not a number"});
  // The whole word is the number: a NUL byte ended the reading (the rest was ignored), and a
  // bad word is quoted shortened with its control bytes escaped (it reached the terminal whole).
  constexpr char kNul[] = "6.283185307179586\0junk\n";
  expect_input_error([&] { read_cone_file(write(std::string(kNul, sizeof kNul - 1)), 1); },
                     {"line 1", "'6.283185307179586\\x00junk' is not a number"});
  const std::string escape = "\x1b[31m" + std::string(100, 'x');
  try {
    read_cone_file(write(escape + "\n"), 1);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'\\x1b[31mxxx"), std::string::npos) << what;
    EXPECT_EQ(what.find('\x1b'), std::string::npos) << what;
    EXPECT_LT(what.size(), 120u) << what;
  }
  std::filesystem::remove_all(dir);
}

TEST(FieldFile, TheWholeWordIsTheNumber) {
  const auto dir = std::filesystem::temp_directory_path() / "strictmin_field_file";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "field.txt").string();
  constexpr char kNul[] = "1 0 0\n1\0zz 0 0\n";
  std::ofstream(path) << std::string(kNul, sizeof kNul - 1);
  expect_input_error([&] { read_field_file(path, 2); }, {"line 2", "face 1", "'1\\x00zz' is not a number"});
  std::ofstream(path) << "# field\r1 0 0\r0 1 0\r";  // carriage returns alone end lines
  const Eigen::MatrixXd d = read_field_file(path, 2);
  EXPECT_EQ(d(1, 1), 1.0);
  std::ofstream(path) << "1 0 0\r0 1\r";
  expect_input_error([&] { read_field_file(path, 2); }, {"line 2", "face 1", "expected 3 numbers"});
  std::filesystem::remove_all(dir);
}

// Cones given in code (GParamOptions::cones, Python's cones=) are held to the cone file's
// range: a total angle 2 pi - q pi/2 that is positive (q <= 3) and at most 2 pi + 10,000
// quarter turns. They were taken as they came (q = 100000 was solved).
TEST(ConeField, ConesOutOfTheFilesRangeAreRefused) {
  const Mesh cube = make_cube_surface(3);
  for (int q : {4, 100000, -10001}) {
    std::vector<int> cones(cube.num_vertices(), 0);
    cones[0] = q;
    cones[1] = 8 - q;  // the sum is still 4 chi = 8
    GParamOptions o;
    o.solver.method = Method::L2;
    o.cones = cones;
    o.field_source = "cones";
    expect_input_error([&] { global_parametrize(cube, o); },
                       {"cones: vertex 0: the index " + std::to_string(q) + "/4", "-10000 <= q <= 3"});
  }
}

// --parallel on the small shared meshes (genus 0 and 4), measured 2026-11-26: E cow 3033 ->
// 2082, fertility 2656 -> 1966; the L-infinity maximum cow 0.464 -> 0.390, fertility 0.434
// -> 0.378; the same singularities.
TEST(SharedMeshes, ParallelFieldIsSmootherAndLowersTheMaximum) {
  for (const char* name : {"cow", "fertility"}) {
    const Mesh* m = shared_closed_mesh(name);
    if (!m) GTEST_SKIP() << "no closed/" << name << ".obj under " << STRICTMIN_SHARED_DATA;
    const auto runs = test_support::linf_against_smoothest(*m, [](GParamOptions& o) { o.parallel_field = true; });
    const GParamOutcome &smooth = runs.smoothest, &parallel = runs.variant;
    EXPECT_EQ(parallel.quarters, smooth.quarters) << name;
    EXPECT_EQ(parallel.cones_missed, 0) << name;
    EXPECT_NEAR(parallel.field_energy_before_parallel, smooth.field.energy, 1e-9 * smooth.field.energy) << name;
    EXPECT_LT(parallel.field.energy, 0.8 * smooth.field.energy) << name;
    EXPECT_EQ(parallel.result.status, SolveStatus::Solved) << name;
    EXPECT_LT(parallel.measured.stats.max, 0.92 * smooth.measured.stats.max) << name;
    EXPECT_LT(parallel.seam_error, 1e-9) << name;
  }
}

}  // namespace
