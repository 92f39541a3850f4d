// Mesh validation: one test per kind of bad input, checking the words of the message.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "expect_input_error.h"
#include "strictmin/io/input_error.h"
#include "strictmin/io/mesh_io.h"
#include "strictmin/mesh/generators.h"
#include "strictmin/mesh/validate.h"

using namespace strictmin;

namespace {

using test_support::expect_input_error;

void expect_invalid(const Mesh& m, const std::vector<std::string>& words) {
  expect_input_error([&] { validate_mesh(m, "m.obj"); }, words);
}

Mesh mesh(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  Mesh m;
  m.V = V;
  m.F = F;
  return m;
}

// Unit square in 3D, two counter-clockwise triangles.
Mesh square() {
  Eigen::MatrixXd V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
  Eigen::MatrixXi F(2, 3);
  F << 0, 1, 2, 0, 2, 3;
  return mesh(V, F);
}

// Two tets sharing face (1, 2, 3), both positive.
Mesh two_tets() {
  Eigen::MatrixXd V(5, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1;
  Eigen::MatrixXi F(2, 4);
  F << 0, 1, 2, 3, 4, 1, 3, 2;
  return mesh(V, F);
}

}  // namespace

TEST(Validate, GoodMeshesPass) {
  std::vector<std::string> warnings;
  EXPECT_NO_THROW(validate_mesh(square(), "square.obj", &warnings));
  EXPECT_NO_THROW(validate_mesh(two_tets(), "tets.mesh", &warnings));
  EXPECT_NO_THROW(validate_mesh(make_grid(4, 4), "grid", &warnings));
  EXPECT_TRUE(warnings.empty());
}

TEST(Validate, EmptyFile) {
  expect_input_error([] { read_mesh_from_string("", "void.obj"); }, {"void.obj: empty file"});
  expect_input_error([] { read_mesh_from_string("# nothing\n", "c.off"); }, {"c.off: empty file"});
  expect_input_error([] { read_mesh_from_string("\n", "e.mesh"); }, {"e.mesh: empty file"});
}

TEST(Validate, NoFaces) {
  expect_input_error([] { read_mesh_from_string("v 0 0 0\nv 1 0 0\n", "pts.obj"); }, {"pts.obj: no faces"});
}

TEST(Validate, NonFiniteCoordinate) {
  expect_input_error([] { read_mesh_from_string("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 nan 1\nf 1 2 3\n", "n.obj"); },
                     {"n.obj: vertex 3 (0-based) has a non-finite coordinate (nan)"});
  Mesh m = square();
  m.V(2, 0) = -INFINITY;
  expect_invalid(m, {"m.obj: vertex 2 (0-based) has a non-finite coordinate (-inf)"});
}

TEST(Validate, IndexOutOfRange) {
  Mesh m = square();
  m.F(1, 2) = 9;
  expect_invalid(m, {"m.obj: face 1 (0-based) has vertex index 9 out of range (the mesh has 4 vertices)"});
  m.F(1, 2) = -1;
  expect_invalid(m, {"face 1 (0-based)", "vertex index -1 out of range"});
}

TEST(Validate, RepeatedIndex) {
  Mesh m = square();
  m.F(1, 2) = 0;
  expect_invalid(m, {"m.obj: face 1 (0-based) uses vertex 0 twice"});
  Mesh t = two_tets();
  t.F(0, 3) = 1;
  expect_invalid(t, {"tet 0 (0-based) uses vertex 1 twice"});
}

TEST(Validate, ZeroAreaFace) {
  Mesh m = square();
  m.V.row(3) << 2, 2, 0;  // face 1 = (0, 2, 3): collinear along the diagonal
  expect_invalid(m, {"m.obj: face 1 (0-based) has zero area", "0, 2, 3"});
  m.V.row(3) = m.V.row(2);  // coincident corners
  expect_invalid(m, {"face 1 (0-based) has zero area"});
}

TEST(Validate, SliverIsNotZeroArea) {
  // A 0.05-degree sliver in a mesh of size ~1000 is a real triangle.
  Eigen::MatrixXd V(4, 2);
  const double angle = 0.05 * M_PI / 180.0;
  V << 0, 0, 1000, 0, 1000 * std::cos(angle), 1000 * std::sin(angle), 0, -1000;
  Eigen::MatrixXi F(2, 3);
  F << 0, 1, 2, 0, 3, 1;
  EXPECT_NO_THROW(validate_mesh(mesh(V, F), "sliver.obj"));
}

// The zero-area test is scale-free: it used to compute d^2 and areas in the file's units,
// so a right triangle with legs of 1e160 overflowed to "zero area" and legs of 1e-170
// underflowed to it. Sizes the solvers cannot take are rejected by name.
TEST(Validate, ScaleDecidesNothingButTheSizeLimit) {
  for (double scale : {1e-150, 1e-100, 1e100, 1e149}) {
    Mesh m = square();
    m.V *= scale;
    EXPECT_NO_THROW(validate_mesh(m, "m.obj")) << scale;
    Mesh t = two_tets();
    t.V *= scale;
    EXPECT_NO_THROW(validate_mesh(t, "m.obj")) << scale;
  }
  Mesh m = square();
  m.V *= 1e160;
  expect_invalid(m, {"m.obj: the mesh is too large", "1e+160", "1e-150 to 1e150"});
  m = square();
  m.V *= 1e-170;
  expect_invalid(m, {"m.obj: the mesh is too small", "1e-170"});
  m = square();
  m.V.col(0) *= 1.7e308;  // the side itself overflows a double
  m.V(0, 0) = -1.7e308;
  expect_invalid(m, {"too large", "above 1.8e308"});
  // The image of a map (no geometry checks) may be collapsed or tiny, but not beyond 1e150:
  // its distortions overflowed (eval: infinite maxima; interp: frames "solved" with none finite).
  for (double scale : {0.0, 1e-200, 1e149}) {
    m = square();
    m.V *= scale;
    EXPECT_NO_THROW(validate_mesh(m, "m.obj", nullptr, false)) << scale;
  }
  m = square();
  m.V *= 1e200;
  try {
    validate_mesh(m, "m.obj", nullptr, false);
    ADD_FAILURE() << "an image of 1e200 was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("m.obj: vertex 1 (0-based) has the coordinate 1e+200, beyond 1e150"),
              std::string::npos)
        << e.what();
  }
  // UVs are held to the same limit, with or without the geometry checks.
  m = square();
  m.UV = m.V.leftCols(2);
  m.FUV = m.F;
  m.UV(2, 1) = -1e160;
  for (bool geometry : {true, false})
    EXPECT_THROW(validate_mesh(m, "m.obj", nullptr, geometry), InputError) << geometry;
}

