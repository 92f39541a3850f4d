// The smoothest cross field (Knoeppel et al. 2013) and face frames (docs/gparam.md).
#include "strictmin/field/cross_field.h"

#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Geometry>
#include <Eigen/SparseCore>

#include "strictmin/io/input_error.h"
#include "strictmin/solvers/sparse_cholesky.h"
#include "solvers/serial_cholmod_scope.h"

namespace strictmin {
namespace {

using Complex = std::complex<double>;

Eigen::Vector3d row3(const Eigen::MatrixXd& M, int r) { return M.row(r).transpose(); }

double edge_weight(const Mesh& mesh, const SurfaceGraph& g, const FaceFrames& fr, int e) {
  const double len2 = (mesh.V.row(g.edges(e, 1)) - mesh.V.row(g.edges(e, 0))).squaredNorm();
  return 3.0 * len2 / (fr.area(g.edge_faces(e, 0)) + fr.area(g.edge_faces(e, 1)));
}

// Adds the complex entry c at (i, j) of a Hermitian matrix as its real 2x2 block
// [[Re c, -Im c], [Im c, Re c]] (unknowns interleaved: 2f = Re u_f, 2f+1 = Im u_f).
void add_block(std::vector<Eigen::Triplet<double>>& t, int i, int j, Complex c) {
  t.emplace_back(2 * i, 2 * j, c.real());
  t.emplace_back(2 * i, 2 * j + 1, -c.imag());
  t.emplace_back(2 * i + 1, 2 * j, c.imag());
  t.emplace_back(2 * i + 1, 2 * j + 1, c.real());
}

// E as a real symmetric 2F by 2F matrix (see the header).
Eigen::SparseMatrix<double> energy_matrix(const Mesh& mesh, const SurfaceGraph& g, const FaceFrames& fr) {
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<size_t>(g.num_edges()) * 16);
  for (int e = 0; e < g.num_edges(); ++e) {
    const int f = g.edge_faces(e, 0), h = g.edge_faces(e, 1);
    const double w = edge_weight(mesh, g, fr, e);
    const Complex rho = std::polar(1.0, 4.0 * fr.transport(e));
    // w |u_h - rho u_f|^2 = w (|u_h|^2 + |u_f|^2 - 2 Re(conj(u_h) rho u_f))
    add_block(t, f, f, w);
    add_block(t, h, h, w);
    add_block(t, h, f, -w * rho);
    add_block(t, f, h, -w * std::conj(rho));
  }
  Eigen::SparseMatrix<double> A(2 * g.num_faces, 2 * g.num_faces);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

void normalize_per_face(const Eigen::VectorXd& x, Eigen::VectorXcd& u) {
  u.resize(x.size() / 2);
  for (Eigen::Index f = 0; f < u.size(); ++f) {
    const Complex z(x(2 * f), x(2 * f + 1));
    u(f) = std::abs(z) > 0 ? z / std::abs(z) : Complex(1, 0);
  }
}

// Multiplies the field by the global phase that gives face `f` the direction d.
void pin_phase(Eigen::VectorXcd& u, int f, const Eigen::Vector3d& d, const FaceFrames& fr) {
  const double a = std::atan2(d.dot(row3(fr.y, f)), d.dot(row3(fr.x, f)));
  u *= std::polar(1.0, 4.0 * a) / u(f);
}

}  // namespace

FaceFrames face_frames(const Mesh& mesh, const SurfaceGraph& g) {
  FaceFrames fr;
  const int F = g.num_faces;
  fr.x.resize(F, 3);
  fr.y.resize(F, 3);
  fr.normal.resize(F, 3);
  fr.area.resize(F);
  for (int f = 0; f < F; ++f) {
    const Eigen::Vector3d p0 = row3(mesh.V, mesh.F(f, 0)), p1 = row3(mesh.V, mesh.F(f, 1)),
                          p2 = row3(mesh.V, mesh.F(f, 2));
    const Eigen::Vector3d n = (p1 - p0).cross(p2 - p0);
    fr.area(f) = 0.5 * n.norm();
    fr.normal.row(f) = n.normalized().transpose();
    fr.x.row(f) = (p1 - p0).normalized().transpose();
    fr.y.row(f) = n.normalized().cross((p1 - p0).normalized()).transpose();
  }
  fr.transport.resize(g.num_edges());
  for (int e = 0; e < g.num_edges(); ++e) {
    const Eigen::Vector3d d = row3(mesh.V, g.edges(e, 1)) - row3(mesh.V, g.edges(e, 0));
    const int f = g.edge_faces(e, 0), h = g.edge_faces(e, 1);
    const double theta_f = std::atan2(d.dot(row3(fr.y, f)), d.dot(row3(fr.x, f)));
    const double theta_h = std::atan2(d.dot(row3(fr.y, h)), d.dot(row3(fr.x, h)));
    fr.transport(e) = theta_h - theta_f;
  }
  return fr;
}

double field_energy(const Eigen::VectorXcd& u, const Mesh& mesh, const SurfaceGraph& g, const FaceFrames& fr) {
  double sum = 0;
  for (int e = 0; e < g.num_edges(); ++e) {
    const int f = g.edge_faces(e, 0), h = g.edge_faces(e, 1);
    sum += edge_weight(mesh, g, fr, e) * std::norm(u(h) - std::polar(1.0, 4.0 * fr.transport(e)) * u(f));
  }
  return sum;
}

CrossField smoothest_cross_field(const Mesh& mesh, const SurfaceGraph& g, const FaceFrames& fr,
                                 const CrossFieldOptions& options) {
  const int F = g.num_faces;
  const Eigen::SparseMatrix<double> A = energy_matrix(mesh, g, fr);
  Eigen::VectorXd mass(2 * F);
  for (int f = 0; f < F; ++f) mass(2 * f) = mass(2 * f + 1) = fr.area(f);
  // Shift: A may be singular (a zero-energy field exists, e.g. on a polycube).
  const double eps = 1e-8 * A.diagonal().sum() / mass.sum();
  Eigen::SparseMatrix<double> S = A;
  for (int i = 0; i < 2 * F; ++i) S.coeffRef(i, i) += eps * mass(i);
  SerialCholmodScope serial;
  SparseCholesky cholesky(true);  // AMD: as good as METIS here and much faster to compute
  cholesky.analyze(S);
  CrossField out;
  if (!cholesky.factorize(S)) throw InputError("cross field: the connection Laplacian could not be factorized");

  std::mt19937 random(12345);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::VectorXd x(2 * F);
  for (int i = 0; i < 2 * F; ++i) x(i) = uniform(random);
  auto m_normalize = [&](Eigen::VectorXd& v) { v /= std::sqrt(v.dot(mass.cwiseProduct(v))); };
  m_normalize(x);
  // The real operator acts on the complex eigenvector's plane {x, ix} as a real scalar, so
  // the iterates settle without turning: stop when one moves by less than the tolerance.
  for (int it = 1; it <= options.max_iterations; ++it) {
    Eigen::VectorXd next = cholesky.solve(mass.cwiseProduct(x));
    m_normalize(next);
    const Eigen::VectorXd change = next - x;
    x.swap(next);
    out.iterations = it;
    if (std::sqrt(change.dot(mass.cwiseProduct(change))) <= options.tolerance) break;
  }
  normalize_per_face(x, out.u);
  if (options.pin_face >= 0 && options.pin_face < F) pin_phase(out.u, options.pin_face, options.pin_direction, fr);
  out.energy = field_energy(out.u, mesh, g, fr);
  return out;
}

// Face shape operators from dihedral angles: S_f = sum over f's edges of theta_e |e| m m^T
// (m: the edge's in-plane normal, in f's frame); returns (S_xx - S_yy)/2 + i S_xy squared over
// its modulus: |k1 - k2|/2-weighted e^{4i phi} for a principal direction phi.
Eigen::VectorXcd curvature_directions(const Mesh& mesh, const SurfaceGraph& g, const FaceFrames& fr) {
  Eigen::VectorXcd q = Eigen::VectorXcd::Zero(g.num_faces);
  for (int e = 0; e < g.num_edges(); ++e) {
    const int f = g.edge_faces(e, 0), h = g.edge_faces(e, 1);
    const Eigen::Vector3d d = row3(mesh.V, g.edges(e, 1)) - row3(mesh.V, g.edges(e, 0));
    const Eigen::Vector3d nf = row3(fr.normal, f), nh = row3(fr.normal, h);
    const double theta = std::atan2(nf.cross(nh).dot(d.normalized()), nf.dot(nh));
    for (int side : {f, h}) {
      // In-plane normal of the edge at angle a + pi/2: m m^T has (xx - yy)/2 + i xy = -e^{2ia}/2.
      const double a = std::atan2(d.dot(row3(fr.y, side)), d.dot(row3(fr.x, side)));
      q(side) += -0.5 * theta * d.norm() * std::polar(1.0, 2.0 * a);
    }
  }
  for (int f = 0; f < g.num_faces; ++f) q(f) = std::abs(q(f)) > 0 ? q(f) * q(f) / std::abs(q(f)) : Complex(0, 0);
  return q;
}

CrossField curvature_cross_field(const Mesh& mesh, const SurfaceGraph& g, const FaceFrames& fr, double alignment) {
  const int F = g.num_faces;
  Eigen::VectorXcd q = curvature_directions(mesh, g, fr);
  double mean = 0;
  for (int f = 0; f < F; ++f) mean += fr.area(f) * std::abs(q(f));
  mean /= fr.area.sum();
  if (mean > 0) q /= mean;
  const Eigen::SparseMatrix<double> A = energy_matrix(mesh, g, fr);
  Eigen::VectorXd mass(2 * F), rhs(2 * F);
  for (int f = 0; f < F; ++f) mass(2 * f) = mass(2 * f + 1) = fr.area(f);
  const double s = alignment * A.diagonal().sum() / mass.sum();
  Eigen::SparseMatrix<double> S = A;
  for (int i = 0; i < 2 * F; ++i) S.coeffRef(i, i) += s * mass(i);
  for (int f = 0; f < F; ++f) {
    rhs(2 * f) = s * fr.area(f) * q(f).real();
    rhs(2 * f + 1) = s * fr.area(f) * q(f).imag();
  }
  SerialCholmodScope serial;
  SparseCholesky cholesky(true);
  cholesky.analyze(S);
  if (!cholesky.factorize(S)) throw InputError("cross field: the curvature system could not be factorized");
  const Eigen::VectorXd x = cholesky.solve(rhs).col(0);
  CrossField out;
  normalize_per_face(x, out.u);
  out.iterations = 1;
  out.energy = field_energy(out.u, mesh, g, fr);
  return out;
}

CrossField cross_field_from_directions(const Eigen::MatrixXd& d, const FaceFrames& fr, const std::string& source) {
  const Eigen::Index F = fr.x.rows();
  const std::string name = source.empty() ? std::string("field") : source;
  if (d.rows() != F || d.cols() != 3)
    throw InputError(name + ": " + std::to_string(d.rows()) + " directions for " + std::to_string(F) +
                     " faces (one 3D direction per face, one per line)");
  CrossField out;
  out.u.resize(F);
  for (Eigen::Index f = 0; f < F; ++f) {
    const Eigen::Vector3d v = d.row(f).transpose();
    const std::string where = located(name, static_cast<long>(f) + 1, "face " + std::to_string(f) + ": ");
    if (!v.allFinite()) throw InputError(where + "the direction is not finite");
    const double a = v.dot(row3(fr.x, static_cast<int>(f))), b = v.dot(row3(fr.y, static_cast<int>(f)));
    if (!(std::hypot(a, b) > 1e-9 * v.norm()) || v.norm() == 0)
      throw InputError(where + "the direction is zero or perpendicular to the face");
    out.u(f) = std::polar(1.0, 4.0 * std::atan2(b, a));
  }
  return out;
}

Eigen::MatrixXd field_directions(const CrossField& field, const FaceFrames& fr) {
  Eigen::MatrixXd d(field.u.size(), 3);
  for (Eigen::Index f = 0; f < field.u.size(); ++f) {
    const double a = std::arg(field.u(f)) / 4.0;
    d.row(f) = std::cos(a) * fr.x.row(f) + std::sin(a) * fr.y.row(f);
  }
  return d;
}

}  // namespace strictmin
