#include "strictmin/mesh/polycube.h"

#include <cmath>
#include <map>
#include <random>
#include <set>
#include <string>

#include "strictmin/io/input_error.h"

namespace strictmin {

Mesh make_polycube(const std::vector<std::array<int, 3>>& cubes, int n, double scale, unsigned seed) {
  if (cubes.empty() || n < 1 || !(scale > 0 && std::isfinite(scale)))
    throw InputError("make_polycube: at least one cube, n >= 1 and a positive scale (got " +
                     std::to_string(cubes.size()) + " cubes, n = " + std::to_string(n) + ")");
  const std::set<std::array<int, 3>> occupied(cubes.begin(), cubes.end());
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  std::map<std::array<int, 3>, int> index;  // lattice point (units of 1/n) -> vertex
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector3i> faces;
  // Boundary squares: the side of a cube whose neighbour across it is empty.
  for (const auto& c : occupied)
    for (int axis = 0; axis < 3; ++axis)
      for (int sign : {-1, 1}) {
        std::array<int, 3> nb = c;
        nb[axis] += sign;
        if (occupied.count(nb)) continue;
        // In-plane axes a, b with a x b = the outward normal (sign along axis).
        int a = (axis + 1) % 3, b = (axis + 2) % 3;
        if (sign < 0) std::swap(a, b);
        std::array<int, 3> origin{c[0] * n, c[1] * n, c[2] * n};
        if (sign > 0) origin[axis] += n;
        std::vector<int> grid((n + 1) * (n + 1));
        for (int i = 0; i <= n; ++i)
          for (int j = 0; j <= n; ++j) {
            std::array<int, 3> key = origin;
            key[a] += i;
            key[b] += j;
            auto [it, added] = index.try_emplace(key, static_cast<int>(points.size()));
            if (added) {
              Eigen::Vector3d p(key[0], key[1], key[2]);
              if (i > 0 && i < n && j > 0 && j < n) {  // inside the square: move in its plane
                p[a] += jitter(random);
                p[b] += jitter(random);
              }
              points.push_back(p * scale / n);
            }
            grid[i * (n + 1) + j] = it->second;
          }
        for (int i = 0; i < n; ++i)
          for (int j = 0; j < n; ++j) {
            const int p00 = grid[i * (n + 1) + j], p10 = grid[(i + 1) * (n + 1) + j];
            const int p01 = grid[i * (n + 1) + j + 1], p11 = grid[(i + 1) * (n + 1) + j + 1];
            if (random() % 2) {
              faces.emplace_back(p00, p10, p11);
              faces.emplace_back(p00, p11, p01);
            } else {
              faces.emplace_back(p00, p10, p01);
              faces.emplace_back(p10, p11, p01);
            }
          }
      }
  Mesh m;
  m.V.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (size_t i = 0; i < points.size(); ++i) m.V.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  m.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (size_t i = 0; i < faces.size(); ++i) m.F.row(static_cast<Eigen::Index>(i)) = faces[i].transpose();
  return m;
}

Mesh make_cube_surface(int n, double side, unsigned seed) { return make_polycube({{0, 0, 0}}, n, side, seed); }

Mesh make_frame_surface(int n, unsigned seed) {
  std::vector<std::array<int, 3>> cubes;
  for (int x = 0; x < 3; ++x)
    for (int y = 0; y < 3; ++y)
      if (x != 1 || y != 1) cubes.push_back({x, y, 0});
  return make_polycube(cubes, n, 1.0, seed);
}

Mesh make_bulged_frame_surface(int n, unsigned seed) {
  Mesh m = make_frame_surface(n, seed);
  for (int v = 0; v < m.num_vertices(); ++v) {
    const double x = m.V(v, 0), y = m.V(v, 1), z = m.V(v, 2);
    m.V(v, 2) = z + (z > 0.5 ? 1 : -1) * 0.25 * std::sin(M_PI * x / 3) * std::sin(M_PI * y / 3);
  }
  return m;
}

Mesh frame_with_a_window(const Mesh& frame) {
  std::vector<char> window(static_cast<std::size_t>(frame.num_elements()), 1);
  for (int f = 0; f < frame.num_elements(); ++f)
    for (int i = 0; i < 3; ++i) {
      const Eigen::RowVector3d p = frame.V.row(frame.F(f, i));
      if (std::abs(p.x()) > 1e-12 || p.y() < 1 - 1e-12 || p.y() > 2 + 1e-12) window[static_cast<std::size_t>(f)] = 0;
    }
  return without_elements(frame, window);
}

}  // namespace strictmin
