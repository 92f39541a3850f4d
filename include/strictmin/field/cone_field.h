#pragma once
// A cross field with prescribed singularities (cones)
// (docs/gparam.md, "Fields from cones").
//
// The field is parallel for the face frames' transport corrected by a small rotation x_e
// per edge (a trivial connection, Crane et al. 2010): x is the smallest, in the field
// energy's weights, that makes the holonomy around every vertex v its cone's q_v quarter
// turns (angle defect K_v plus the turns of x around v = q_v pi/2) and, on a surface of
// genus g, the holonomy around each of 2g loops a whole number of quarter turns. The
// singularities are then exactly the cones (vertex_indices recovers them), wherever they
// are, and the field is as smooth as they allow.
//
// x = (exact part from a vertex potential) + (harmonic part):
//   L lambda = q pi/2 - K,  L = C A C^T, A = diag(1 / w_e), x_e = (C^T lambda)_e / w_e,
// with C the vertices' circulation (+1 at edges(e,1), -1 at edges(e,0)) and w_e the field
// energy's edge weight (cross_field.h), then a harmonic form fixing the loops' holonomy.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "strictmin/field/cross_field.h"
#include "strictmin/field/surface_graph.h"
#include "strictmin/mesh/mesh.h"

namespace strictmin {

// The field with exactly the cones `quarters` (#V, each vertex's index in quarters; they
// must add up to 4 chi). Pins the global rotation as options.pin_face / pin_direction (face
// 0 along its first edge otherwise). Throws InputError (naming `source`) for a wrong size or
// a sum other than 4 chi, and for invalid options (CrossFieldOptions::is_valid).
CrossField cone_cross_field(const Mesh& mesh, const SurfaceGraph& graph, const FaceFrames& frames,
                            const std::vector<int>& quarters, const CrossFieldOptions& options = {},
                            const std::string& source = "");

// The cone file (the convention of seamless-parametrization tools): one line per vertex,
// the vertex's total angle in radians, 2 pi where there is no cone; an index-q/4 cone has
// the angle 2 pi - q pi/2. Reading throws InputError naming the file and line for a
// malformed line, an angle that is not 2 pi minus a whole number of quarter turns (to
// 1e-6), or a wrong line count.
std::vector<int> read_cone_file(const std::string& path, int num_vertices);
void write_cone_file(const std::string& path, const std::vector<int>& quarters);

// Cones asked for (a cone file's, GParamOptions::cones) must be ones a surface can have: a
// total angle 2 pi - q pi/2 that is positive and at most 2 pi + 10,000 quarter turns, i.e.
// -kMostConeQuarters <= q <= 3, as the cone file's angles (beyond, no field on any mesh has
// such a cone, and the index would not fit an int). Throws InputError naming `where` and the
// vertex.
constexpr int kMostConeQuarters = 10000;
void check_cone_indices(const std::vector<int>& quarters, const std::string& where);

}  // namespace strictmin
