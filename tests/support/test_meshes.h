#pragma once
// Test problems shared by several test files.
#include "strictmin/mesh/mesh.h"
#include "strictmin/problem/problem.h"

namespace strictmin::test_support {

// A 4 x 1 bar of 16 x 4 grid cells (128 triangles) with random rotation targets (angles in
// [-0.4, 0.4], seed 3), so that its strict-minimizer levels are distinct; the left end is
// fixed, the right end turned by 0.5 rad and moved. Used for the L_p and exact tests.
Problem random_target_bar();

// The field-deviation problem of a disk mesh (per-triangle frames, identity targets) with three
// boundary vertices held where an L2 map with one pinned vertex puts them (a third of the
// boundary apart, in vertex order): the surface problems of bench_linf and the tests.
Problem disk_with_three_pins(const Mesh& mesh);

}  // namespace strictmin::test_support
