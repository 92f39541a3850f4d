#pragma once
// Integer-grid maps (docs/gparam.md, "Integer-grid maps"): the seamless problem's
// singularities and seam translations rounded to the grid of the target edge length h, so
// that the map's integer iso-lines close up across the seams into a quad mesh (what quad
// extraction, e.g. QEx, takes as input; the rounding of Bommes et al. 2009, "Mixed-integer
// quadrangulation").
//
// In UV units (the map / h) a map is an integer-grid map when every singular vertex lands
// on an integer point and every seam transition f_left = R f_right + t has an integer t
// (R is a quarter turn, so the grid maps to itself across the seam). Greedy rounding, with
// L2 solves in between:
//   1. the singular vertices, nearest to an integer point first, a quarter of those left at a
//      time (halved while the values of one step contradict each other), each held at its
//      point (a fixed vertex);
//   2. then the branch translations the same way, each as two equality rows
//      f_left(v) - R f_right(v) = h n on one vertex of the branch (the seam rows carry it along
//      the branch).
// The order makes the greedy consistent: every relation among the translations (around a
// regular vertex where branches meet, sum R_i t_i = 0; around a singular vertex,
// (I - prod R) f = sum R_i t_i) has integer coefficients, so once the singular vertices are
// integer, a translation that the others determine is an integer combination of integers,
// and its rows are redundant, not contradictory. Rounded together they can contradict
// (0.4 + 0.4 - 0.8 = 0 rounds to 0 + 0 - 1), which the L2 solve finds; the step is then
// halved. With handles (genus >= 1) the translations around a loop of the cut enter their
// relations with coefficients such as I - R (determinant 2), and earlier roundings can fix a
// later translation at a half-integer: there each step also solves with perturbed targets,
// and a step that fixes a value not rounded yet off the grid is tried again (halved, then a
// value alone at the four grid points around it). A value every try fails for is left to
// the others, off the grid (counted below).
#include <functional>
#include <string>
#include <vector>

#include "strictmin/field/cut_graph.h"
#include "strictmin/field/singularities.h"
#include "strictmin/field/surface_graph.h"
#include "strictmin/mesh/mesh.h"
#include "strictmin/problem/problem.h"

namespace strictmin {

struct IntegerGridRounding {
  int singularities = 0;       // singular vertices held at integer points (wedge 0's excepted)
  int translations = 0;        // branches given an integer translation (the off-grid ones not counted)
  int solves = 0;              // L2 solves between the rounding steps
  int retried_steps = 0;       // steps whose values contradicted each other, tried again with half
  // Values the others fix off the grid (each alone contradicted them): left unrounded, so
  // the map is not an integer-grid map there (integer_grid_error shows by how much).
  int singularities_off_grid = 0, translations_off_grid = 0;
  double largest_rounding = 0; // the largest move to the grid of a rounded value, in UV units
  double time_s = 0;
};

struct IntegerGridOptions {
  // On surfaces with handles, solve each step a second time with perturbed targets and retry
  // a step that fixes a value not rounded yet off the grid (above). false: no look-ahead
  // (half the solves; fertility then leaves 14 translations off the grid), for comparison.
  bool look_ahead = true;
};

// Rounds `problem` (the seamless problem of mesh, graph and cut, h = 1 units) in place: adds
// the fixed singular vertices and the translation rows for the grid of spacing h (surface
// units). Throws InputError when the seamless problem's L2 matrix cannot be factored (its
// L2 map would fail as well).
IntegerGridRounding round_to_integer_grid(const Mesh& mesh, const SurfaceGraph& graph, const CutGraph& cut,
                                          const std::vector<Singularity>& singular, double h, Problem& problem,
                                          const std::function<void(const std::string&)>& progress = nullptr,
                                          const IntegerGridOptions& options = {});

// How far the map X (#wedges by 2, h = 1 units) is from an integer-grid map in UV units:
// the largest distance of a singular vertex's wedge, or of a branch translation / h, to the
// nearest integer point (per coordinate).
double integer_grid_error(const Mesh& mesh, const SurfaceGraph& graph, const CutGraph& cut,
                          const std::vector<Singularity>& singular, double h, const Eigen::MatrixXd& X);

}  // namespace strictmin
