// The smoothest cross field (Knoeppel et al. 2013) and face frames (docs/gparam.md).
#include "strictmin/solvers/interrupt.h"
#include "strictmin/field/cross_field.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <utility>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "field/hermitian_cholesky.h"
#include "field/lanczos.h"
#include "strictmin/io/input_error.h"
#include "strictmin/solvers/timing.h"
#include "solvers/option_check.h"
#include "solvers/serial_cholmod_scope.h"

namespace strictmin {
namespace {

using Complex = std::complex<double>;

Eigen::Vector3d row3(const Eigen::MatrixXd& M, int r) { return M.row(r).transpose(); }

// Factors the field's Hermitian system and records the analysis and factorization times.
void factorize_or_throw(HermitianCholesky& cholesky, const HermitianLower& A, const std::string& system,
                        CrossField& out) {
  if (!cholesky.factorize(A)) throw InputError("cross field: the " + system + " could not be factorized");
  out.timing.analyze_s = cholesky.analyze_s;
  out.timing.factorize_s = cholesky.factorize_s;
}

// E + D (D diagonal) as a complex F by F Hermitian matrix, lower triangle (see the header): per edge
// w (|u_f|^2 + |u_h|^2) on the diagonal and -w rho at (h, f) (-w conj(rho) at (f, h)).
HermitianLower hermitian_energy(const Mesh& mesh, const SurfaceGraph& g, const FaceFrames& fr,
                                const Eigen::VectorXd& diagonal) {
  const int F = g.num_faces, E = g.num_edges();
  HermitianLower A;
  A.n = F;
  A.start.assign(F + 1, 0);
  for (int e = 0; e < E; ++e)
    if (!g.is_boundary_edge(e)) ++A.start[std::min(g.edge_faces(e, 0), g.edge_faces(e, 1)) + 1];
  for (int f = 0; f < F; ++f) A.start[f + 1] += A.start[f] + 1;  // + 1: the diagonal
  A.row.resize(A.start[F]);
  A.value.assign(A.start[F], Complex(0, 0));
  std::vector<int> next(A.start.begin(), A.start.end() - 1);
  for (int f = 0; f < F; ++f) {
    A.row[next[f]] = f;
    A.value[next[f]++] = diagonal(f);
  }
  for (int e = 0; e < E; ++e) {
    if (g.is_boundary_edge(e)) continue;
    const int f = g.edge_faces(e, 0), h = g.edge_faces(e, 1);
    const double w = field_edge_weight(mesh, g, fr, e);
    const Complex rho = std::polar(1.0, 4.0 * fr.transport(e));
    A.value[A.start[f]] += w;
    A.value[A.start[h]] += w;
    const int col = std::min(f, h), k = next[col]++;
    A.row[k] = std::max(f, h);
    A.value[k] = h > f ? -w * rho : -w * std::conj(rho);
  }
  // Rows sorted within each column (the diagonal stays first), duplicates (two faces that
  // share two edges) summed.
  std::vector<int> start(F + 1, 0), row;
  std::vector<Complex> value;
  row.reserve(A.row.size());
  value.reserve(A.row.size());
  std::vector<std::pair<int, Complex>> column;
  for (int f = 0; f < F; ++f) {
    column.clear();
    for (int k = A.start[f]; k < A.start[f + 1]; ++k) column.emplace_back(A.row[k], A.value[k]);
    std::sort(column.begin(), column.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& [r, v] : column) {
      if (!row.empty() && static_cast<int>(row.size()) > start[f] && row.back() == r) {
        value.back() += v;
      } else {
        row.push_back(r);
        value.push_back(v);
      }
    }
    start[f + 1] = static_cast<int>(row.size());
  }
  A.start.swap(start);
  A.row.swap(row);
  A.value.swap(value);
  return A;
}

double trace(const HermitianLower& A) {
  double sum = 0;
  for (int f = 0; f < A.n; ++f) sum += A.value[A.start[f]].real();  // the diagonal is first
  return sum;
}

Eigen::VectorXcd normalize_per_face(const Eigen::VectorXcd& x) {
  Eigen::VectorXcd u(x.size());
  for (Eigen::Index f = 0; f < x.size(); ++f) u(f) = std::abs(x(f)) > 0 ? x(f) / std::abs(x(f)) : Complex(1, 0);
  return u;
}

// CrossFieldOptions::unit: from the normalized eigenvector u, steps of
// u <- normalize((E + s M)^-1 s M u) (E + s M factored in the cholesky that held E + eps M:
// the same pattern, so its analysis is kept); returns the field of least E met.
void lower_among_unit_fields(const Mesh& mesh, const SurfaceGraph& g, const FaceFrames& fr,
                             const CrossFieldOptions& options, HermitianLower& A, double eps,
                             HermitianCholesky& cholesky, CrossField& out) {
  const auto t0 = std::chrono::steady_clock::now();
  const int F = g.num_faces;
  const double s = options.unit_diffusion * (trace(A) - eps * fr.area.sum()) / fr.area.sum();
  for (int f = 0; f < F; ++f) A.value[A.start[f]] += (s - eps) * fr.area(f);
  if (!cholesky.factorize(A)) throw InputError("cross field: the unit field's diffusion system could not be factorized");
  cholesky.compact_for_solves();
  const Eigen::VectorXcd sM = s * fr.area.cast<Complex>();
  Eigen::VectorXcd u = out.u;
  double best = out.energy;
  int since_progress = 0;
  for (int step = 1; step <= options.unit_max_steps && since_progress < options.unit_patience; ++step) {
    check_interrupt();  // solvers/interrupt.h
    u = u.cwiseProduct(sM);
    cholesky.solve_in_place(u);
    u = normalize_per_face(u);
    const double energy = field_energy(u, mesh, g, fr);
    out.unit_steps = step;
    ++since_progress;
    if (energy < best) {
      if (energy < (1.0 - options.unit_progress) * best) since_progress = 0;
      best = energy;
      out.u = u;
    }
  }
  out.energy = best;
  out.timing.unit_s = seconds_since(t0);
}

// The field a boundary face must have (docs/gparam.md, "Surfaces with boundary"): the
// fourth power of its boundary side's direction; a face with two boundary sides takes the
// normalized sum of both (the longer side's when the two are 45 degrees apart and cancel).
// Zero on interior faces.
Eigen::VectorXcd boundary_alignment(const Mesh& mesh, const SurfaceGraph& g, const FaceFrames& fr) {
  Eigen::VectorXcd q = Eigen::VectorXcd::Zero(g.num_faces);
  for (int f = 0; f < g.num_faces; ++f) {
    Complex sum(0, 0), longest(0, 0);
    double longest_length = -1;
    for (int i = 0; i < 3; ++i) {
      if (!g.is_boundary_edge(g.face_edges(f, i))) continue;
      const Eigen::Vector3d d = row3(mesh.V, mesh.F(f, (i + 1) % 3)) - row3(mesh.V, mesh.F(f, i));
      const Complex side = std::polar(1.0, 4.0 * fr.angle(f, d));
      sum += side;
      if (d.norm() > longest_length) {
        longest_length = d.norm();
        longest = side;
      }
    }
    if (longest_length >= 0) q(f) = std::abs(sum) > 1e-6 ? sum / std::abs(sum) : longest;
  }
  return q;
}

// Solves A x = rhs with x fixed to `fixed_value` on the faces where it is non-zero (the
// boundary faces): A's free rows and columns factored, the fixed columns moved to the
// right-hand side. A's free block is positive definite when every free face is connected to
// a fixed one (a connected surface with boundary).
Eigen::VectorXcd solve_with_fixed_faces(const HermitianLower& A, const Eigen::VectorXcd& rhs,
                                        const Eigen::VectorXcd& fixed_value, const std::string& system,
                                        CrossField& out) {
  const int n = A.n;
  std::vector<int> free_index(n, -1);
  int m = 0;
  for (int f = 0; f < n; ++f)
    if (fixed_value(f) == Complex(0, 0)) free_index[f] = m++;
  HermitianLower free;
  free.n = m;
  free.start.assign(m + 1, 0);
  Eigen::VectorXcd b(m);
  for (int f = 0; f < n; ++f)
    if (free_index[f] >= 0) b(free_index[f]) = rhs(f);
  for (int c = 0; c < n; ++c) {
    for (int k = A.start[c]; k < A.start[c + 1]; ++k) {
      const int r = A.row[k];  // A(r, c) = value, A(c, r) = conj(value)
      const bool rf = free_index[r] >= 0, cf = free_index[c] >= 0;
      if (rf && cf) {
        free.row.push_back(free_index[r]);
        free.value.push_back(A.value[k]);
      } else if (rf) {
        b(free_index[r]) -= A.value[k] * fixed_value(c);
      } else if (cf) {
        b(free_index[c]) -= std::conj(A.value[k]) * fixed_value(r);
      }
    }
    if (free_index[c] >= 0) free.start[free_index[c] + 1] = static_cast<int>(free.row.size());
  }
  Eigen::VectorXcd x = fixed_value;
  if (m == 0) return x;
  SerialCholmodScope serial;
  HermitianCholesky cholesky;
  factorize_or_throw(cholesky, free, system, out);
  const Eigen::VectorXcd y = cholesky.solve(b);
  for (int f = 0; f < n; ++f)
    if (free_index[f] >= 0) x(f) = y(free_index[f]);
  return x;
}

}  // namespace

bool CrossFieldOptions::is_valid(std::string* why) const {
  OptionCheck check(why);
  check.at_least("max_iterations", max_iterations, 1)
      .at_least("pin_face", pin_face, -1)
      .positive("tolerance", tolerance)
      .positive("unit_diffusion", unit_diffusion)
      .at_least("unit_max_steps", unit_max_steps, 0)
      .at_least("unit_patience", unit_patience, 1)
      .non_negative("unit_progress", unit_progress)
      .that(pin_direction.allFinite(), "pin_direction must be finite");
  return check.ok();
}

void pin_field_rotation(Eigen::VectorXcd& u, int f, const Eigen::Vector3d& d, const FaceFrames& fr) {
  u *= std::polar(1.0, 4.0 * fr.angle(f, d)) / u(f);
}

double field_edge_weight(const Mesh& mesh, const SurfaceGraph& g, const FaceFrames& fr, int e) {
  const double len2 = (mesh.V.row(g.edges(e, 1)) - mesh.V.row(g.edges(e, 0))).squaredNorm();
  return 3.0 * len2 / (fr.area(g.edge_faces(e, 0)) + fr.area(g.edge_faces(e, 1)));
}

double FaceFrames::angle(int f, const Eigen::Vector3d& d) const { return std::atan2(d.dot(row3(y, f)), d.dot(row3(x, f))); }

double FaceFrames::transport_from(const SurfaceGraph& g, int e, int f) const {
  return g.edge_faces(e, 0) == f ? transport(e) : -transport(e);
}

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
    fr.transport(e) = 0;
    if (g.is_boundary_edge(e)) continue;
    const Eigen::Vector3d d = row3(mesh.V, g.edges(e, 1)) - row3(mesh.V, g.edges(e, 0));
    const int f = g.edge_faces(e, 0), h = g.edge_faces(e, 1);
    fr.transport(e) = fr.angle(h, d) - fr.angle(f, d);
  }
  return fr;
}

