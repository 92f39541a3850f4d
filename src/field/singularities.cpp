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
  return fr.angle(f, (mesh.V.row(b) - mesh.V.row(a)).transpose());
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

std::vector<double> field_edge_turns(const Mesh& mesh, const SurfaceGraph& g, const FaceFrames& fr,
                                     const Eigen::VectorXcd& u) {
  std::vector<double> turns(g.num_edges());
  tbb::parallel_for(tbb::blocked_range<int>(0, g.num_edges(), 4096), [&](const tbb::blocked_range<int>& range) {
    for (int e = range.begin(); e < range.end(); ++e) {
      const int f = g.edge_faces(e, 0), h = g.edge_faces(e, 1);
      if (h < 0) {  // from the side (as its face runs it) to the field
        turns[e] = quarter_remainder(std::arg(u(f)) / 4.0 - side_angle(mesh, fr, f, g.edges(e, 0), g.edges(e, 1)));
        continue;
      }
      // arg(u_h / (e^{4it} u_f)) = arg(u_h conj(e^{4it} u_f)), written out (std::complex's
      // division and product are library calls).
      const double t = fr.transport(e);
      const double c = std::cos(4.0 * t), sn = std::sin(4.0 * t);
      const double pr = c * u(f).real() - sn * u(f).imag(), pi = c * u(f).imag() + sn * u(f).real();
      const double re = u(h).real() * pr + u(h).imag() * pi, im = u(h).imag() * pr - u(h).real() * pi;
      double delta = std::atan2(im, re) / 4.0;  // (-pi/4, pi/4]
      if (delta <= -std::numbers::pi / 4) delta += std::numbers::pi / 2;
      turns[e] = delta;
    }
  });
  return turns;
}

std::vector<int> vertex_indices(const Mesh& mesh, const SurfaceGraph& g, const FaceFrames& fr,
                                const Eigen::VectorXcd& u, std::vector<double>* raw) {
  const Eigen::VectorXd K = angle_defects(mesh, g);
  const std::vector<double> turns = field_edge_turns(mesh, g, fr, u);
  std::vector<int> quarters(g.num_vertices, 0);
  if (raw) raw->assign(g.num_vertices, 0.0);
  tbb::parallel_for(tbb::blocked_range<int>(0, g.num_vertices, 4096), [&](const tbb::blocked_range<int>& range) {
    for (int v = range.begin(); v < range.end(); ++v) {
      double turn = 0;
      const int begin = g.fan_start[v], end = g.fan_start[v + 1];
      // An open fan crosses one edge fewer than it has faces: its last face's is the boundary.
      for (int k = begin; k < end - (g.boundary_vertex[v] ? 1 : 0); ++k) {
        const int e = g.fan_edge(k);  // crossed to reach the next face
        turn += g.edge_faces(e, 0) == g.fan_faces[k] ? turns[e] : -turns[e];
      }
      if (g.boundary_vertex[v]) {  // from the side leaving v to the field, and from the field to the side reaching v
        const int leaving = g.face_edges(g.fan_faces[begin], g.fan_corners[begin]), reaching = g.fan_edge(end - 1);
        turn += turns[leaving] - turns[reaching];
      }
      const double q = 4.0 * (K(v) + turn) / (2 * std::numbers::pi);
      quarters[v] = static_cast<int>(std::lround(q));
      if (raw) (*raw)[v] = q;
    }
  });
  return quarters;
}

int spread_full_turn_singularities(const Mesh& mesh, const SurfaceGraph& g, const FaceFrames& fr, Eigen::VectorXcd& u,
                                   std::vector<int>& quarters) {
  int changed = 0;
  for (int round = 0; round < 8; ++round) {
    bool any = false;
    for (int v = 0; v < g.num_vertices; ++v) {
      if (g.boundary_vertex[v] || quarters[v] < 4) continue;
      any = true;
      ++changed;
      const int begin = g.fan_start[v], end = g.fan_start[v + 1];
      double a = std::arg(u(g.fan_faces[begin])) / 4.0;  // the direction, moved across the fan
      for (int k = begin + 1; k < end; ++k) {
        const int e = g.fan_edge(k - 1), f = g.fan_faces[k - 1], h = g.fan_faces[k];
        a += fr.transport_from(g, e, f);
        bool on_boundary = false;
        for (int i = 0; i < 3; ++i) on_boundary = on_boundary || g.is_boundary_edge(g.face_edges(h, i));
        if (!on_boundary) u(h) = std::polar(1.0, 4.0 * a);
      }
    }
    if (!any) break;
    quarters = vertex_indices(mesh, g, fr, u);
  }
  return changed;
}

std::vector<Singularity> singularities(const std::vector<int>& quarters) {
  std::vector<Singularity> out;
  for (size_t v = 0; v < quarters.size(); ++v)
    if (quarters[v] != 0) out.push_back({static_cast<int>(v), quarters[v]});
  return out;
}

}  // namespace strictmin
