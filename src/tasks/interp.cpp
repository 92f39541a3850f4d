#include "strictmin/tasks/interp.h"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <numeric>
#include <sstream>

#include "strictmin/io/input_error.h"
#include "strictmin/mesh/validate.h"
#include "strictmin/problem/parts.h"
#include "strictmin/measures/measures.h"
#include "strictmin/measures/polar.h"
#include "strictmin/solvers/l2.h"
#include "strictmin/tasks/rotation_unwrap.h"
#include "io/text_parse.h"
#include "mesh/image_sizes.h"

namespace strictmin {
namespace {

std::string element_text(const Eigen::MatrixXi& F, int e) {
  std::ostringstream os;
  os << "(";
  for (int j = 0; j < F.cols(); ++j) os << (j ? " " : "") << F(e, j);
  os << ")";
  return os.str();
}

void check_same_connectivity(const Mesh& s, const Mesh& t, const std::string& sn, const std::string& tn) {
  const auto kind = [](const Mesh& m) { return m.F.cols() == 4 ? std::string("tets") : std::string("triangles"); };
  if (s.F.cols() != t.F.cols())
    throw InputError(sn + " has " + kind(s) + " but " + tn + " has " + kind(t) + "; interpolation needs the same elements");
  if (s.num_vertices() != t.num_vertices())
    throw InputError(sn + " has " + std::to_string(s.num_vertices()) + " vertices but " + tn + " has " +
                     std::to_string(t.num_vertices()) + "; interpolation needs the same connectivity");
  if (s.num_elements() != t.num_elements())
    throw InputError(sn + " has " + std::to_string(s.num_elements()) + " elements but " + tn + " has " +
                     std::to_string(t.num_elements()) + "; interpolation needs the same connectivity");
  for (int e = 0; e < s.num_elements(); ++e)
    if (s.F.row(e) != t.F.row(e))
      throw InputError("element " + std::to_string(e) + " (0-based) differs: " + element_text(s.F, e) + " in " + sn +
                       ", " + element_text(t.F, e) + " in " + tn + "; interpolation needs the same connectivity");
}

Eigen::MatrixXd as_3d(const Eigen::MatrixXd& V) {
  if (V.cols() == 3) return V;
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(V.rows(), 3);
  out.leftCols(V.cols()) = V;
  return out;
}

}  // namespace

std::string interp_kind_name(InterpKind k) {
  switch (k) {
    case InterpKind::Planar: return "planar";
    case InterpKind::Surface: return "surface";
    case InterpKind::Tets: return "tets";
  }
  return "?";
}

std::string rotation_blend_name(RotationBlend b) {
  switch (b) {
    case RotationBlend::Auto: return "auto";
    case RotationBlend::Logarithms: return "logarithms";
    case RotationBlend::Tree: return "tree";
  }
  return "?";
}

RotationBlend parse_rotation_blend(const std::string& word, const std::string& flag) {
  for (RotationBlend b : {RotationBlend::Auto, RotationBlend::Logarithms, RotationBlend::Tree})
    if (word == rotation_blend_name(b)) return b;
  throw InputError(flag + " takes auto, logarithms or tree, not '" + word + "'");
}

Interpolator::Interpolator(const Mesh& source, const Mesh& target, const std::string& sn, const std::string& tn,
                           RotationBlend blend)
    : source_(source) {
  check_mesh_structure(source, sn);
  check_mesh_structure(target, tn);
  check_image_sizes(target, tn);  // a target of 1e200 gave frames with no finite distortion, "solved"
  check_same_connectivity(source, target, sn, tn);
  if (source.num_elements() == 0) throw InputError(sn + " has no elements");
  if (source.F.cols() == 4) kind_ = InterpKind::Tets;
  else kind_ = source.is_planar() && target.is_planar() ? InterpKind::Planar : InterpKind::Surface;
  if (kind_ == InterpKind::Planar && blend != RotationBlend::Auto)
    throw InputError("rotation blend '" + rotation_blend_name(blend) + "' is for 3D poses (surfaces and tets); " + sn +
                     " and " + tn + " are planar, whose rotations are angles (unwrapped without jumps)");

  problem_ = make_problem(source);
  const int E = problem_.num_elements();
  if (kind_ == InterpKind::Planar) {
    source_X_ = to_planar(source).V;
    target_X_ = to_planar(target).V;
    source_z_ = source.V.cols() == 3 ? source.V(0, 2) : 0.0;
    target_z_ = target.V.cols() == 3 ? target.V(0, 2) : 0.0;
  } else {
    source_X_ = as_3d(source.V);
    target_X_ = as_3d(target.V);
  }
  if (kind_ == InterpKind::Surface) {
    // A surface triangle in its own 2D frame maps into 3D: J is 3 by 2.
    problem_.image_dim = 3;
    problem_.positions = source_X_;
    problem_.targets.resize(static_cast<Eigen::Index>(E) * 3, 2);
  }
  const int n = problem_.image_dim, d = problem_.domain_dim;
  if (kind_ == InterpKind::Surface) frames_.resize(static_cast<Eigen::Index>(E) * 3, 2);
  shapes_.resize(static_cast<Eigen::Index>(E) * d, d);
  Eigen::MatrixXd logs(E, d == 2 && n == 2 ? 1 : 3);
  for (int e = 0; e < E; ++e) {
    const Eigen::MatrixXd Jt = problem_.jacobian(e, target_X_);
    if (kind_ == InterpKind::Surface) {
      // Jt = U Y with U (3 by 2) orthonormal columns; the 3D rotation R takes the source
      // frame Fs (the source's own differential) and its normal to U and U's normal.
      const Eigen::MatrixXd Fs = problem_.jacobian(e, source_X_);
      const Eigen::MatrixXd U = closest_rotation(Jt);
      const Eigen::MatrixXd Y = U.transpose() * Jt;
      shapes_.middleRows(e * 2, 2) = 0.5 * (Y + Y.transpose());
      frames_.middleRows(e * 3, 3) = Fs;
      const Eigen::Vector3d u0 = U.col(0), u1 = U.col(1), f0 = Fs.col(0), f1 = Fs.col(1);
      Eigen::Matrix3d A, B;
      A << u0, u1, u0.cross(u1);
      B << f0, f1, f0.cross(f1);
      logs.row(e) = rotation_log(A * B.transpose()).transpose();
    } else {
      const Polar p = polar_decomposition(Jt);
      shapes_.middleRows(e * d, d) = p.Y;
      if (d == 2) logs(e, 0) = rotation_angle(p.R);
      else logs.row(e) = rotation_log(p.R).transpose();
    }
  }
  const auto neighbours = element_neighbours(problem_.elements);
  logs_ = logs.cols() == 1 ? Eigen::MatrixXd(unwrap_angles(neighbours, logs.col(0)))
                            : unwrap_rotation_vectors(neighbours, logs, &rotation_jumps_);
  if (logs.cols() == 3) {
    // Where the logarithms jump the rotations are blended relative to their neighbours'.
    std::vector<Eigen::Matrix3d> rotations(E);
    for (int e = 0; e < E; ++e) rotations[e] = rotation_exp(logs.row(e).transpose());
    const bool tree = blend == RotationBlend::Tree || (blend == RotationBlend::Auto && rotation_jumps_ > 0);
    if (tree) tree_blend_ = TreeRotationBlend(neighbours, rotations);
    rotation_disagreements_ = count_disagreeing_neighbours(neighbours, rotations, blended_rotations(0.5), 0.5, std::numbers::pi / 2);
  }

  // Connected parts (each gets its own pin).
  ElementParts parts = element_parts(problem_);
  component_ = std::move(parts.part);
  num_components_ = parts.count;
}

std::vector<Eigen::Matrix3d> Interpolator::blended_rotations(double t) const {
  if (!tree_blend_.empty()) return tree_blend_.at(t);
  std::vector<Eigen::Matrix3d> out(logs_.rows());
  for (Eigen::Index e = 0; e < logs_.rows(); ++e) out[e] = rotation_exp(t * logs_.row(e).transpose());
  return out;
}

std::string Interpolator::rotation_blend() const {
  if (kind_ == InterpKind::Planar) return "angles";
  return tree_blend_.empty() ? "logarithms" : "tree";
}

std::string Interpolator::warning() const {
  if (rotation_disagreements_ == 0) return "";
  return std::to_string(rotation_disagreements_) + " pairs of neighbouring elements have blended rotations more " +
         "than 90 degrees apart at t = 0.5 (the poses turn them by about 180 degrees relative to each other, or " +
         "their rotations wind around a loop of elements): the frames may distort or fold there; check each " +
         "frame's flipped count and distortion (docs/interp.md, \"Limits\")";
}

Eigen::MatrixXd Interpolator::targets_at(double t, Eigen::MatrixXd* shapes) const {
  const int n = problem_.image_dim, d = problem_.domain_dim, E = problem_.num_elements();
  Eigen::MatrixXd targets(static_cast<Eigen::Index>(E) * n, d);
  shapes->resize(static_cast<Eigen::Index>(E) * n, d);
  const std::vector<Eigen::Matrix3d> rotations = kind_ == InterpKind::Planar ? std::vector<Eigen::Matrix3d>() : blended_rotations(t);
  for (int e = 0; e < E; ++e) {
    const Eigen::MatrixXd Yt = (1 - t) * Eigen::MatrixXd::Identity(d, d) + t * shapes_.middleRows(e * d, d);
    if (kind_ == InterpKind::Planar) {
      shapes->middleRows(e * 2, 2) = Yt;
      targets.middleRows(e * 2, 2) = rotation_2d(t * logs_(e, 0)) * Yt;
    } else {
      const Eigen::Matrix3d& R = rotations[e];
      // Surfaces: the shape handed to the local step is Fs Y(t) (3 by 2), so its target
      // Q Fs Y(t) ranges over the same family U Y(t) (U with orthonormal columns).
      const Eigen::MatrixXd S = kind_ == InterpKind::Surface ? Eigen::MatrixXd(frames_.middleRows(e * 3, 3) * Yt) : Yt;
      shapes->middleRows(e * n, n) = S;
      targets.middleRows(e * n, n) = R * S;
    }
  }
  return targets;
}

InterpFrame Interpolator::at(double t, const InterpOptions& options) const {
  if (!(t >= 0.0 && t <= 1.0)) throw InputError("interpolation time t = " + io_detail::exact_text(t) + " is outside [0, 1]");
  const Method method = options.solver.method;
  if (method == Method::Exact)
    throw InputError("interp: --method exact (the exact strict minimizer) is for field deviation only; use --method "
                     "direct or relax");
  const int V = problem_.num_vertices;
  if (options.pin_vertex < -1)  // -1 is the centroid; other negative values were taken for it silently
    throw InputError("interp: pinned vertex " + std::to_string(options.pin_vertex) +
                     " is not a vertex (0-based; -1 pins the centroid)");
  if (options.pin_vertex >= V || (options.pin_vertex >= 0 && component_[options.pin_vertex] < 0))
    throw InputError("interp: pinned vertex " + std::to_string(options.pin_vertex) + " is not a vertex of an element (the mesh has " +
                     std::to_string(V) + " vertices, 0-based)");

  Problem p = problem_;
  LocalGlobalOptions lg = options.local_global;
  lg.local = LocalStep::Rotation;
  p.targets = targets_at(t, &lg.shapes);
  const Eigen::MatrixXd X_t = (1 - t) * source_X_ + t * target_X_;  // linear interpolation: pins only
  // One pinned vertex per connected part: the asked-for one in its part, else the part's first.
  std::vector<int> anchor(num_components_, -1);
  if (options.pin_vertex >= 0) anchor[component_[options.pin_vertex]] = options.pin_vertex;
  for (int v = 0; v < V; ++v)
    if (component_[v] >= 0 && anchor[component_[v]] < 0) anchor[component_[v]] = v;
  p.positions = X_t;
  for (int v = 0; v < V; ++v) p.fixed[v] = component_[v] < 0 ? 1 : 0;
  for (int a : anchor) p.fixed[a] = 1;

  InterpFrame out;
  out.t = t + 0.0;  // -0 is 0
  const Result start = solve_l2(p);  // FD with the interpolated targets
  if (!start.ok() || lg.max_iterations <= 0) {
    out.result = lg.max_iterations <= 0 && start.ok() ? run_method(p, options.solver) : start;
  } else {
    out.result = local_global(p, start.positions, options.solver, lg);
  }
  // The distortion is translation invariant, so pinning the centroid is pinning any vertex
  // and then translating each part to its interpolated centroid.
  Eigen::MatrixXd& X = out.result.positions;
  for (int c = 0; c < num_components_; ++c) {
    if (options.pin_vertex >= 0 && component_[options.pin_vertex] == c) continue;
    Eigen::RowVectorXd shift = Eigen::RowVectorXd::Zero(X.cols());
    int count = 0;
    for (int v = 0; v < V; ++v)
      if (component_[v] == c) {
        shift += X_t.row(v) - X.row(v);
        ++count;
      }
    shift /= count;
    for (int v = 0; v < V; ++v)
      if (component_[v] == c) X.row(v) += shift;
  }
  out.result.distortion = local_distortion(p, X, lg);

  out.mesh = source_;
  if (kind_ == InterpKind::Planar && source_.V.cols() == 3) {
    out.mesh.V.leftCols(2) = X;
    out.mesh.V.col(2).setConstant((1 - t) * source_z_ + t * target_z_);  // between the two planes
  } else {
    out.mesh.V = X;
  }
  out.weights = p.weights;
  out.stats = distortion_stats(out.result.distortion, p.weights);
  if (kind_ == InterpKind::Surface)
    out.stats.flipped = -1;  // not defined: a 3x2 Jacobian has no orientation (DistortionStats)
  else
    for (int e = 0; e < p.num_elements(); ++e) out.stats.flipped += is_flipped(p.jacobian(e, X)) ? 1 : 0;
  return out;
}

}  // namespace strictmin