double field_energy(const Eigen::VectorXcd& u, const Mesh& mesh, const SurfaceGraph& g, const FaceFrames& fr) {
  double sum = 0;
  for (int e = 0; e < g.num_edges(); ++e) {
    if (g.is_boundary_edge(e)) continue;
    const int f = g.edge_faces(e, 0), h = g.edge_faces(e, 1);
    sum += field_edge_weight(mesh, g, fr, e) * std::norm(u(h) - std::polar(1.0, 4.0 * fr.transport(e)) * u(f));
  }
  return sum;
}

namespace {

// The smoothest field on a surface with boundary: E(u) least with u fixed on the boundary
// faces to their boundary sides' directions (a Dirichlet problem: one solve, no eigenvector),
// normalized per face. options.unit and pin_face are refused (the boundary sets the rotation).
CrossField aligned_smoothest_field(const Mesh& mesh, const SurfaceGraph& g, const FaceFrames& fr,
                                   const CrossFieldOptions& options) {
  if (options.unit) throw InputError("cross field: the unit field (--field unit) takes closed surfaces only");
  if (options.pin_face >= 0)
    throw InputError("cross field: pin_face is for closed surfaces (on a surface with boundary the boundary sets the "
                     "field's rotation)");
  const auto t0 = std::chrono::steady_clock::now();
  const HermitianLower A = hermitian_energy(mesh, g, fr, Eigen::VectorXd::Zero(g.num_faces));
  CrossField out;
  out.timing.assemble_s = seconds_since(t0);
  const auto t1 = std::chrono::steady_clock::now();
  out.u = normalize_per_face(solve_with_fixed_faces(A, Eigen::VectorXcd::Zero(g.num_faces),
                                                    boundary_alignment(mesh, g, fr), "connection Laplacian", out));
  out.timing.iterate_s = seconds_since(t1) - out.timing.analyze_s - out.timing.factorize_s;
  out.iterations = 1;
  out.energy = out.eigen_energy = field_energy(out.u, mesh, g, fr);
  return out;
}

}  // namespace

