#pragma once
// Internal: the isometric frame of a triangle in 3D (local_frame_coordinates, problem.h).
// Not a public header.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace strictmin {

// An exact scale (a power of two) that brings edges far from unit length (beyond 2^+-150)
// near 1; 1 otherwise. The frame's second axis is cubic in the edges' length, which
// overflows above about 1e51 and underflows below 1e-51; ordinary edges are left as given,
// so their frames are what they always were, bit for bit.
inline double frame_edge_scale(const Eigen::Vector3d& e1, const Eigen::Vector3d& e2) {
  const double size = std::max(e1.cwiseAbs().maxCoeff(), e2.cwiseAbs().maxCoeff());
  if (!(size > 0) || !std::isfinite(size) || (size >= 0x1p-150 && size <= 0x1p150)) return 1;
  return std::exp2(-std::round(std::log2(size)));
}

// The frame axes of a triangle with edges e1 and e2 from its first corner, already scaled
// by frame_edge_scale: x along e1, y in the plane, orthogonal to x, on the side of e2 (as
// columns).
inline Eigen::Matrix<double, 3, 2> frame_axes_of_edges(const Eigen::Vector3d& e1, const Eigen::Vector3d& e2) {
  Eigen::Matrix<double, 3, 2> axes;
  axes.col(0) = e1.normalized();
  axes.col(1) = (e1.cross(e2)).cross(e1).normalized();
  return axes;
}

// The triangle's frame axes (e1 = p1 - p0, e2 = p2 - p0).
inline Eigen::Matrix<double, 3, 2> frame_axes(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                              const Eigen::Vector3d& p2) {
  const double s = frame_edge_scale(p1 - p0, p2 - p0);
  return frame_axes_of_edges((p1 - p0) * s, (p2 - p0) * s);
}

}  // namespace strictmin
