// The Problem's contract at every solver's entry (problem/check_problem.h) and the mesh's at
// make_problem's (mesh/validate.h, check_mesh_structure): a Problem or Mesh built in code with
// wrong sizes, indices out of range or non-finite numbers is an InputError naming what is
// wrong, for every solver, instead of out-of-range reads, a loop without end (relax with an
// infinite target) or NaN maps reported as solved.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <filesystem>
#include <stdexcept>

#include "strictmin/io/input_error.h"
#include "strictmin/io/mesh_io.h"
#include "strictmin/measures/field_deviation.h"
#include "strictmin/measures/measures.h"
#include "strictmin/measures/polar.h"
#include "strictmin/mesh/generators.h"
#include "strictmin/mesh/polycube.h"
#include "strictmin/mesh/surface_generators.h"
#include "strictmin/report/histogram.h"
#include "strictmin/report/stats.h"
#include "strictmin/report/strict_order.h"
#include "strictmin/solvers/linf.h"
#include "strictmin/problem/check_problem.h"
#include "strictmin/problem/problem.h"
#include "strictmin/solvers/conformal.h"
#include "strictmin/solvers/local_global.h"
#include "strictmin/solvers/l2.h"
#include "strictmin/solvers/relax.h"
#include "strictmin/tasks/deform.h"
#include "strictmin/tasks/map_distortion.h"
#include "strictmin/tasks/method.h"
#include "strictmin/mesh/validate.h"

using namespace strictmin;

namespace {

// A 4 x 4 grid with its left and right columns held (a well-posed problem).
Problem grid_problem() {
  Problem p = make_problem(make_grid(4, 4));
  std::vector<Handle> handles;
  for (int v = 0; v < p.num_vertices; ++v) {
    const double x = p.positions(v, 0);
    if (x < 1e-9 || x > 1 - 1e-9) handles.push_back({v, p.positions.row(v).transpose() * (x > 0.5 ? 1.2 : 1.0)});
  }
  p.fix(handles);
  return p;
}

const std::vector<Method> kMethods = {Method::L2, Method::Linf, Method::Lp, Method::Irls, Method::Relax,
                                      Method::Direct, Method::Exact};

// Every method throws InputError on p, with `needle` in the message.
void expect_refused_by_every_method(const Problem& p, const std::string& needle, const std::string& what) {
  for (Method m : kMethods) {
    SolverOptions o;
    o.method = m;
    o.relax.sweeps = 1;
    try {
      run_method(p, o);
      ADD_FAILURE() << what << ": " << method_name(m) << " accepted it";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << what << ", " << method_name(m) << ": " << e.what();
    }
  }
}

}  // namespace

TEST(CheckProblem, AWellFormedProblemPasses) {
  const Problem p = grid_problem();
  EXPECT_NO_THROW(check_problem(p, "test"));
  for (Method m : kMethods) {
    SolverOptions o;
    o.method = m;
    EXPECT_EQ(run_method(p, o).status, SolveStatus::Solved) << method_name(m);
  }
}