CrossField smoothest_cross_field(const Mesh& mesh, const SurfaceGraph& g, const FaceFrames& fr,
                                 const CrossFieldOptions& options) {
  std::string why;
  if (!options.is_valid(&why)) throw InputError("cross field options: " + why);
  const int F = g.num_faces;
  if (g.has_boundary()) return aligned_smoothest_field(mesh, g, fr, options);
  auto t0 = std::chrono::steady_clock::now();
  HermitianLower A = hermitian_energy(mesh, g, fr, Eigen::VectorXd::Zero(F));
  // Shift: E may be singular (a zero-energy field exists, e.g. on a polycube).
  const double eps = 1e-8 * trace(A) / fr.area.sum();
  for (int f = 0; f < F; ++f) A.value[A.start[f]] += eps * fr.area(f);
  CrossField out;
  out.timing.assemble_s = seconds_since(t0);
  SerialCholmodScope serial;
  HermitianCholesky cholesky;
  factorize_or_throw(cholesky, A, "connection Laplacian", out);
  t0 = std::chrono::steady_clock::now();
  cholesky.compact_for_solves();  // 20-30 solves follow
  // A fixed pseudo-random start: the field's global phase is that of its projection.
  std::mt19937 random(12345);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::VectorXcd x0(F);
  for (int f = 0; f < F; ++f) {
    const double re = uniform(random);
    x0(f) = Complex(re, uniform(random));
  }
  const LanczosResult eigen = lanczos_smallest(cholesky, fr.area, x0, options.max_iterations, options.tolerance);
  out.timing.iterate_s = seconds_since(t0);
  if (!eigen.vector.allFinite()) throw InputError("cross field: the eigenvector iteration gave non-finite values");
  out.iterations = eigen.steps;
  out.residual = eigen.residual;
  out.u = normalize_per_face(eigen.vector);
  out.energy = out.eigen_energy = field_energy(out.u, mesh, g, fr);
  if (options.unit) lower_among_unit_fields(mesh, g, fr, options, A, eps, cholesky, out);
  if (options.pin_face >= F)
    throw InputError("cross field: pin_face " + std::to_string(options.pin_face) + " is beyond the mesh's " +
                     std::to_string(F) + " faces");
  if (options.pin_face >= 0) pin_field_rotation(out.u, options.pin_face, options.pin_direction, fr);
  return out;
}