TEST(Validate, ZeroVolumeTet) {
  Mesh t = two_tets();
  t.V.row(4) << 0.25, 0.25, 0.5;  // in the plane x + y + z = 1 of face (1, 2, 3)
  expect_invalid(t, {"m.obj: tet 1 (0-based) has zero volume", "coplanar"});
}

TEST(Validate, DuplicateFaces) {
  Mesh m = square();
  m.F.conservativeResize(3, 3);
  m.F.row(2) << 2, 0, 1;  // face 0 again, rotated
  expect_invalid(m, {"m.obj: faces 0 and 2 (0-based) have the same vertices"});
}

TEST(Validate, NonManifoldEdge) {
  Eigen::MatrixXd V(5, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1;
  Eigen::MatrixXi F(3, 3);
  F << 0, 1, 2, 1, 0, 3, 0, 1, 4;
  expect_invalid(mesh(V, F), {"m.obj: edge (0, 1) is shared by 3 faces (non-manifold)", "faces 0, 1, 2 (0-based)"});
}

TEST(Validate, NonManifoldTetFace) {
  Mesh t = two_tets();
  t.V.conservativeResize(6, 3);
  t.V.row(5) << 1, 1, 0.8;
  t.F.conservativeResize(3, 4);
  t.F.row(2) << 5, 1, 3, 2;
  expect_invalid(t, {"m.obj: face (1, 2, 3) is shared by 3 tets (non-manifold)", "tets 0, 1, 2"});
}

TEST(Validate, InconsistentOrientationOfASurface) {
  Mesh m = square();
  m.V(3, 2) = 0.5;  // not planar: only the edge rule applies
  m.F.row(1) << 0, 3, 2;
  expect_invalid(m, {"m.obj: faces 0 and 1 (0-based) have inconsistent orientation across edge (0, 2)"});
}

TEST(Validate, InconsistentOrientationInThePlane) {
  // Two separate triangles, one counter-clockwise and one clockwise: no shared edge.
  Eigen::MatrixXd V(6, 2);
  V << 0, 0, 1, 0, 0, 1, 5, 0, 6, 0, 5, 1;
  Eigen::MatrixXi F(2, 3);
  F << 0, 1, 2, 3, 5, 4;
  expect_invalid(mesh(V, F), {"m.obj: faces have inconsistent orientation in the plane",
                              "face 0 (0-based) is counter-clockwise", "face 1 (0-based) clockwise"});
}

TEST(Validate, AllClockwisePlanarMeshIsAccepted) {
  Mesh m = make_grid(3, 3);
  m.F.col(1).swap(m.F.col(2));
  std::vector<std::string> warnings;
  EXPECT_NO_THROW(validate_mesh(m, "cw.obj", &warnings));
  EXPECT_TRUE(warnings.empty());
}

TEST(Validate, TetsWithInconsistentOrientationAcrossAFace) {
  Mesh t = two_tets();
  t.F.row(1) << 4, 1, 2, 3;  // inverted
  expect_invalid(t, {"m.obj: tets 0 and 1 (0-based) have inconsistent orientation across face (1, 2, 3)"});
}

TEST(Validate, TetsWithBothSigns) {
  Eigen::MatrixXd V(8, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 5, 0, 0, 6, 0, 0, 5, 1, 0, 5, 0, 1;
  Eigen::MatrixXi F(2, 4);
  F << 0, 1, 2, 3, 4, 5, 7, 6;
  expect_invalid(mesh(V, F), {"m.obj: tets have inconsistent orientation", "tet 0 (0-based) has positive volume",
                              "tet 1 (0-based) negative volume"});
}

TEST(Validate, AllTetsInverted) {
  Mesh t = two_tets();
  t.F.col(2).swap(t.F.col(3));
  expect_invalid(t, {"m.obj: all tets are inverted", "swap two corners"});
}

TEST(Validate, UnreferencedVerticesWarn) {
  Mesh m = square();
  m.V.conservativeResize(21, 3);
  for (int i = 4; i < 21; ++i) m.V.row(i) << i, i, i;  // 17 unused vertices, first 4
  std::vector<std::string> warnings;
  validate_mesh(m, "x.obj", &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0], "x.obj: 17 vertices are used by no face (first: 4, 0-based); they are ignored");
  EXPECT_EQ(unreferenced_vertices(m).size(), 17u);
  EXPECT_EQ(unreferenced_vertices(m).front(), 4);

  // Through the reader: kept (indices stay valid), one warning.
  const Mesh r = read_mesh_from_string("v 0 0 0\nv 9 9 9\nv 1 0 0\nv 0 1 0\nf 1 3 4\n", "one.obj", &warnings);
  EXPECT_EQ(r.num_vertices(), 4);
  EXPECT_EQ(warnings.back(), "one.obj: 1 vertex is used by no face (vertex 1, 0-based); it is ignored");
}

TEST(Validate, WrongShapes) {
  Mesh m = square();
  m.F.conservativeResize(2, 5);
  expect_invalid(m, {"elements have 5 corners"});
  Mesh t = two_tets();
  t.V.conservativeResize(5, 2);
  expect_invalid(t, {"tetrahedra need 3D vertex coordinates"});
}

TEST(Validate, TextureIndexOutOfRange) {
  Mesh m = square();
  m.UV = Eigen::MatrixXd::Zero(3, 2);
  m.FUV.resize(2, 3);
  m.FUV << 0, 1, 2, 0, 2, 3;
  expect_invalid(m, {"face 1 (0-based) has texture coordinate index 3 out of range"});
}

TEST(Validate, LargeMeshesValidate) {
  // 180k triangles and 162k tets: the checks are O(n log n) (timings belong to bench/).
  EXPECT_NO_THROW(validate_mesh(make_grid(300, 300), "big grid"));
  EXPECT_NO_THROW(validate_mesh(make_tet_box(30, 30, 30), "big box"));
}
