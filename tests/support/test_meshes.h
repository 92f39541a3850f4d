#pragma once
// Test problems shared by several test files.
#include <functional>
#include <string>

#include "strictmin/mesh/mesh.h"
#include "strictmin/problem/problem.h"
#include "strictmin/tasks/gparam.h"

namespace strictmin::test_support {

// The values of a distortion vector from largest to smallest (the distributions that the
// strict order compares rank by rank).
Eigen::VectorXd sorted_down(Eigen::VectorXd values);

// A 4 x 1 bar of 16 x 4 grid cells (128 triangles) with random rotation targets (angles in
// [-0.4, 0.4], seed 3), so that its strict-minimizer levels are distinct; the left end is
// fixed, the right end turned by 0.5 rad and moved. Used for the L_p and exact tests.
Problem random_target_bar();

// The paper's Figure 2 (tasks/examples.h, make_square_example): a cells x cells grid of the
// unit square, boundary fixed, the centre vertex figure2_centre(cells) moved by `shift` in x.
Problem figure2(int cells, double shift);
int figure2_centre(int cells);

// The same problem with one handle replaced by equality rows x_v = its position (two rows in
// 2D): the vertex becomes free, held by the equalities instead.
Problem handle_as_equalities(const Problem& p, int vertex);

// A cells_x x cells_y grid of [0, length] x [0, height] whose two ends are turned by +angle
// (left) and -angle (right) about their centres (handles), targets the identity.
Problem bent_bar(int cells_x, int cells_y, double length, double height, double angle);

// The mesh closed/NAME.obj of the shared data (read once per test program), or nullptr when
// the shared data is absent (the caller skips).
const Mesh* shared_closed_mesh(const std::string& name);

// The seamless problem of a closed surface (tasks/gparam.h: the smoothest field, its cut, the
// default edge length), as global parametrization builds it before its solve.
Problem seamless_problem(const Mesh& mesh);

// Global parametrization by L-infinity with the smoothest field and with a variant of it
// (`vary` changes the options: the unit field, the parallel field...), for the tests that
// compare a field with the smoothest one.
struct FieldComparison {
  GParamOutcome smoothest, variant;
};
FieldComparison linf_against_smoothest(const Mesh& mesh, const std::function<void(GParamOptions&)>& vary);

// Poincare-Hopf on a gparam outcome's field: the indices (quarters) add up to 4 chi and each
// unrounded index is within 1e-9 (x 4) of its rounding (gtest expectations, naming `name`).
void expect_poincare_hopf(const Mesh& mesh, const GParamOutcome& g, const std::string& name);

}  // namespace strictmin::test_support
