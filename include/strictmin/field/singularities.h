#pragma once
// Indices of a cross field's singular vertices, from the full formula (docs/gparam.md):
// walking the faces f_0 .. f_{m-1}, f_0 counter-clockwise around v, with
// delta_j = arg(u_{j+1} / (rho_j u_j)) / 4 in (-pi/4, pi/4] the field's turn relative to
// transport (rho_j = e^{4i transport}) and K_v = 2 pi - (the angles at v),
//   index(v) = (K_v + sum_j delta_j) / (2 pi),
// a multiple of 1/4; the indices sum to the Euler characteristic (Poincare-Hopf). Never the
// sum of mismatches mod 4, which loses negative indices and breaks Poincare-Hopf.
// A boundary vertex's fan is open (f_0 .. f_{m-1}, m - 1 turns) and K_v = pi - (the angles at
// v), the boundary's turn there, and the sum takes two more turns: from the boundary side
// leaving v to the field in f_0, and from the field in f_{m-1} to the side reaching v, each
// modulo pi/2 in (-pi/4, pi/4] (zero for a field along the boundary). The index is again a
// multiple of 1/4 (+1/4 at a square's corner, -1/4 at a reflex right angle, 0 where the
// boundary runs straight) and Poincare-Hopf holds with it (docs/gparam.md, "Surfaces with
// boundary").
#include <Eigen/Core>
#include <vector>

#include "strictmin/field/cross_field.h"
#include "strictmin/field/surface_graph.h"
#include "strictmin/mesh/mesh.h"

namespace strictmin {

// Angle defect 2 pi - sum of the corner angles at each vertex (#V); pi - the sum at a
// boundary vertex.
Eigen::VectorXd angle_defects(const Mesh& mesh, const SurfaceGraph& graph);

// The index of every vertex in quarters (#V integers) and, in *raw if given, the unrounded
// 4 (K_v + sum delta) / (2 pi) (within rounding of an integer).
std::vector<int> vertex_indices(const Mesh& mesh, const SurfaceGraph& graph, const FaceFrames& frames,
                                const Eigen::VectorXcd& u, std::vector<double>* raw = nullptr);

struct Singularity {
  int vertex = 0;
  int quarters = 0;  // index * 4
};

std::vector<Singularity> singularities(const std::vector<int>& quarters);

}  // namespace strictmin
