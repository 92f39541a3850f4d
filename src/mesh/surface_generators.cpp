#include "strictmin/mesh/surface_generators.h"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <string>

#include "strictmin/io/input_error.h"
#include "strictmin/mesh/generators.h"

namespace strictmin {
namespace {

// The unit-square grid with each vertex (x, y) sent through `f` into 3D.
template <class Fn>
Mesh bent_grid(int nx, int ny, Fn f) {
  Mesh g = make_grid(nx, ny);
  Mesh m;
  m.F = g.F;
  m.V.resize(g.V.rows(), 3);
  for (Eigen::Index v = 0; v < g.V.rows(); ++v) m.V.row(v) = f(g.V(v, 0), g.V(v, 1)).transpose();
  return m;
}

}  // namespace

Mesh make_cylinder_patch(int nx, int ny, double radius, double angle, double height) {
  return bent_grid(nx, ny, [&](double x, double y) {
    return Eigen::Vector3d(radius * std::cos(angle * x), radius * std::sin(angle * x), height * y);
  });
}

Mesh make_cone_patch(int nx, int ny, double r0, double r1, double angle, double half_angle) {
  return bent_grid(nx, ny, [&](double x, double y) {
    const double rho = r0 + (r1 - r0) * y, t = angle * x;
    return Eigen::Vector3d(rho * std::sin(half_angle) * std::cos(t), rho * std::sin(half_angle) * std::sin(t),
                           rho * std::cos(half_angle));
  });
}

Mesh make_tilted_plane(int nx, int ny) {
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized())).toRotationMatrix();
  return bent_grid(nx, ny, [&](double x, double y) { return Eigen::Vector3d(R * Eigen::Vector3d(x, 0.7 * y, 0)); });
}

Mesh make_spherical_cap(int rings, int sectors, double max_polar) {
  if (rings < 1 || sectors < 3 || !(max_polar > 0 && max_polar <= std::numbers::pi))
    throw InputError("make_spherical_cap: rings >= 1, sectors >= 3 and max_polar in (0, pi] (got " +
                     std::to_string(rings) + ", " + std::to_string(sectors) + ", " + std::to_string(max_polar) + ")");
  Mesh m;
  m.V.resize(1 + rings * sectors, 3);
  m.V.row(0) << 0, 0, 1;
  const auto vid = [&](int ring, int sector) { return 1 + (ring - 1) * sectors + (sector % sectors); };
  for (int r = 1; r <= rings; ++r)
    for (int s = 0; s < sectors; ++s) {
      const double polar = max_polar * r / rings, azimuth = 2 * std::numbers::pi * s / sectors;
      m.V.row(vid(r, s)) << std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth), std::cos(polar);
    }
  m.F.resize(sectors + 2 * (rings - 1) * sectors, 3);
  int f = 0;
  for (int s = 0; s < sectors; ++s) m.F.row(f++) << 0, vid(1, s), vid(1, s + 1);
  for (int r = 1; r < rings; ++r)
    for (int s = 0; s < sectors; ++s) {
      // Alternate the diagonal so the cap has no preferred direction.
      const int a = vid(r, s), b = vid(r + 1, s), c = vid(r + 1, s + 1), d = vid(r, s + 1);
      if ((r + s) % 2 == 0) {
        m.F.row(f++) << a, b, c;
        m.F.row(f++) << a, c, d;
      } else {
        m.F.row(f++) << a, b, d;
        m.F.row(f++) << b, c, d;
      }
    }
  return m;
}

}  // namespace strictmin
