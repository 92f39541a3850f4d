#include "strictmin/mesh/generators.h"

#include <cstdio>
#include <limits>
#include <string>
#include <utility>

#include "strictmin/io/input_error.h"

namespace strictmin {
namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw InputError(what);
}

// Vertex indices are ints: a count beyond them overflowed into a negative size (segfault).
void require_int_count(double count, const char* who) {
  if (count <= std::numeric_limits<int>::max()) return;
  char why[160];
  std::snprintf(why, sizeof why, "%s: the mesh would have %.3g vertices or elements, more than an int can index", who,
                count);
  throw InputError(why);
}

}  // namespace

Mesh make_grid(int nx, int ny, double width, double height, double x0, double y0) {
  require(nx >= 1 && ny >= 1, "make_grid: nx and ny must be at least 1 (got " + std::to_string(nx) + ", " +
                                  std::to_string(ny) + ")");
  require(width > 0 && height > 0, "make_grid: width and height must be positive");
  require_int_count(2.0 * nx * ny, "make_grid");
  require_int_count((nx + 1.0) * (ny + 1.0), "make_grid");
  Mesh mesh;
  mesh.V.resize((nx + 1) * (ny + 1), 2);
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i)
      mesh.V.row(j * (nx + 1) + i) << x0 + width * i / nx, y0 + height * j / ny;
  mesh.F.resize(2 * nx * ny, 3);
  int f = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = j * (nx + 1) + i, b = a + 1, c = a + nx + 2, d = a + nx + 1;  // ccw from (i, j)
      if ((i + j) % 2 == 0) {  // diagonal a-c
        mesh.F.row(f++) << a, b, c;
        mesh.F.row(f++) << a, c, d;
      } else {  // diagonal b-d
        mesh.F.row(f++) << a, b, d;
        mesh.F.row(f++) << b, c, d;
      }
    }
  return mesh;
}

Mesh make_tet_box(int nx, int ny, int nz, double width, double height, double depth) {
  require(nx >= 1 && ny >= 1 && nz >= 1, "make_tet_box: nx, ny and nz must be at least 1");
  require(width > 0 && height > 0 && depth > 0, "make_tet_box: width, height and depth must be positive");
  require_int_count(6.0 * nx * ny * nz, "make_tet_box");
  require_int_count((nx + 1.0) * (ny + 1.0) * (nz + 1.0), "make_tet_box");
  auto index = [&](int i, int j, int k) { return (k * (ny + 1) + j) * (nx + 1) + i; };
  Mesh mesh;
  mesh.V.resize((nx + 1) * (ny + 1) * (nz + 1), 3);
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
        mesh.V.row(index(i, j, k)) << width * i / nx, height * j / ny, depth * k / nz;

  // Kuhn subdivision: one tet per ordering (p0, p1, p2) of the axes, along the path
  // 000 -> e_p0 -> e_p0 + e_p1 -> 111. Every cube shares the main diagonal direction, so
  // the face diagonals match across cubes. Odd permutations are reoriented by swapping
  // the middle corners.
  static constexpr int kPermutations[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
  mesh.F.resize(6 * nx * ny * nz, 4);
  int t = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (int p = 0; p < 6; ++p) {
          int step[3] = {0, 0, 0};
          int corner[4];
          corner[0] = index(i, j, k);
          for (int s = 0; s < 3; ++s) {
            ++step[kPermutations[p][s]];
            corner[s + 1] = index(i + step[0], j + step[1], k + step[2]);
          }
          if (p >= 3) std::swap(corner[1], corner[2]);  // odd permutation: negative as built
          mesh.F.row(t++) << corner[0], corner[1], corner[2], corner[3];
        }
  return mesh;
}

}  // namespace strictmin