TEST(CheckProblem, EveryMethodRefusesInconsistentArrays) {
  const Problem good = grid_problem();
  const std::vector<std::pair<std::string, std::function<void(Problem&)>>> cases = {
      {"fixed flags", [](Problem& p) { p.fixed.resize(3); }},
      {"outside 0..", [](Problem& p) { p.elements(0, 0) = 1000; }},
      {"outside 0..", [](Problem& p) { p.elements(2, 1) = -1; }},
      {"the map is", [](Problem& p) { p.num_vertices += 5; p.fixed.resize(p.num_vertices, 0); }},
      {"targets", [](Problem& p) { p.targets.conservativeResize(4, Eigen::NoChange); }},
      {"weights", [](Problem& p) { p.weights.conservativeResize(2); }},
      {"element array", [](Problem& p) { p.image_dim = 3; p.domain_dim = 3; }},
      {"dimensions", [](Problem& p) { p.image_dim = 2; p.domain_dim = 3; }},
      {"the map is", [](Problem& p) { p.positions.conservativeResize(3, Eigen::NoChange); }},
      {"columns", [](Problem& p) { p.eq_matrix.resize(1, 5); p.eq_rhs = Eigen::VectorXd::Zero(1); }},
      {"right-hand sides", [](Problem& p) { p.eq_matrix.resize(2, 2 * p.num_vertices); p.eq_rhs = Eigen::VectorXd::Zero(1); }},
      {"target is not finite", [](Problem& p) { p.targets(0, 0) = INFINITY; }},
      {"target is not finite", [](Problem& p) { p.targets(3, 1) = NAN; }},
      {"weight", [](Problem& p) { p.weights(1) = -1; }},
      {"weight", [](Problem& p) { p.weights(1) = NAN; }},
      {"gradients are not finite", [](Problem& p) { p.gradients(0, 0) = INFINITY; }},
      {"position is not finite", [](Problem& p) { p.positions(0, 0) = NAN; }},
      {"vertex 25 is free but belongs to no element and no equality", [](Problem& p) {
         p.num_vertices += 1;  // the grid's 25 vertices and one that no element uses, left free
         p.fixed.push_back(0);
         p.positions.conservativeResize(p.num_vertices, Eigen::NoChange);
         p.positions.row(25) << 7, 7;
       }},
  };
  for (const auto& [needle, spoil] : cases) {
    Problem p = good;
    spoil(p);
    expect_refused_by_every_method(p, needle, needle);
  }
}

// A vertex that no element uses is still determined when an equality ties it to one that an
// element uses: no refusal, and the solve puts it where the equality says.
TEST(CheckProblem, AVertexInNoElementButInAnEqualityIsDetermined) {
  Problem p = grid_problem();
  const int free_vertex = 6, extra = p.num_vertices;
  ASSERT_FALSE(p.fixed[free_vertex]);
  p.num_vertices += 1;
  p.fixed.push_back(0);
  p.positions.conservativeResize(p.num_vertices, Eigen::NoChange);
  p.positions.row(extra) << 7, 7;
  std::vector<Eigen::Triplet<double>> rows;  // x_extra - x_free_vertex = (0.5, -0.25)
  for (int r = 0; r < 2; ++r) {
    rows.emplace_back(r, 2 * extra + r, 1.0);
    rows.emplace_back(r, 2 * free_vertex + r, -1.0);
  }
  p.eq_matrix.resize(2, 2 * p.num_vertices);
  p.eq_matrix.setFromTriplets(rows.begin(), rows.end());
  p.eq_rhs = Eigen::Vector2d(0.5, -0.25);
  EXPECT_NO_THROW(check_problem(p, "test"));
  SolverOptions o;
  o.method = Method::L2;
  const Result r = run_method(p, o);
  ASSERT_EQ(r.status, SolveStatus::Solved) << r.message;
  EXPECT_NEAR(r.positions(extra, 0) - r.positions(free_vertex, 0), 0.5, 1e-9);
  EXPECT_NEAR(r.positions(extra, 1) - r.positions(free_vertex, 1), -0.25, 1e-9);
}

