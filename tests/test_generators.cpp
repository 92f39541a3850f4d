// make_grid and make_tet_box: layout, orientation, measure, validity.
#include <gtest/gtest.h>

#include <Eigen/LU>

#include "strictmin/io/input_error.h"
#include "strictmin/io/mesh_io.h"
#include "strictmin/mesh/generators.h"
#include "strictmin/mesh/validate.h"

using namespace strictmin;

namespace {

double signed_area(const Mesh& m, int f) {
  const Eigen::Vector2d a = m.V.row(m.F(f, 0)), b = m.V.row(m.F(f, 1)), c = m.V.row(m.F(f, 2));
  const Eigen::Vector2d u = b - a, v = c - a;
  return 0.5 * (u.x() * v.y() - u.y() * v.x());
}

double signed_volume(const Mesh& m, int t) {
  Eigen::Matrix3d E;
  for (int k = 0; k < 3; ++k) E.row(k) = m.V.row(m.F(t, k + 1)) - m.V.row(m.F(t, 0));
  return E.determinant() / 6.0;
}

}  // namespace

TEST(MakeGrid, LayoutAndPositions) {
  const Mesh g = make_grid(3, 2, 6.0, 4.0, -1.0, 10.0);
  EXPECT_EQ(g.dim(), 2);
  EXPECT_EQ(g.num_vertices(), 4 * 3);
  EXPECT_EQ(g.num_elements(), 2 * 3 * 2);
  // Vertex (i, j) has index j * (nx + 1) + i.
  for (int j = 0; j <= 2; ++j)
    for (int i = 0; i <= 3; ++i) EXPECT_EQ(g.V.row(j * 4 + i), Eigen::RowVector2d(-1.0 + 2.0 * i, 10.0 + 2.0 * j));
}

TEST(MakeGrid, CounterClockwiseAndAreaAddsUp) {
  const Mesh g = make_grid(5, 7, 2.5, 1.5);
  double total = 0.0;
  for (int f = 0; f < g.num_elements(); ++f) {
    EXPECT_GT(signed_area(g, f), 0.0) << "face " << f;
    total += signed_area(g, f);
  }
  EXPECT_NEAR(total, 2.5 * 1.5, 1e-12);
}

TEST(MakeGrid, DiagonalsAlternate) {
  const Mesh g = make_grid(2, 1);
  // Cell (0, 0) is cut along 0-4, cell (1, 0) along 2-4: the first triangles differ in kind.
  auto has = [&](int f, int v) { return (g.F.row(f).array() == v).any(); };
  EXPECT_TRUE(has(0, 0) && has(0, 4) && has(1, 0) && has(1, 4));
  EXPECT_TRUE(has(2, 2) && has(2, 4) && has(3, 2) && has(3, 4));
}

TEST(MakeGrid, ValidatesClean) {
  std::vector<std::string> warnings;
  EXPECT_NO_THROW(validate_mesh(make_grid(8, 5), "grid", &warnings));
  EXPECT_NO_THROW(validate_mesh(make_grid(1, 1), "grid", &warnings));
  EXPECT_TRUE(warnings.empty());
  EXPECT_TRUE(make_grid(2, 2).is_planar());
}

TEST(MakeGrid, BadArguments) {
  EXPECT_THROW(make_grid(0, 3), InputError);
  EXPECT_THROW(make_grid(2, 2, -1.0), InputError);
  EXPECT_THROW(make_grid(100000, 100000), InputError);  // more vertices than an int indexes (segfaulted)
}

TEST(MakeTetBox, LayoutAndPositions) {
  const Mesh b = make_tet_box(2, 3, 4, 2.0, 3.0, 8.0);
  EXPECT_EQ(b.element_type(), ElementType::Tetrahedron);
  EXPECT_EQ(b.num_vertices(), 3 * 4 * 5);
  EXPECT_EQ(b.num_elements(), 6 * 2 * 3 * 4);
  for (int k = 0; k <= 4; ++k)
    for (int j = 0; j <= 3; ++j)
      for (int i = 0; i <= 2; ++i)
        EXPECT_EQ(b.V.row((k * 4 + j) * 3 + i), Eigen::RowVector3d(1.0 * i, 1.0 * j, 2.0 * k));
}

TEST(MakeTetBox, PositiveVolumesAddUp) {
  const Mesh b = make_tet_box(3, 2, 2, 1.5, 2.0, 0.5);
  double total = 0.0;
  for (int t = 0; t < b.num_elements(); ++t) {
    EXPECT_GT(signed_volume(b, t), 0.0) << "tet " << t;
    total += signed_volume(b, t);
  }
  EXPECT_NEAR(total, 1.5 * 2.0 * 0.5, 1e-12);
}

TEST(MakeTetBox, ConformingAndValid) {
  const Mesh b = make_tet_box(3, 3, 2);
  std::vector<std::string> warnings;
  EXPECT_NO_THROW(validate_mesh(b, "box", &warnings));
  EXPECT_TRUE(warnings.empty());
  // Conforming: only the box surface is boundary (2 triangles per square on its sides).
  EXPECT_EQ(tet_boundary_faces(b.F).rows(), 2 * 2 * (3 * 3 + 3 * 2 + 3 * 2));
}

TEST(MakeTetBox, BadArguments) {
  EXPECT_THROW(make_tet_box(1, 0, 1), InputError);
  EXPECT_THROW(make_tet_box(1, 1, 1, 1.0, 0.0), InputError);
  EXPECT_THROW(make_tet_box(2000, 2000, 2000), InputError);  // more tets than an int indexes (segfaulted)
}
