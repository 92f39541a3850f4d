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
//      time, each held at its point (a fixed vertex); a step whose values contradict each
//      other is tried again with half as many;
//   2. then the branch translations the same way, each as two equality rows
//      f_left(v) - R f_right(v) = h n on one vertex of the branch (the seam rows carry it along
//      the branch).
// Every integer value must stay completable: the values satisfy homogeneous integer relations
// around the cut's nodes ((I - P) f_s = sum_b Q_b t_b at a singular vertex, sum_b Q_b t_b = 0
// at a regular one; docs/gparam.md, "The node relations"), and with handles (genus >= 1)
// their coefficients include I - R (determinant 2), so values rounded first can fix a later
// one at a half-integer. The exact check (IntegerGridOptions::look_ahead) keeps the affine
// lattice of integer solutions that agree with the values held so far (from the relations'
// Hermite normal form, GMP integers); each step's first value goes to the point of its
// completable coset nearest the map's value, the others to their nearest grid point when
// that can still be completed (else they wait for the next step). No dead end can then
// arise, and the L2 solves never contradict but by round-off.
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
  // the map is not an integer-grid map there (integer_grid_error shows by how much). None
  // with the exact check.
  int singularities_off_grid = 0, translations_off_grid = 0;
  // With the exact check: values held at a completable point other than their nearest grid
  // point (that one would have been a dead end).
  int moved_past_nearest = 0;
  double largest_rounding = 0; // the largest move to the grid of a rounded value, in UV units
  double time_s = 0;
  double check_time_s = 0;     // of which the exact check (the relations' Hermite form and the fixes)
};

struct IntegerGridOptions {
  // The exact check (above): every value is held where the values held before it can be
  // completed to an integer solution of the node relations. false: plain greedy rounding
  // (the L2 solves find contradictions only, so with handles a value can be fixed off the
  // grid and is left there; fertility at 1000 quads then leaves 14 translations off the
  // grid), for comparison.
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