// relax reads copy_base and copy_rotation by vertex (seam groups): a copy_base entry out of
// range or a missing copy_rotation segfaulted.
TEST(CheckProblem, EveryMethodRefusesCopiesOutOfRange) {
  Problem good = grid_problem();
  int v = 0;
  while (good.fixed[v]) ++v;
  good.eq_matrix.resize(1, 2 * good.num_vertices);
  good.eq_matrix.insert(0, 2 * v) = 1.0;
  good.eq_rhs = Eigen::VectorXd::Constant(1, good.positions(v, 0));
  good.copy_base.resize(good.num_vertices);
  for (int w = 0; w < good.num_vertices; ++w) good.copy_base[w] = w;
  good.copy_rotation = Eigen::MatrixXd::Identity(2, 2).replicate(good.num_vertices, 1);
  EXPECT_NO_THROW(check_problem(good, "test"));
  const std::vector<std::pair<std::string, std::function<void(Problem&)>>> cases = {
      {"copy_base has", [](Problem& p) { p.copy_base.pop_back(); }},
      {"copy_base of vertex", [&](Problem& p) { p.copy_base[v] = 100000; }},
      {"copy_base of vertex", [&](Problem& p) { p.copy_base[v] = -2; }},
      {"copy_rotation", [](Problem& p) { p.copy_rotation.resize(0, 0); }},
      {"copy_rotation is not finite", [](Problem& p) { p.copy_rotation(3, 0) = NAN; }},
  };
  for (const auto& [needle, spoil] : cases) {
    Problem p = good;
    spoil(p);
    expect_refused_by_every_method(p, needle, needle);
  }
}

// x_0 = 5 with vertex 0 held at (0, 0): no map meets it. linf, direct and exact dropped the
// row (all its unknowns held) and said solved with the row violated by 5.
TEST(CheckProblem, AnEqualityOnFixedVerticesThatFailsIsRefused) {
  Problem p = grid_problem();
  ASSERT_TRUE(p.fixed[0]);
  p.eq_matrix.resize(1, 2 * p.num_vertices);
  p.eq_matrix.insert(0, 0) = 1.0;
  p.eq_rhs = Eigen::VectorXd::Constant(1, 5.0);
  expect_refused_by_every_method(p, "fixed vertices only and does not hold", "x_0 = 5");
  p.eq_rhs(0) = p.positions(0, 0);  // one that holds is kept, and met (relax takes seams only)
  for (Method m : kMethods) {
    if (m == Method::Relax) continue;
    SolverOptions o;
    o.method = m;
    const Result r = run_method(p, o);
    EXPECT_EQ(r.status, SolveStatus::Solved) << method_name(m) << ": " << r.message;
    EXPECT_NEAR(r.positions(0, 0), p.positions(0, 0), 1e-12) << method_name(m);
  }
}

TEST(CheckProblem, StartsAndOptionsOfTheOtherEntries) {
  const Problem p = grid_problem();
  EXPECT_THROW(relax(p, Eigen::MatrixXd::Zero(3, 2)), InputError);
  SolverOptions o;
  o.method = Method::Linf;
  EXPECT_THROW(local_global(p, Eigen::MatrixXd::Zero(3, 2), o, LocalGlobalOptions{}), InputError);
  ConformalOptions c;
  EXPECT_THROW(solve_conformal_linf(p, Eigen::MatrixXd::Zero(2, 2), c), InputError);
  c.element_bounds = Eigen::VectorXd::Ones(2);
  EXPECT_THROW(solve_conformal_linf(p, p.positions, c), InputError);
  for (auto spoil : std::vector<std::function<void(ConformalOptions&)>>{
           [](ConformalOptions& x) { x.bisection_tolerance = NAN; },
           [](ConformalOptions& x) { x.frame_tolerance = -1; },
           [](ConformalOptions& x) { x.max_bisection_steps = -5; },
           [](ConformalOptions& x) { x.max_frame_iterations = 0; },
           [](ConformalOptions& x) { x.max_ipm_iterations = 0; }}) {
    ConformalOptions bad;
    spoil(bad);
    std::string why;
    EXPECT_FALSE(bad.is_valid(&why));
    EXPECT_FALSE(why.empty());
    EXPECT_THROW(solve_conformal_linf(p, p.positions, bad), InputError);
  }
  EXPECT_TRUE(ConformalOptions{}.is_valid());
}

