// linf_tool: makes an L-infinity field-deviation problem, solves it with solve_linf and writes
// JSON with the cone program (G as triplets over the free dofs, h, per-element bounds) and
// the result (k, lower_bound, iterations, status), for tests/py/test_linf_cvxopt.py and for
// timing by hand.
//
//   linf_tool [problem] [targets] [options] [--out FILE]
// problem (one of):
//   --grid NX NY [--shift S]      unit square, boundary fixed, centre moved by (S, 0) (Figure 2)
//   --bar NX NY [--bend A]        bar [0,4]x[0,1], left end fixed, right end rotated by A radians
//   --tet NX NY NZ [--shift S]    unit tet box, bottom face fixed, top face moved by (S, 0, 0)
//   --mesh FILE                   a surface or planar mesh: 3 boundary vertices fixed where an
//                                 L2 map (one vertex pinned) puts them
// targets: --rotations SEED [--angle A]   random rotations (angle uniform in [-A, A])
// options: --bounds COUNT VALUE SEED  COUNT random elements get the fixed bound VALUE
//          --l2opt (minimize_l2_among_optimal)  --verbose / --verbose2  --no-dump (result only)
//          --reg X (static regularisation)  --refine N (CG steps)  --step F (step fraction)
#include <Eigen/Dense>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "strictmin/io/mesh_io.h"
#include "strictmin/mesh/generators.h"
#include "strictmin/solvers/l2.h"
#include "strictmin/solvers/linf.h"

using namespace strictmin;

