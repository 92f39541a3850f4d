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

// The field's turn across every edge (#E), computed once per edge so that its two ends see
// opposite turns (a turn of exactly pi/4 taken separately at both ends would not cancel): across
// an interior edge, from edge_faces(e, 0) to edge_faces(e, 1) relative to transport, in
// (-pi/4, pi/4]; on a boundary edge, from its side (as its face runs it) to the field in its
// face, modulo pi/2 in (-pi/4, pi/4]. The cut's matchings are taken from the same turns.
std::vector<double> field_edge_turns(const Mesh& mesh, const SurfaceGraph& graph, const FaceFrames& frames,
                                     const Eigen::VectorXcd& u);

// The index of every vertex in quarters (#V integers) and, in *raw if given, the unrounded
// 4 (K_v + sum delta) / (2 pi) (within rounding of an integer).
std::vector<int> vertex_indices(const Mesh& mesh, const SurfaceGraph& graph, const FaceFrames& frames,
                                const Eigen::VectorXcd& u, std::vector<double>* raw = nullptr);

// A field with an interior singularity of index +1 or more (quarters >= 4: a cone of angle 0
// or less, which no seamless map can have; every method then collapses the map around it) can
// come out of the smoothest field on a symmetric surface (a round disk, a hemisphere). Such a
// vertex's fan is given its first face's direction moved across the fan (faces with a
// boundary side keep theirs), which sends the field's full turn out to the vertices around
// the fan, where it falls as smaller indices; repeated (a few rounds) while a vertex is left
// at +1 or more. Updates u and quarters; returns the fans changed. docs/gparam.md,
// "Singularities".
int spread_full_turn_singularities(const Mesh& mesh, const SurfaceGraph& graph, const FaceFrames& frames,
                                   Eigen::VectorXcd& u, std::vector<int>& quarters);

struct Singularity {
  int vertex = 0;
  int quarters = 0;  // index * 4
};

std::vector<Singularity> singularities(const std::vector<int>& quarters);

}  // namespace strictmin