TEST(CheckMesh, MakeProblemAndTasksRefuseAMeshWithBadIndicesOrShape) {
  const Mesh good = make_grid(3, 3);
  const std::vector<std::pair<std::string, std::function<void(Mesh&)>>> cases = {
      {"has vertex index 999 out of range", [](Mesh& m) { m.F(3, 1) = 999; }},
      {"has vertex index -2 out of range", [](Mesh& m) { m.F(0, 0) = -2; }},
      {"corners", [](Mesh& m) { m.F.conservativeResize(Eigen::NoChange, 2); }},
      {"corners", [](Mesh& m) { m.F.conservativeResize(Eigen::NoChange, 5); }},
      {"coordinates", [](Mesh& m) { m.V.conservativeResize(Eigen::NoChange, 1); }},
      {"non-finite", [](Mesh& m) { m.V(4, 1) = NAN; }},
      {"the mesh has no elements", [](Mesh& m) { m.F.resize(0, 3); }},
  };
  for (const auto& [needle, spoil] : cases) {
    Mesh m = good;
    spoil(m);
    try {
      make_problem(m);
      ADD_FAILURE() << needle << ": make_problem accepted it";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
    EXPECT_THROW(deform(m, {{0, Eigen::Vector2d(0, 0)}}, DeformOptions{}), InputError) << needle;
  }
}

// The public helpers' contracts: sizes that disagree and empty matrices are errors, not
// out-of-range reads (they returned values read beyond their arrays, or segfaulted).
TEST(CheckArguments, PublicHelpersRefuseSizesThatDisagree) {
  const Problem p = grid_problem();
  EXPECT_THROW(field_deviation(p, Eigen::MatrixXd::Zero(3, 2)), std::invalid_argument);
  const Eigen::VectorXd three = Eigen::VectorXd::Ones(3), two = Eigen::VectorXd::Ones(2);
  EXPECT_THROW(distortion_stats(three, two), std::invalid_argument);
  EXPECT_THROW(compare_strict(three, Eigen::VectorXd::Ones(5), three), std::invalid_argument);
  EXPECT_THROW(distortion_levels(three, two, 1e-6), std::invalid_argument);
  Eigen::VectorXd bad_weights = three;
  bad_weights(1) = INFINITY;
  EXPECT_THROW(distortion_histogram(three, bad_weights, 2.0), std::invalid_argument);
  bad_weights(1) = -1;
  EXPECT_THROW(distortion_histogram(three, bad_weights, 2.0), std::invalid_argument);
  EXPECT_THROW(signed_singular_values(Eigen::MatrixXd(0, 0)), std::invalid_argument);
  EXPECT_THROW(closest_rotation(Eigen::MatrixXd(0, 0)), std::invalid_argument);
  EXPECT_THROW(rotation_angle(Eigen::MatrixXd::Identity(3, 3)), std::invalid_argument);
  EXPECT_THROW(make_spherical_cap(0, 0), InputError);
  EXPECT_THROW(make_polycube({}, 2), InputError);
  EXPECT_THROW(make_polycube({{0, 0, 0}}, 0), InputError);
  LinfOptions o;
  o.element_bounds = Eigen::VectorXd::Constant(p.num_elements(), -1.0);
  o.element_bounds(3) = INFINITY;  // free elements have a negative bound (it ended stalled)
  EXPECT_THROW(solve_linf(p, o), InputError);
}

// The helpers that take a map next to a mesh or problem read it by vertex or corner: a map
// of another size read beyond it (map_distortion returned 8e+248 for 3 corner images of 32
// triangles, a UV-mapped mesh whose FUV has 2 columns 3e+130).
TEST(CheckArguments, MapHelpersRefuseMapsOfAnotherSize) {
  const Problem p = grid_problem();
  const Mesh grid = make_grid(4, 4);
  EXPECT_THROW(map_distortion(grid, Eigen::MatrixXd::Zero(3, 2), Measure::Arap), InputError);
  EXPECT_THROW(corner_images(grid.F, Eigen::MatrixXd::Zero(3, 2)), InputError);
  EXPECT_THROW(frame_distortion(p, Eigen::MatrixXd::Zero(3, 2)), InputError);
  EXPECT_THROW(conformal_distortion(p, Measure::Quasiconformal, Eigen::MatrixXd::Zero(3, 2)), InputError);
  Problem q = p;
  EXPECT_THROW(local_step(q, Eigen::MatrixXd::Zero(3, 2), {}), InputError);
  EXPECT_THROW(local_distortion(p, Eigen::MatrixXd::Zero(3, 2), {}), InputError);
  LocalGlobalOptions small_shapes;
  small_shapes.shapes = Eigen::MatrixXd::Identity(2, 2);
  EXPECT_THROW(local_distortion(p, p.positions, small_shapes), InputError);
  const Mesh cap = make_spherical_cap(3, 6);
  Mesh mapped = cap;
  mapped.UV = Eigen::MatrixXd::Zero(3, 2);  // FUV's indices go beyond it
  mapped.FUV = cap.F;
  EXPECT_THROW(map_distortion(cap, mapped, Measure::Arap), InputError);
  mapped.UV = Eigen::MatrixXd::Zero(cap.num_vertices(), 2);
  mapped.FUV = Eigen::MatrixXi::Zero(cap.num_elements(), 2);
  EXPECT_THROW(map_distortion(cap, mapped, Measure::Arap), InputError);
}

// The solvers' reusable parts, given another problem than the one they were built for, read
// it by their own indices (relax swept without end or segfaulted); fix() writes the flags and
// positions by vertex (it segfaulted on a problem without them).
TEST(CheckArguments, ReusableSolversRefuseAnotherProblem) {
  const Problem p = grid_problem();
  const Problem other = make_problem(make_grid(2, 2));
  const L2Solver l2(p);
  EXPECT_THROW(l2.solve(other), InputError);
  L2Solver reweighted(p);
  EXPECT_THROW(reweighted.reweight(p, Eigen::VectorXd::Ones(3)), InputError);
  const RelaxSweeper sweeper(p);
  Eigen::MatrixXd X = other.positions;
  EXPECT_THROW(sweeper.sweep(other, X), InputError);
  Problem unsized;
  unsized.num_vertices = 4;
  EXPECT_THROW(unsized.fix({{2, Eigen::Vector2d(1, 1)}}), InputError);
}

// A NaN handle coordinate was called "beyond 1e150".
TEST(CheckArguments, DeformNamesANaNHandleCoordinate) {
  try {
    deform(make_grid(2, 2), {{0, Eigen::Vector2d(NAN, 0)}}, DeformOptions{});
    ADD_FAILURE() << "a NaN handle was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("has the coordinate nan, not a number"), std::string::npos) << e.what();
  }
}

// Two handles on one vertex with different targets: the later one won silently.
TEST(CheckArguments, DeformRefusesTwoTargetsForOneVertex) {
  const Mesh m = make_grid(2, 2);
  EXPECT_THROW(deform(m, {{0, Eigen::Vector2d(0, 0)}, {0, Eigen::Vector2d(5, 0)}, {8, Eigen::Vector2d(1, 1)}},
                      DeformOptions{}),
               InputError);
  // The same target twice is one handle.
  EXPECT_NO_THROW(deform(m, {{0, Eigen::Vector2d(0, 0)}, {0, Eigen::Vector2d(0, 0)}, {8, Eigen::Vector2d(1, 1)}},
                         DeformOptions{}));
}

// NaN shapes made every local distortion NaN, which the maximum skipped: local-global said
// "the start's distortion is zero to rounding", solved, with a NaN distortion.
TEST(CheckArguments, LocalGlobalRefusesShapesThatAreNotFinite) {
  const Problem p = grid_problem();
  LocalGlobalOptions o;
  o.shapes = Eigen::MatrixXd::Identity(2, 2).replicate(p.num_elements(), 1);
  o.shapes(5, 1) = NAN;
  SolverOptions s;
  s.method = Method::Linf;
  EXPECT_THROW(local_global(p, p.positions, s, o), InputError);
  Problem q = p;
  EXPECT_THROW(local_step(q, p.positions, o), InputError);
}

// An accept_tolerance of NaN never accepted a move and swept without end.
TEST(CheckArguments, RelaxSweeperRefusesAnAcceptToleranceOutOfRange) {
  const Problem p = grid_problem();
  for (double bad : {static_cast<double>(NAN), -0.5, 1.0}) EXPECT_THROW(RelaxSweeper(p, bad), InputError) << bad;
}

// UV and FUV of the documented widths (mesh.h): write_mesh read FUV(e, 2) of a 2-column FUV
// and wrote its garbage.
TEST(CheckMesh, TextureCoordinatesOfTheWrongWidthAreRefused) {
  Mesh m = make_grid(2, 2);
  m.UV = Eigen::MatrixXd::Zero(m.num_vertices(), 2);
  m.FUV = Eigen::MatrixXi::Zero(m.num_elements(), 2);
  EXPECT_THROW(check_mesh_structure(m, "m"), InputError);
  const std::string path = (std::filesystem::temp_directory_path() / "strictmin_check_uv.obj").string();
  EXPECT_THROW(write_mesh(path, m), InputError);
  EXPECT_FALSE(std::filesystem::exists(path));
  m.FUV = m.F;
  m.UV = Eigen::MatrixXd::Zero(m.num_vertices(), 3);
  EXPECT_THROW(check_mesh_structure(m, "m"), InputError);
  m.UV = Eigen::MatrixXd::Zero(m.num_vertices(), 2);
  EXPECT_NO_THROW(check_mesh_structure(m, "m"));
}

TEST(CheckArguments, WriteMeshRefusesWhatReadMeshWouldAndWritesNothing) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "strictmin_check_write";
  std::filesystem::create_directories(dir);
  Mesh m = make_grid(2, 2);
  m.F(1, 2) = 99;
  for (const char* name : {"m.obj", "m.off", "m.ply"}) {
    const std::string path = (dir / name).string();
    EXPECT_THROW(write_mesh(path, m), InputError) << name;
    EXPECT_FALSE(std::filesystem::exists(path)) << name;
  }
  std::filesystem::remove_all(dir);
}