namespace {

[[noreturn]] void usage(const std::string& why) {
  std::cerr << "linf_tool: " << why << "\n(see the comment at the top of tests/tools/linf_tool.cpp)\n";
  std::exit(2);
}

Eigen::MatrixXd random_rotation(int n, std::mt19937& rng, double angle) {
  std::uniform_real_distribution<double> U(-angle, angle);
  if (n == 2) {
    const double a = U(rng);
    Eigen::Matrix2d R;
    R << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
    return R;
  }
  std::normal_distribution<double> N(0, 1);
  Eigen::Vector3d axis(N(rng), N(rng), N(rng));
  return Eigen::AngleAxisd(U(rng), axis.normalized()).toRotationMatrix();
}

// Vertices on edges used by one element only (triangle meshes).
std::vector<int> boundary_vertices(const Mesh& mesh) {
  std::map<std::pair<int, int>, int> count;
  for (int f = 0; f < mesh.num_elements(); ++f)
    for (int j = 0; j < 3; ++j) {
      int a = mesh.F(f, j), b = mesh.F(f, (j + 1) % 3);
      if (a > b) std::swap(a, b);
      ++count[{a, b}];
    }
  std::set<int> out;
  for (const auto& [edge, c] : count)
    if (c == 1) out.insert({edge.first, edge.second});
  return {out.begin(), out.end()};
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  auto num = [&](size_t i) {
    if (i >= args.size()) usage("missing value after " + args[i - 1]);
    return std::stod(args[i]);
  };
  std::string kind, mesh_path, out_path;
  int nx = 10, ny = 10, nz = 4;
  double shift = 0.2, bend = 0.5, angle = 0.5;
  int rot_seed = -1, bound_count = 0, bound_seed = 1;
  double bound_value = 0;
  bool l2opt = false, dump = true;
  int verbose = 0;
  double reg = -1, step = -1;
  int refine = -1;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--grid" || a == "--bar") {
      kind = a.substr(2);
      nx = static_cast<int>(num(i + 1));
      ny = static_cast<int>(num(i + 2));
      i += 2;
    } else if (a == "--tet") {
      kind = "tet";
      nx = static_cast<int>(num(i + 1));
      ny = static_cast<int>(num(i + 2));
      nz = static_cast<int>(num(i + 3));
      i += 3;
    } else if (a == "--mesh") {
      kind = "mesh";
      if (i + 1 >= args.size()) usage("missing file after --mesh");
      mesh_path = args[++i];
    } else if (a == "--shift") {
      shift = num(++i);
    } else if (a == "--bend") {
      bend = num(++i);
    } else if (a == "--rotations") {
      rot_seed = static_cast<int>(num(++i));
    } else if (a == "--angle") {
      angle = num(++i);
    } else if (a == "--bounds") {
      bound_count = static_cast<int>(num(i + 1));
      bound_value = num(i + 2);
      bound_seed = static_cast<int>(num(i + 3));
      i += 3;
    } else if (a == "--out") {
      if (i + 1 >= args.size()) usage("missing file after --out");
      out_path = args[++i];
    } else if (a == "--l2opt") {
      l2opt = true;
    } else if (a == "--verbose") {
      verbose = 1;
    } else if (a == "--verbose2") {
      verbose = 2;
    } else if (a == "--reg") {
      reg = num(++i);
    } else if (a == "--step") {
      step = num(++i);
    } else if (a == "--refine") {
      refine = static_cast<int>(num(++i));
    } else if (a == "--no-dump") {
      dump = false;
    } else {
      usage("unknown argument " + a);
    }
  }
  if (kind.empty()) usage("give a problem: --grid, --bar, --tet or --mesh");

  Problem p;
  std::vector<Handle> handles;
  if (kind == "grid") {
    const Mesh mesh = make_grid(nx, ny);
    p = make_problem(mesh);
    for (int v = 0; v < mesh.num_vertices(); ++v) {
      const int i = v % (nx + 1), j = v / (nx + 1);
      if (i == 0 || j == 0 || i == nx || j == ny) handles.push_back({v, mesh.V.row(v).transpose()});
    }
    const int centre = (ny / 2) * (nx + 1) + nx / 2;
    handles.push_back({centre, Eigen::Vector2d(mesh.V(centre, 0) + shift, mesh.V(centre, 1))});
  } else if (kind == "bar") {
    const Mesh mesh = make_grid(nx, ny, 4.0, 1.0);
    p = make_problem(mesh);
    Eigen::Matrix2d R;
    R << std::cos(bend), -std::sin(bend), std::sin(bend), std::cos(bend);
    for (int v = 0; v < mesh.num_vertices(); ++v) {
      const int i = v % (nx + 1);
      if (i == 0) handles.push_back({v, mesh.V.row(v).transpose()});
      if (i == nx) {
        const Eigen::Vector2d q = mesh.V.row(v).transpose() - Eigen::Vector2d(4.0, 0.5);
        handles.push_back({v, Eigen::Vector2d(4.0, 0.5) + 0.8 * (R * q) + Eigen::Vector2d(-0.5, 1.0)});
      }
    }
  } else if (kind == "tet") {
    const Mesh mesh = make_tet_box(nx, ny, nz);
    p = make_problem(mesh);
    for (int v = 0; v < mesh.num_vertices(); ++v) {
      const int k = v / ((nx + 1) * (ny + 1));
      if (k == 0) handles.push_back({v, mesh.V.row(v).transpose()});
      if (k == nz) handles.push_back({v, mesh.V.row(v).transpose() + Eigen::Vector3d(shift, 0, 0.3 * shift)});
    }
  } else {
    const Mesh mesh = read_mesh(mesh_path);
    p = make_problem(mesh);
    const std::vector<int> b = boundary_vertices(mesh);
    if (b.size() < 3) usage("the mesh needs a boundary");
    Problem pinned = p;
    pinned.fix({{b[0], Eigen::VectorXd::Zero(p.image_dim)}});
    const Result l2 = solve_l2(pinned);
    for (size_t idx : {size_t{0}, b.size() / 3, 2 * b.size() / 3})
      handles.push_back({b[idx], l2.positions.row(b[idx]).transpose()});
  }
  p.fix(handles);
  if (rot_seed >= 0) {
    std::mt19937 rng(rot_seed);
    for (int e = 0; e < p.num_elements(); ++e) p.set_target(e, random_rotation(p.image_dim, rng, angle));
  }
  LinfOptions options;
  options.minimize_l2_among_optimal = l2opt;
  options.verbose = verbose;
  if (reg >= 0) options.regularization = reg;
  if (refine >= 0) options.refinement_steps = refine;
  if (step > 0) options.step_fraction = step;
  if (bound_count > 0) {
    std::mt19937 rng(bound_seed);
    options.element_bounds = Eigen::VectorXd::Constant(p.num_elements(), -1.0);
    std::uniform_int_distribution<int> pick(0, p.num_elements() - 1);
    for (int c = 0; c < bound_count; ++c) options.element_bounds[pick(rng)] = bound_value;
  }
  if (verbose)
    options.progress = [](const IterationRecord& r) {
      std::fprintf(stderr, "linf %3d k %.12f bound %.12f gap %.2e t %.3fs\n", r.iteration, r.max_distortion, r.lower_bound,
                   r.certified_gap, r.time_s);
    };

  const Result r = solve_linf(p, options);
  double k = -1;
  for (int e = 0; e < p.num_elements(); ++e)
    if (options.element_bounds.size() == 0 || !(options.element_bounds[e] >= 0)) k = std::max(k, r.distortion[e]);
  nlohmann::json j;
  j["elements"] = p.num_elements();
  j["vertices"] = p.num_vertices;
  j["k"] = k;
  j["lower_bound"] = r.lower_bound;
  j["iterations"] = r.iterations;
  j["status"] = status_name(r.status);
  j["message"] = r.message;
  j["time_s"] = r.time_s;
  j["l2_energy"] = (p.weights.array() * r.distortion.array().square()).sum();
  if (dump) {
    const auto red = p.reduced();
    j["n"] = p.image_dim;
    j["m"] = p.domain_dim;
    j["num_x"] = red.G.cols();
    std::vector<int> gi, gj;
    std::vector<double> gv;
    for (int c = 0; c < red.G.outerSize(); ++c)
      for (Eigen::SparseMatrix<double>::InnerIterator it(red.G, c); it; ++it) {
        gi.push_back(static_cast<int>(it.row()));
        gj.push_back(static_cast<int>(it.col()));
        gv.push_back(it.value());
      }
    j["G"] = {{"rows", red.G.rows()}, {"cols", red.G.cols()}, {"i", gi}, {"j", gj}, {"v", gv}};
    j["h"] = std::vector<double>(red.h.data(), red.h.data() + red.h.size());
    std::vector<double> bounds(p.num_elements(), -1.0);
    for (int e = 0; e < p.num_elements() && options.element_bounds.size() > 0; ++e)
      if (options.element_bounds[e] >= 0) bounds[e] = options.element_bounds[e];
    j["bounds"] = bounds;
    j["weights"] = std::vector<double>(p.weights.data(), p.weights.data() + p.weights.size());
    j["distortion"] = std::vector<double>(r.distortion.data(), r.distortion.data() + r.distortion.size());
  }
  if (out_path.empty()) {
    std::cout << j.dump() << "\n";
  } else {
    std::ofstream(out_path) << j.dump() << "\n";
    std::fprintf(stderr, "%s: %d elements, k = %.12f, lower bound = %.12f, %d iterations, %s, %.3f s\n",
                 out_path.c_str(), p.num_elements(), k, r.lower_bound, r.iterations, status_name(r.status).c_str(),
                 r.time_s);
  }
  return 0;
}
