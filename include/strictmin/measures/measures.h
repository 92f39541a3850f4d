#pragma once
// Per-element distortion measures of a differential J (image_dim by domain_dim; exact
// closed forms for 2x2, SVD for 3x3 and the rest). One enum, one place each.
//
//   fd    field deviation        ||J - R||_F, R the element's target matrix
//   arap  as-rigid-as-possible   min over rotations Q of ||J - Q||_F
//   asap  as-similar-as-possible min over similarities sQ of ||J - sQ||_F
//   qc    quasiconformal         sigma_1 / sigma_d  (1 for a similarity)
//   iso   isometric              max(sigma_1, 1 / sigma_d)  (1 for a rotation)
//
// Singular values are signed: when det J < 0 the smallest one is negative, so ARAP and ASAP
// measure the distance to proper rotations, and qc / iso are +infinity for a flipped or
// degenerate element (det J <= 0).
#include <Eigen/Core>
#include <optional>
#include <string>

namespace strictmin {

enum class Measure { FieldDeviation, Arap, Asap, Quasiconformal, Isometric };

std::string measure_name(Measure m);  // "fd", "arap", "asap", "qc", "iso"
// Accepts the short names above and long ones ("field-deviation", "quasiconformal",
// "isometric"); nullopt otherwise.
std::optional<Measure> parse_measure(const std::string& name);

// Signed singular values, largest first (the last is negative when det J < 0).
Eigen::VectorXd signed_singular_values(const Eigen::MatrixXd& J);

// Closest rotation to J in the Frobenius norm (the ARAP local step); for a non-square J
// (a 3D surface's 3 by 2 differential) the closest matrix with orthonormal columns.
Eigen::MatrixXd closest_rotation(const Eigen::MatrixXd& J);
// Closest similarity s Q (Q a rotation, s >= 0 real) to J (the ASAP local step).
Eigen::MatrixXd closest_similarity(const Eigen::MatrixXd& J);

// D(J) for the measure; R is only read by fd.
double distortion(Measure m, const Eigen::MatrixXd& J, const Eigen::MatrixXd& R);

// det J <= 0 (square J only; a non-square J never counts as flipped). A collapsed element
// counts too: its smallest singular value at most kCollapsedRatio times its largest, where
// rounding alone decides the sign of det J (a tet with two vertices on one point has det J
// of 1e-17 either way); qc is infinite there.
bool is_flipped(const Eigen::MatrixXd& J);
constexpr double kCollapsedRatio = 1e-12;

}  // namespace strictmin
