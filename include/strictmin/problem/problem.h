#pragma once
// The Problem: everything a solver needs, and nothing else (docs/maths.md section 1).
//
// A piecewise-linear map sends vertex v to q_v (an image_dim vector). On element T with
// corners v_0..v_m and barycentric gradients g_0..g_m (domain_dim vectors, in the element's
// own frame) its differential is J_T = sum_j q_{v_j} g_j^T, an image_dim by domain_dim
// matrix, linear in the q's. The field-deviation distortion is D_T = ||J_T - R_T||_F.
//
// Unknowns are laid out vertex-major: dof (v, r) has index v * image_dim + r. vec(J_T) is
// row-major: entry (r, c) of J_T is row T * image_dim * domain_dim + r * domain_dim + c.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "strictmin/mesh/handle.h"
#include "strictmin/mesh/mesh.h"

namespace strictmin {

struct Problem {
  int image_dim = 2;   // n: 2 for planar maps and parametrizations, 3 for tets
  int domain_dim = 2;  // m: 2 for triangles (planar or in a local frame), 3 for tets
  int num_vertices = 0;

  Eigen::MatrixXi elements;   // #E by m+1, vertex indices
  Eigen::MatrixXd gradients;  // #E*(m+1) by m: row T*(m+1)+j is grad(phi_j) on T
  Eigen::VectorXd weights;    // #E: area or volume of T in the rest pose
  Eigen::MatrixXd targets;    // #E*n by m: rows T*n .. T*n+n-1 hold R_T

  std::vector<char> fixed;    // #V: 1 if the vertex is eliminated (a handle)
  Eigen::MatrixXd positions;  // #V by n: fixed vertices' values; for free ones a start

  // Linear equality constraints eq_matrix * q = eq_rhs on the full vertex-major dof vector
  // (seams of global parametrization). Empty when there are none.
  Eigen::SparseMatrix<double> eq_matrix;
  Eigen::VectorXd eq_rhs;

  // Copies of one point (global parametrization: the wedges of a seam vertex), for solvers
  // that move one point at a time (relax). Empty, or #V entries: copy_base[v] is the first
  // copy of v's group (v itself for a vertex without copies), -1 for a copy that must hold
  // still while the equalities' translations are held (a singular seam vertex); rows
  // v*n .. v*n+n-1 of copy_rotation hold R_v with q_v = R_v q_base + t_v. Moving the base
  // by d moves copy v by R_v d and keeps every equality (docs/gparam.md, "relax").
  std::vector<int> copy_base;
  Eigen::MatrixXd copy_rotation;

  int num_elements() const { return static_cast<int>(elements.rows()); }
  int corners() const { return domain_dim + 1; }
  int jacobian_size() const { return image_dim * domain_dim; }
  bool has_equalities() const { return eq_matrix.rows() > 0; }

  // Index of each vertex among the free ones (-1 for fixed vertices), and their number.
  std::vector<int> free_index() const;
  int num_free() const;

  // Differential of the map X (#V by n) on element e (n by m).
  Eigen::MatrixXd jacobian(int e, const Eigen::MatrixXd& X) const;
  Eigen::MatrixXd target(int e) const { return targets.middleRows(e * image_dim, image_dim); }
  void set_target(int e, const Eigen::MatrixXd& R) { targets.middleRows(e * image_dim, image_dim) = R; }

  // Sparse operator from the full dof vector (n*#V) to the stacked vec(J_T) (#E*n*m).
  Eigen::SparseMatrix<double> jacobian_operator() const;

  // The same restricted to the free dofs: vec(J - R) = G x - h, with x the free dofs in
  // vertex-major order over free vertices (free_index) and h = vec(R) - G_fixed q_fixed.
  struct Reduced {
    Eigen::SparseMatrix<double> G;
    Eigen::VectorXd h;
  };
  Reduced reduced() const;

  // Free dofs of X, and X with its free dofs replaced by x.
  Eigen::VectorXd free_dofs(const Eigen::MatrixXd& X) const;
  Eigen::MatrixXd with_free_dofs(const Eigen::VectorXd& x) const;

  // Fix vertices at given positions (positional constraints). Throws InputError on a
  // vertex out of range, a position of the wrong dimension, or fixed / positions not sized
  // #V and #V by image_dim.
  void fix(const std::vector<Handle>& handles);
};

// Problems for the three kinds of element, targets R_T = identity, nothing fixed, start
// positions = rest positions (for surfaces: zero).
// planar triangles: V is #V by 2 (or 3 with constant z), image_dim = domain_dim = 2;
// surface triangles: each in an isometric frame of its own, image_dim = domain_dim = 2;
// tets: image_dim = domain_dim = 3.
// Vertices used by no element are fixed where they are. Throws InputError for a mesh
// check_mesh_structure refuses and for a mesh without elements.
Problem make_problem(const Mesh& mesh);

// The same with every triangle of a 3D surface in its own frame, even when the surface is
// flat (constant z): the frames that targets written per face (local_frame_coordinates'
// x axis along the first edge) are in, as the seamless problem's are.
Problem make_surface_problem(const Mesh& mesh);

// Per-element isometric 2D frame of a 3D triangle: returns the corners' 2D coordinates
// (3 by 2), first corner at the origin, first edge along the x axis.
Eigen::Matrix<double, 3, 2> local_frame_coordinates(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                                    const Eigen::Vector3d& p2);

}  // namespace strictmin
