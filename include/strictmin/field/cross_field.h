#pragma once
// Face-based 4-direction (cross) fields on a closed surface (docs/gparam.md, "The field").
//
// Each face f has an orthonormal frame (x_f along its first edge F(f,0) -> F(f,1), y_f = n_f x
// x_f: the frame of local_frame_coordinates in problem.h, so angles in it are angles in the
// Problem's element frames). A direction at angle a in f is e^{ia}; a cross is stored as
// u_f = e^{4ia}, which is the same for the four directions a + k pi/2.
//
// Transport: unfolding f and g about their shared edge maps angle a in f to
// a + transport(e) in g, transport(e) = theta_g - theta_f with theta the edge vector's angle
// in each frame (from edge_faces(e,0) to edge_faces(e,1)). The smoothness energy
//   E(u) = sum_e w_e |u_g - e^{4i transport(e)} u_f|^2,  w_e = 3 |e|^2 / (A_f + A_g)
// is zero exactly for fields that are parallel up to quarter turns.
#include <Eigen/Core>
#include <complex>
#include <optional>
#include <string>
#include <vector>

#include "strictmin/field/surface_graph.h"
#include "strictmin/mesh/mesh.h"

namespace strictmin {

struct FaceFrames {
  Eigen::MatrixXd x, y, normal;  // #F by 3, unit
  Eigen::VectorXd area;          // #F
  Eigen::VectorXd transport;     // #E: theta_g - theta_f (radians), see above

  // The angle of the 3D vector d (in face f's plane) in f's frame, from x towards y.
  double angle(int f, const Eigen::Vector3d& d) const;
  // The transport of edge e read from its face f to its other face: transport(e) from
  // edge_faces(e, 0), its opposite from edge_faces(e, 1).
  double transport_from(const SurfaceGraph& graph, int e, int f) const;
};

FaceFrames face_frames(const Mesh& mesh, const SurfaceGraph& graph);

// The smoothness energy's weight w_e = 3 |e|^2 / (A_f + A_g) of edge e (above).
double field_edge_weight(const Mesh& mesh, const SurfaceGraph& graph, const FaceFrames& frames, int e);

// Wall seconds of a computed field's phases (0 for a given field).
struct CrossFieldTiming {
  double assemble_s = 0, analyze_s = 0, factorize_s = 0, iterate_s = 0, unit_s = 0;
  double parallel_s = 0;  // GParamOptions::parallel_field: the parallel field with these singularities
};

struct CrossField {
  Eigen::VectorXcd u;   // #F, |u_f| = 1: the fourth power of any of the face's four directions
  double energy = 0;    // E(u) above
  int iterations = 0;   // solves with the factorization (Lanczos steps; 0 for a given field)
  int unit_steps = 0;   // diffusion-and-normalize steps after them (CrossFieldOptions::unit)
  double eigen_energy = 0;  // E of the normalized eigenvector, before those steps
  double residual = 0;  // the smoothest field's relative eigen-residual at the end (see below)
  CrossFieldTiming timing;
};

struct CrossFieldOptions {
  // Lanczos steps (solves with the factorization) at most, and the stop: the relative
  // residual ||T y - theta y||_M / (theta ||y||_M) of T = (E + eps M)^-1 M's top Ritz pair.
  // 1e-12 because the per-face normalized field is sensitive where the eigenvector is small:
  // at 1e-9 to 1e-11 the singularities of elephant and horse still move (docs/gparam.md).
  int max_iterations = 60;
  double tolerance = 1e-12;
  // Rotate the whole field (E is invariant under a global phase) so that face `pin_face`
  // has a direction along pin_direction (projected into its plane). -1: no pinning; below -1
  // is refused, and so is a face beyond the mesh's (InputError in the functions).
  int pin_face = -1;
  Eigen::Vector3d pin_direction = Eigen::Vector3d::UnitX();
  // The smoothest *unit* field (`--field unit`): the normalized eigenvector is not the unit
  // field of least E (normalizing per face raises E most where the eigenvector is small, and
  // leaves close pairs of opposite singularities there). Starting from it, steps of implicit
  // diffusion and normalization,
  //   u <- normalize((E + s M)^-1 s M u),  s = unit_diffusion * trace(E) / trace(M)
  // (a Merriman-Bence-Osher scheme for unit fields), lower E and let such pairs annihilate;
  // the field of least E met is kept. They stop when unit_patience steps in a row have not
  // lowered the least E by a fraction unit_progress, or after unit_max_steps. One more
  // factorization (the same pattern, so no new analysis), one solve a step.
  bool unit = false;
  double unit_diffusion = 0.1;
  int unit_max_steps = 200;
  int unit_patience = 10;
  double unit_progress = 1e-3;
  // True when valid; otherwise *why says which option and why (InputError in the functions).
  bool is_valid(std::string* why = nullptr) const;
};

// The smoothest field (Knoeppel et al. 2013): the eigenvector of the smallest eigenvalue
// of E against the area mass, by Lanczos on (E + eps M)^-1 M with one sparse Cholesky
// factorization of the complex Hermitian (E + eps M), normalized per face; with
// options.unit, then lowered among unit fields (see CrossFieldOptions::unit).
CrossField smoothest_cross_field(const Mesh& mesh, const SurfaceGraph& graph, const FaceFrames& frames,
                                 const CrossFieldOptions& options = {});

// A field aligned with the principal curvature directions where the surface is curved and
// smooth elsewhere (Knoeppel et al. 2013, Section 6): q_f = the 4th power of a principal
// direction of face f's shape operator (from its edges' dihedral angles), weighted by the
// anisotropy |k1 - k2| and normalized to area-weighted mean 1; then u solves
// (E + s M) u = s M q with s = alignment * trace(E) / trace(M), normalized per face. Larger
// `alignment` follows the curvature more closely, smaller is smoother.
CrossField curvature_cross_field(const Mesh& mesh, const SurfaceGraph& graph, const FaceFrames& frames,
                                 double alignment = 0.1);

// A field from one 3D direction per face (#F by 3): each is projected into its face's plane.
// Throws InputError naming `source` and the face (and, when `lines` is given, the file's line
// of that face's direction: read_field_file's) for a non-finite or zero (after projection)
// direction, or the wrong number of rows.
CrossField cross_field_from_directions(const Eigen::MatrixXd& directions, const FaceFrames& frames,
                                       const std::string& source = "", const std::vector<long>& lines = {});

// Multiplies the field u by the global rotation that gives face f a direction along d
// (projected into its plane).
void pin_field_rotation(Eigen::VectorXcd& u, int f, const Eigen::Vector3d& d, const FaceFrames& frames);

// Smoothness energy E(u) of any field u (#F).
double field_energy(const Eigen::VectorXcd& u, const Mesh& mesh, const SurfaceGraph& graph, const FaceFrames& frames);

// One of the four directions of each face (the one at angle arg(u_f)/4), #F by 3, unit.
Eigen::MatrixXd field_directions(const CrossField& field, const FaceFrames& frames);

// The field file: one line per face, "x y z" (any vector in the face's plane); '#' starts a
// comment, blank lines are skipped. Reading throws InputError naming the file and line for a
// malformed line or a wrong line count. `lines` (optional) receives each face's line number.
Eigen::MatrixXd read_field_file(const std::string& path, int num_faces, std::vector<long>* lines = nullptr);
void write_field_file(const std::string& path, const Eigen::MatrixXd& directions);

}  // namespace strictmin