// Face shape operators from dihedral angles: S_f = sum over f's edges of theta_e |e| m m^T
// (m: the edge's in-plane normal, in f's frame); returns (S_xx - S_yy)/2 + i S_xy squared over
// its modulus: |k1 - k2|/2-weighted e^{4i phi} for a principal direction phi.
Eigen::VectorXcd curvature_directions(const Mesh& mesh, const SurfaceGraph& g, const FaceFrames& fr) {
  Eigen::VectorXcd q = Eigen::VectorXcd::Zero(g.num_faces);
  for (int e = 0; e < g.num_edges(); ++e) {
    if (g.is_boundary_edge(e)) continue;  // no dihedral angle
    const int f = g.edge_faces(e, 0), h = g.edge_faces(e, 1);
    const Eigen::Vector3d d = row3(mesh.V, g.edges(e, 1)) - row3(mesh.V, g.edges(e, 0));
    const Eigen::Vector3d nf = row3(fr.normal, f), nh = row3(fr.normal, h);
    const double theta = std::atan2(nf.cross(nh).dot(d.normalized()), nf.dot(nh));
    for (int side : {f, h}) {
      // In-plane normal of the edge at angle a + pi/2: m m^T has (xx - yy)/2 + i xy = -e^{2ia}/2.
      const double a = fr.angle(side, d);
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
  const auto t0 = std::chrono::steady_clock::now();
  HermitianLower A = hermitian_energy(mesh, g, fr, Eigen::VectorXd::Zero(F));
  const double s = alignment * trace(A) / fr.area.sum();
  for (int f = 0; f < F; ++f) A.value[A.start[f]] += s * fr.area(f);
  const Eigen::VectorXcd rhs = s * fr.area.cast<Complex>().cwiseProduct(q);
  CrossField out;
  out.timing.assemble_s = seconds_since(t0);
  if (g.has_boundary()) {
    out.u = normalize_per_face(solve_with_fixed_faces(A, rhs, boundary_alignment(mesh, g, fr), "curvature system", out));
  } else {
    SerialCholmodScope serial;
    HermitianCholesky cholesky;
    factorize_or_throw(cholesky, A, "curvature system", out);
    out.u = normalize_per_face(cholesky.solve(rhs));
  }
  out.iterations = 1;
  out.energy = field_energy(out.u, mesh, g, fr);
  return out;
}

CrossField cross_field_from_directions(const Eigen::MatrixXd& d, const FaceFrames& fr, const std::string& source,
                                      const std::vector<long>& lines) {
  const Eigen::Index F = fr.x.rows();
  const std::string name = source.empty() ? std::string("field") : source;
  if (d.rows() != F || d.cols() != 3)
    throw InputError(name + ": " + std::to_string(d.rows()) + " directions for " + std::to_string(F) +
                     " faces (one 3D direction per face" + (lines.empty() ? ")" : ", one per line)"));
  CrossField out;
  out.u.resize(F);
  for (Eigen::Index f = 0; f < F; ++f) {
    const std::string face = "face " + std::to_string(f) + ": ";
    const std::string where = static_cast<Eigen::Index>(lines.size()) == F
                                  ? located(name, lines[static_cast<size_t>(f)], face)
                                  : name + ": " + face;
    const Eigen::Vector3d given = d.row(f).transpose();
    if (!given.allFinite()) throw InputError(where + "the direction is not finite");
    // Scaled to its largest component first: 1e308 or 1e-320 are directions too (their norm
    // overflows or underflows).
    const double largest = given.cwiseAbs().maxCoeff();
    if (largest == 0) throw InputError(where + "the direction is zero");
    const Eigen::Vector3d v = given / largest;
    const double a = v.dot(row3(fr.x, static_cast<int>(f))), b = v.dot(row3(fr.y, static_cast<int>(f)));
    if (!(std::hypot(a, b) > 1e-9 * v.norm()))
      throw InputError(where + "the direction is perpendicular to the face");
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