// Equalities on free vertices that cannot all hold (x_v = 0.3 and x_v = 0.5) are a problem
// without an answer, not a malformed one: every method reports it infeasible, with L2's
// exact reason, instead of a Newton system that fails (linf and the methods built on it).
TEST(CheckProblem, ContradictoryEqualitiesAreInfeasibleForEveryMethod) {
  Problem p = grid_problem();
  int v = 0;
  while (p.fixed[v]) ++v;
  p.eq_matrix.resize(2, 2 * p.num_vertices);
  p.eq_matrix.insert(0, 2 * v) = 1.0;
  p.eq_matrix.insert(1, 2 * v) = 1.0;
  p.eq_rhs = Eigen::Vector2d(0.3, 0.5);
  for (Method m : kMethods) {
    SolverOptions o;
    o.method = m;
    o.relax.sweeps = 1;
    const Result r = run_method(p, o);
    EXPECT_EQ(r.status, SolveStatus::Infeasible) << method_name(m) << ": " << r.message;
    EXPECT_NE(r.message.find("the linear equalities contradict each other (residual 0.2)"), std::string::npos)
        << method_name(m) << ": " << r.message;
  }
  p.eq_rhs(1) = 0.3;  // the same row twice: consistent, and met
  for (Method m : kMethods) {
    if (m == Method::Relax) continue;  // relax moves seam copies only (docs/gparam.md)
    SolverOptions o;
    o.method = m;
    const Result r = run_method(p, o);
    EXPECT_EQ(r.status, SolveStatus::Solved) << method_name(m) << ": " << r.message;
    EXPECT_NEAR(r.positions(v, 0), 0.3, 1e-7) << method_name(m);
  }
}
