#include "linf_program.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/SparseCholesky>

namespace strictmin::linf_detail {

std::string format(double v) {
  std::ostringstream os;
  os.precision(6);
  os << v;
  return os.str();
}

socp::IpmSettings ipm_settings(const LinfOptions& o) {
  socp::IpmSettings s;
  s.max_iterations = o.max_iterations;
  s.gap_tolerance = o.gap_tolerance;
  s.feasibility_tolerance = o.feasibility_tolerance;
  s.step_fraction = o.step_fraction;
  s.regularization = o.regularization;
  s.refinement_steps = o.refinement_steps;
  s.eliminate_equalities = o.eliminate_equalities;
  s.verbose = o.verbose;
  return s;
}

// Cones in the order of their elements' first vertex (free and bounded elements each kept
// together): the passes over the cones then read the vertices, and the gathers over a
// vertex's cones (G^T) read the cones, nearly in order. The seamless problems keep the
// mesh's face order, which is far from its vertex order (horse: consecutive faces' first
// vertices 4,000 apart at the median), and the gathers waited on memory.
void order_by_vertices(const Problem& p, std::vector<int>& elems, int free_count) {
  auto first_vertex = [&](int e) { return p.elements.row(e).minCoeff(); };
  auto by_vertex = [&](int a, int b) { return first_vertex(a) < first_vertex(b); };
  std::stable_sort(elems.begin(), elems.begin() + free_count, by_vertex);
  std::stable_sort(elems.begin() + free_count, elems.end(), by_vertex);
}

MainProgram::MainProgram(const Problem& p, const LinfOptions& o, const socp::ElementClasses& classes)
    : problem(p), options(o), cls(classes) {
  const int n = p.image_dim;
  elems = cls.free_elements;
  elems.insert(elems.end(), cls.bounded_elements.begin(), cls.bounded_elements.end());
  if (p.has_equalities()) order_by_vertices(p, elems, static_cast<int>(cls.free_elements.size()));
  num_free_cones = static_cast<int>(cls.free_elements.size());
  vertex_dof.assign(p.num_vertices, -1);
  const std::vector<int> fi = p.free_index();
  for (int v = 0; v < p.num_vertices; ++v)
    if (fi[v] >= 0) vertex_dof[v] = fi[v] * n;
  num_x = p.num_free() * n;
  prog = socp::element_program(p, elems, vertex_dof, num_x, p.positions);
  // Bounded cones: head k_T instead of k.
  for (int i = num_free_cones; i < prog.num_element_cones(); ++i) {
    prog.head_a[i] = 0.0;
    prog.head_b[i] = o.element_bounds[elems[i]];
  }
  // Constant free elements: one scalar cone k - constant_max >= 0.
  has_kmin = cls.constant_max > -kInf;
  if (has_kmin) {
    prog.has_scalar = true;
    prog.head_a.conservativeResize(prog.num_cones());
    prog.head_b.conservativeResize(prog.num_cones());
    prog.head_a[prog.num_cones() - 1] = 1.0;
    prog.head_b[prog.num_cones() - 1] = -cls.constant_max;
  }
  has_k = num_free_cones > 0 || has_kmin;
  socp::restrict_equalities(p, vertex_dof, num_x, p.positions, p.fixed, prog);
}

double MainProgram::max_free(const Eigen::VectorXd& d) const {
  double k = has_kmin ? cls.constant_max : -kInf;
  for (int i = 0; i < num_free_cones; ++i) k = std::max(k, d[i]);
  return k;
}

bool MainProgram::bounds_met(const Eigen::VectorXd& d) const {
  for (int i = num_free_cones; i < prog.num_element_cones(); ++i)
    if (d[i] - prog.head_b[i] > options.feasibility_tolerance * std::max(1.0, prog.head_b[i])) return false;
  return true;
}

bool MainProgram::equalities_met(const Eigen::VectorXd& x) const {
  if (prog.num_eq() == 0) return true;
  const double scale = std::max(1.0, prog.beq.cwiseAbs().maxCoeff());
  return (prog.A * x - prog.beq).cwiseAbs().maxCoeff() <= options.feasibility_tolerance * scale;
}

Candidate MainProgram::evaluate(const Eigen::VectorXd& x) const {
  Candidate cd;
  cd.x = x;
  const Eigen::VectorXd d = socp::cone_distortions(prog, x);
  for (int i = 0; i < prog.num_element_cones(); ++i) {
    if (i < num_free_cones)
      cd.kmax = std::max(cd.kmax, d[i]);
    else
      cd.excess = std::max(cd.excess, d[i] - prog.head_b[i]);
  }
  if (has_kmin) cd.kmax = std::max(cd.kmax, cls.constant_max);
  return cd;
}

void MainProgram::widen_bounds(double amount) {
  for (int i = num_free_cones; i < prog.num_element_cones(); ++i) prog.head_b[i] += amount;
}

double MainProgram::bound_scale() const {
  double scale = 1.0;
  for (int i = num_free_cones; i < prog.num_element_cones(); ++i) scale = std::max(scale, prog.head_b[i]);
  return scale;
}

Eigen::VectorXd onto_equalities(const socp::ConeProgram& prog, Eigen::VectorXd x) {
  if (prog.num_eq() == 0 || x.size() != prog.num_x) return x;
  const Eigen::VectorXd residual = prog.beq - prog.A * x;
  if (residual.cwiseAbs().maxCoeff() == 0) return x;
  const Eigen::SparseMatrix<double> A = prog.A;
  Eigen::SparseMatrix<double> aat = Eigen::SparseMatrix<double>(A * A.transpose());
  double largest = 0;
  for (int r = 0; r < aat.rows(); ++r) largest = std::max(largest, aat.coeff(r, r));
  if (!(largest > 0)) return x;
  for (int r = 0; r < aat.rows(); ++r) aat.coeffRef(r, r) += 1e-13 * largest;  // redundant rows
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(aat);
  if (ldlt.info() != Eigen::Success) return x;
  const Eigen::VectorXd move = A.transpose() * ldlt.solve(residual);
  if (move.allFinite()) x += move;
  return x;
}

}  // namespace strictmin::linf_detail
