#include "strictmin/field/singularities.h"

#include <cmath>
#include <complex>
#include <numbers>

#include <Eigen/Geometry>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace strictmin {
namespace {

// x modulo pi/2, in (-pi/4, pi/4].
double quarter_remainder(double x) {
  const double q = std::numbers::pi / 2;
  double r = x - q * std::round(x / q);
  if (r <= -q / 2) r += q;
  if (r > q / 2) r -= q;
  return r;
}

// The angle of the direction from vertex a to vertex b in face f's frame.
double side_angle(const Mesh& mesh, const FaceFrames& fr, int f, int a, int b) {
  const Eigen::Vector3d d = (mesh.V.row(b) - mesh.V.row(a)).transpose();
  return std::atan2(d.dot(fr.y.row(f).transpose()), d.dot(fr.x.row(f).transpose()));
}

// At a boundary vertex v (open fan f_0 .. f_{m-1}): the turn from the boundary side leaving v
// to the field in f_0, plus the turn from the field in f_{m-1} to the boundary side reaching v
// (seen from v), each modulo pi/2 in (-pi/4, pi/4]. Zero for a field along the boundary; for
// any other (a given field, a face with two boundary sides) it makes the index a multiple of
// 1/4 again, and the two turns of each boundary side cancel between its ends.
double boundary_turns(const Mesh& mesh, const SurfaceGraph& g, const FaceFrames& fr, const Eigen::VectorXcd& u, int v) {
  const int first = g.fan_start[v], last = g.fan_start[v + 1] - 1;
  const int f0 = g.fan_faces[first], fl = g.fan_faces[last];
  const int next = mesh.F(f0, (g.fan_corners[first] + 1) % 3), previous = mesh.F(fl, (g.fan_corners[last] + 2) % 3);
  return quarter_remainder(std::arg(u(f0)) / 4.0 - side_angle(mesh, fr, f0, v, next)) +
         quarter_remainder(side_angle(mesh, fr, fl, v, previous) - std::arg(u(fl)) / 4.0);
}

}  // namespace

Eigen::VectorXd angle_defects(const Mesh& mesh, const SurfaceGraph& g) {
  Eigen::VectorXd K(g.num_vertices);
  for (int v = 0; v < g.num_vertices; ++v) K(v) = (g.boundary_vertex[v] ? 1 : 2) * std::numbers::pi;
  for (int f = 0; f < g.num_faces; ++f)
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d p = mesh.V.row(mesh.F(f, i)).transpose();
      const Eigen::Vector3d a = mesh.V.row(mesh.F(f, (i + 1) % 3)).transpose() - p;
      const Eigen::Vector3d b = mesh.V.row(mesh.F(f, (i + 2) % 3)).transpose() - p;
      K(mesh.F(f, i)) -= std::atan2(a.cross(b).norm(), a.dot(b));
    }
  return K;
}

std::vector<int> vertex_indices(const Mesh& mesh, const SurfaceGraph& g, const FaceFrames& fr,
                                const Eigen::VectorXcd& u, std::vector<double>* raw) {
  const Eigen::VectorXd K = angle_defects(mesh, g);
  std::vector<int> quarters(g.num_vertices, 0);
  if (raw) raw->assign(g.num_vertices, 0.0);
  tbb::parallel_for(tbb::blocked_range<int>(0, g.num_vertices, 4096), [&](const tbb::blocked_range<int>& range) {
    for (int v = range.begin(); v < range.end(); ++v) {
      double turn = 0;
      const int begin = g.fan_start[v], end = g.fan_start[v + 1];
      // An open fan crosses one edge fewer than it has faces: its last face's is the boundary.
      for (int k = begin; k < end - (g.boundary_vertex[v] ? 1 : 0); ++k) {
        const int f = g.fan_faces[k];
        const int e = g.fan_edge(k);  // crossed to reach the next face
        const int next = g.fan_faces[k + 1 < end ? k + 1 : begin];
        const double t = g.edge_faces(e, 0) == f ? fr.transport(e) : -fr.transport(e);
        // arg(u_next / (e^{4it} u_f)) = arg(u_next conj(e^{4it} u_f)), written out (std::complex's
        // division and product are library calls).
        const double c = std::cos(4.0 * t), s = std::sin(4.0 * t);
        const double pr = c * u(f).real() - s * u(f).imag(), pi = c * u(f).imag() + s * u(f).real();
        const double re = u(next).real() * pr + u(next).imag() * pi, im = u(next).imag() * pr - u(next).real() * pi;
        double delta = std::atan2(im, re) / 4.0;  // (-pi/4, pi/4]
        if (delta <= -std::numbers::pi / 4) delta += std::numbers::pi / 2;
        turn += delta;
      }
      if (g.boundary_vertex[v]) turn += boundary_turns(mesh, g, fr, u, v);
      const double q = 4.0 * (K(v) + turn) / (2 * std::numbers::pi);
      quarters[v] = static_cast<int>(std::lround(q));
      if (raw) (*raw)[v] = q;
    }
  });
  return quarters;
}

std::vector<Singularity> singularities(const std::vector<int>& quarters) {
  std::vector<Singularity> out;
  for (size_t v = 0; v < quarters.size(); ++v)
    if (quarters[v] != 0) out.push_back({static_cast<int>(v), quarters[v]});
  return out;
}

}  // namespace strictmin
