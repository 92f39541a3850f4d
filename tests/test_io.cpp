// Mesh file reading (OBJ, OFF, MEDIT), writing (OBJ, OFF, MEDIT, PLY) and atomic writes.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include "expect_input_error.h"
#include "strictmin/io/atomic_file.h"
#include "strictmin/io/input_error.h"
#include "strictmin/io/mesh_io.h"
#include "strictmin/mesh/generators.h"

namespace fs = std::filesystem;
using namespace strictmin;

namespace {

using test_support::expect_input_error;

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void spit(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

// A fresh, empty directory per test, removed afterwards.
class TempDir : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / (std::string("strictmin_io_") + info->name() + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::vector<std::string> listing() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }
  fs::path dir_;
};

const char* kSquareObj =
    "# a unit square\n"
    "v 0 0 0\n"
    "v 1 0 0\n"
    "v 1 1 0\n"
    "v 0 1 0\n"
    "f 1 2 3\n"
    "f 1 3 4\n";

// A mesh with awkward coordinates to check exact (round-trip) number formatting.
Mesh awkward_mesh() {
  Mesh m;
  m.V.resize(4, 3);
  m.V << 0.1, 1.0 / 3.0, -2.5e7,   //
      1e-300, 2.0 / 3.0, 0.0,       //
      1.0, -0.0, 3.141592653589793, //
      123456789.123456789, 1, 1;
  m.F.resize(2, 3);
  m.F << 0, 1, 2, 0, 2, 3;
  return m;
}

// Minimal ASCII PLY reader for the tests: header lines, then vertex and face rows.
struct Ply {
  std::vector<std::string> header;
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  std::vector<double> quality;
};
Ply read_ply(const std::string& path) {
  std::ifstream in(path);
  Ply ply;
  std::string line;
  long nv = 0, nf = 0;
  bool has_quality = false;
  while (std::getline(in, line) && line != "end_header") {
    ply.header.push_back(line);
    std::istringstream ls(line);
    std::string a, b;
    ls >> a >> b;
    if (a == "element" && b == "vertex") ls >> nv;
    if (a == "element" && b == "face") ls >> nf;
    if (line == "property float quality") has_quality = true;
  }
  ply.V.resize(nv, 3);
  for (long i = 0; i < nv; ++i) in >> ply.V(i, 0) >> ply.V(i, 1) >> ply.V(i, 2);
  ply.F.resize(nf, 3);
  for (long f = 0; f < nf; ++f) {
    int n;
    in >> n >> ply.F(f, 0) >> ply.F(f, 1) >> ply.F(f, 2);
    EXPECT_EQ(n, 3);
    if (has_quality) {
      double q;
      in >> q;
      ply.quality.push_back(q);
    }
  }
  return ply;
}

}  // namespace

// ---------------------------------------------------------------------------------------
// OBJ reading

TEST(ReadObj, PlainTriangles) {
  const Mesh m = read_mesh_from_string(kSquareObj, "square.obj");
  EXPECT_EQ(m.num_vertices(), 4);
  EXPECT_EQ(m.dim(), 3);
  ASSERT_EQ(m.num_elements(), 2);
  EXPECT_EQ(m.F.row(1), Eigen::RowVector3i(0, 2, 3));
  EXPECT_FALSE(m.has_uv());
  EXPECT_TRUE(m.is_planar());
}

// A byte-order mark is skipped in text from memory as in a file (it made "v" unknown there).
TEST(ReadObj, ByteOrderMarkInAString) {
  const Mesh m = read_mesh_from_string("\xEF\xBB\xBF" + std::string(kSquareObj), "square.obj");
  EXPECT_EQ(m.num_vertices(), 4);
  EXPECT_EQ(m.num_elements(), 2);
}

TEST(ReadObj, TwoDimensionalVertices) {
  const Mesh m = read_mesh_from_string("v 0 0\nv 1 0\nv 0 1\nf 1 2 3\n", "tri.obj");
  EXPECT_EQ(m.dim(), 2);
  EXPECT_EQ(m.V(1, 0), 1.0);
}

TEST(ReadObj, CornerFormsNegativeIndicesAndIgnoredStatements) {
  const std::string text =
      "mtllib x.mtl\r\n"
      "o thing\r\n"
      "g group\r\n"
      "v 0 0 0\r\n"
      "v 1 0 0\r\n"
      "v 1 1 0  # trailing comment\r\n"
      "v 0 1 0 1.0\r\n"  // w is ignored
      "vn 0 0 1\r\n"
      "vt 0 0\r\n"
      "vt 1 0\r\n"
      "vt 1 1\r\n"
      "vt 0 1\r\n"
      "\r\n"
      "usemtl red\r\n"
      "s off\r\n"
      "f 1/1/1 2/2/1 3/3/1\r\n"
      "f -4/-4 -2/-2 -1/-1\r\n";
  std::vector<std::string> warnings;
  const Mesh m = read_mesh_from_string(text, "corners.obj", &warnings);
  EXPECT_TRUE(warnings.empty());
  ASSERT_EQ(m.num_elements(), 2);
  EXPECT_EQ(m.F.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(m.F.row(1), Eigen::RowVector3i(0, 2, 3));
  ASSERT_TRUE(m.has_uv());
  EXPECT_EQ(m.FUV.row(1), Eigen::RowVector3i(0, 2, 3));
  EXPECT_EQ(m.UV(2, 0), 1.0);
  EXPECT_EQ(m.UV(2, 1), 1.0);
}

// Lines that end with a carriage return alone (the classic Mac convention) are lines: the
// whole file was one line before, read as the first statement only or refused.
TEST(LineEnds, CarriageReturnsAloneEndLinesInEveryReader) {
  const Mesh obj = read_mesh_from_string("# square\rv 0 0 0\rv 1 0 0\rv 1 1 0\rv 0 1 0\rf 1 2 3\rf 1 3 4\r", "cr.obj");
  EXPECT_EQ(obj.num_vertices(), 4);
  EXPECT_EQ(obj.num_elements(), 2);
  const Mesh mixed = read_mesh_from_string("v 0 0 0\r\nv 1 0 0\rv 1 1 0\nv 0 1 0\r\rf 1 2 3\r\nf 1 3 4", "mixed.obj");
  EXPECT_EQ(mixed.num_elements(), 2);
  // Line numbers count each convention's line end once ("\r\n" is one end, "\r\r" two).
  expect_input_error([] { read_mesh_from_string("v 0 0 0\r\nv 1 0 0\r\rv 1 x 0\r", "n.obj"); },
                     {"n.obj: line 4"});
  const Mesh off = read_mesh_from_string("OFF\r# comment\r4 2 0\r0 0 0\r1 0 0\r1 1 0\r0 1 0\r3 0 1 2\r3 0 2 3\r", "cr.off");
  EXPECT_EQ(off.num_elements(), 2);
  // MEDIT: a '#' comment ends at the '\r' (it ran to the end of the file), and lines count.
  const Mesh medit = read_mesh_from_string(
      "MeshVersionFormatted 1\r# comment\rDimension 3\rVertices 3\r0 0 0 0\r1 0 0 0\r0 1 0 0\rTriangles 1\r1 2 3 0\rEnd\r",
      "cr.mesh");
  EXPECT_EQ(medit.num_elements(), 1);
  expect_input_error([] { read_mesh_from_string("Dimension 3\rVertices\r1\r0 x 0 0\r", "n.mesh"); },
                     {"n.mesh", "line 4", "'x'"});
}

TEST(ReadObj, NormalOnlyCorners) {
  const Mesh m = read_mesh_from_string("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n", "n.obj");
  EXPECT_EQ(m.F.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_FALSE(m.has_uv());
}

TEST(ReadObj, UvOnlyWhenEveryFaceHasIt) {
  std::vector<std::string> warnings;
  const Mesh m = read_mesh_from_string(
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nf 1/1 2/2 3/3\nf 1 3 4\n", "partial.obj", &warnings);
  EXPECT_FALSE(m.has_uv());
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("texture coordinates ignored"), std::string::npos);
}

TEST(ReadObj, UnknownStatementWarnsOnce) {
  std::vector<std::string> warnings;
  read_mesh_from_string(std::string(kSquareObj) + "foo 1\nfoo 2\n", "w.obj", &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("w.obj: line 8: unknown statement 'foo'"), std::string::npos) << warnings[0];
}

TEST(ReadObj, QuadIsRejectedWithTheLine) {
  std::string text = "# header\n\n\n\n\n\n\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
  expect_input_error([&] { read_mesh_from_string(text, "quad.obj"); },
                     {"quad.obj: line 12: face with 4 corners; strictmin needs triangles (triangulate the mesh first)"});
}

TEST(ReadObj, FaceWithTwoCornersIsASyntaxError) {
  expect_input_error([] { read_mesh_from_string("v 0 0 0\nv 1 0 0\nf 1 2\n", "two.obj"); },
                     {"two.obj", "line 3", "face with 2 corner"});
}

TEST(ReadObj, MixedVertexDimensions) {
  expect_input_error([] { read_mesh_from_string("v 0 0\nv 1 0 0\nv 0 1\nf 1 2 3\n", "mixed.obj"); },
                     {"mixed.obj", "line 2", "3 coordinates", "line 1 has 2"});
}

TEST(ReadObj, VertexWithOneCoordinate) {
  expect_input_error([] { read_mesh_from_string("v 0\n", "one.obj"); }, {"one.obj", "line 1", "1 coordinate"});
}

TEST(ReadObj, BadNumber) {
  expect_input_error([] { read_mesh_from_string("v 0 0 0\nv 1 zero 0\n", "num.obj"); },
                     {"num.obj", "line 2", "expected a number", "'zero'"});
}

TEST(ReadObj, BadCorner) {
  expect_input_error([] { read_mesh_from_string("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n", "c.obj"); },
                     {"c.obj", "line 4", "bad face corner 'x'"});
  expect_input_error([] { read_mesh_from_string("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "zero.obj"); },
                     {"zero.obj", "line 4", "bad face corner '0'"});
}

TEST(ReadObj, VertexIndexOutOfRange) {
  expect_input_error([] { read_mesh_from_string("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 9\n", "x.obj"); },
                     {"x.obj: line 5: vertex index 9 out of range (the file has 4 vertices)"});
}

TEST(ReadObj, RelativeIndexBeforeFirstVertex) {
  expect_input_error([] { read_mesh_from_string("v 0 0 0\nv 1 0 0\nf -1 -2 -3\nv 0 1 0\n", "rel.obj"); },
                     {"rel.obj", "line 3", "relative vertex index -3"});
}

TEST(ReadObj, TextureIndexOutOfRange) {
  expect_input_error([] { read_mesh_from_string("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n", "t.obj"); },
                     {"t.obj", "line 5", "texture coordinate index 2 out of range"});
}

TEST(ReadObj, RepeatedVertexInAFace) {
  expect_input_error([] { read_mesh_from_string("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2\n", "rep.obj"); },
                     {"rep.obj", "line 4", "uses vertex 2 twice"});
}

// ---------------------------------------------------------------------------------------
// OFF reading

TEST(ReadOff, PlainCommentsAndExtraColumns) {
  const std::string text =
      "COFF\n"
      "# a comment\n"
      "4 2 0\n"
      "0 0 0 255 0 0 255\n"
      "1 0 0 255 0 0 255\n"
      "\n"
      "1 1 0 255 0 0 255  # colour\n"
      "0 1 0 255 0 0 255\n"
      "3 0 1 2 255 255 255\n"
      "3 0 2 3\n";
  const Mesh m = read_mesh_from_string(text, "square.OFF");
  EXPECT_EQ(m.num_vertices(), 4);
  ASSERT_EQ(m.num_elements(), 2);
  EXPECT_EQ(m.F.row(1), Eigen::RowVector3i(0, 2, 3));
  EXPECT_EQ(m.V(2, 1), 1.0);
}

TEST(ReadOff, CountsOnTheHeaderLineAndNoff) {
  const Mesh m = read_mesh_from_string("OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "h.off");
  EXPECT_EQ(m.num_elements(), 1);
  const Mesh n = read_mesh_from_string("NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n", "n.off");
  EXPECT_EQ(n.V(1, 0), 1.0);
  EXPECT_EQ(n.V(1, 2), 0.0);
}

TEST(ReadOff, PolygonIsRejected) {
  expect_input_error(
      [] { read_mesh_from_string("OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n", "quad.off"); },
      {"quad.off: line 7: polygon with 4 corners; strictmin needs triangles (triangulate the mesh first)"});
}

TEST(ReadOff, BadHeader) {
  expect_input_error([] { read_mesh_from_string("PLY\n3 1 0\n", "bad.off"); },
                     {"bad.off", "line 1", "expected the OFF header"});
}

TEST(ReadOff, TruncatedFile) {
  expect_input_error([] { read_mesh_from_string("OFF\n4 1 0\n0 0 0\n1 0 0\n", "short.off"); },
                     {"short.off", "unexpected end of file", "4 vertices, found 2"});
}

TEST(ReadOff, IndexOutOfRange) {
  expect_input_error([] { read_mesh_from_string("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "r.off"); },
                     {"r.off: line 6: vertex index 3 out of range (the file has 3 vertices"});
}

// ---------------------------------------------------------------------------------------
// MEDIT reading

TEST(ReadMedit, TrianglesOnlyIsATriangleMesh) {
  const std::string text =
      "MeshVersionFormatted 1\nDimension 2\nVertices\n3\n0 0 0\n1 0 0\n0 1 0\nTriangles\n1\n1 2 3 7\nEnd\n";
  const Mesh m = read_mesh_from_string(text, "tri.mesh");
  EXPECT_EQ(m.element_type(), ElementType::Triangle);
  EXPECT_EQ(m.dim(), 2);
  EXPECT_EQ(m.F.row(0), Eigen::RowVector3i(0, 1, 2));
}

TEST(ReadMedit, TetsIgnoreTheBoundaryTrianglesAndSkipOtherSections) {
  // Keywords in any case, numbers spread over lines, comments, skippable sections.
  const std::string text =
      "meshversionformatted\n1\n# comment\nDIMENSION 3\n"
      "Vertices 4\n0 0 0 0 1 0 0 0\n0 1 0 0\n0 0 1 0\n"
      "Edges 1 1 2 0\n"
      "Corners 1 1\n"
      "RequiredVertices\n2\n1\n2\n"
      "Triangles\n1\n1 2 3 1\n"
      "Tetrahedra\n1\n1 2 3 4 5\n"
      "end\n";
  const Mesh m = read_mesh_from_string(text, "tet.mesh");
  EXPECT_EQ(m.element_type(), ElementType::Tetrahedron);
  ASSERT_EQ(m.num_elements(), 1);
  EXPECT_EQ(m.F.row(0), Eigen::RowVector4i(0, 1, 2, 3));
  EXPECT_EQ(m.V(1, 0), 1.0);
}

TEST(ReadMedit, MixedElementTypesAreRejected) {
  for (const std::string section : {"Quadrilaterals", "Hexahedra", "Prisms", "Pyramids"}) {
    const std::string text = "MeshVersionFormatted 1\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n" +
                             section + "\n1\n1 2 3 4 0\nEnd\n";
    expect_input_error([&] { read_mesh_from_string(text, "mixed.mesh"); },
                       {"mixed.mesh", "line 9", "mixed element types", "'" + section + "'"});
  }
}

TEST(ReadMedit, EmptyUnsupportedSectionIsHarmless) {
  const Mesh m = read_mesh_from_string(
      "Dimension 3\nVertices 3\n0 0 0 0\n1 0 0 0\n0 1 0 0\nQuadrilaterals 0\nTriangles 1\n1 2 3 0\n", "q0.mesh");
  EXPECT_EQ(m.num_elements(), 1);
}

TEST(ReadMedit, UnknownSection) {
  expect_input_error([] { read_mesh_from_string("Dimension 3\nFoo 1\n", "u.mesh"); },
                     {"u.mesh", "line 2", "unknown section 'Foo'"});
}

TEST(ReadMedit, IndexOutOfRangeNamesTheLine) {
  const std::string text = "Dimension 3\nVertices\n3\n0 0 0 0\n1 0 0 0\n0 1 0 0\nTriangles\n2\n1 2 3 0\n1 2 4 0\n";
  expect_input_error([&] { read_mesh_from_string(text, "r.mesh"); },
                     {"r.mesh: line 10: vertex index 4 out of range (the file has 3 vertices"});
}

TEST(ReadMedit, TruncatedSection) {
  expect_input_error([] { read_mesh_from_string("Dimension 3\nVertices\n3\n0 0 0 0\n1 0 0 0\n", "t.mesh"); },
                     {"t.mesh", "Vertices announces 3 vertices, found 2"});
}

// A second Dimension used to reinterpret the vertices already read, a second Vertices or
// Triangles section to replace the first, without a word.
TEST(ReadMedit, RepeatedSectionsAreRejected) {
  expect_input_error(
      [] { read_mesh_from_string("Dimension 3\nVertices 1\n0 0 0 0\nDimension 2\nVertices 1 0 1 0\n", "d.mesh"); },
      {"d.mesh: line 4: second 'Dimension' (the first is on line 1"});
  const std::string text = "Dimension 2\nVertices 3\n0 0 0\n1 0 0\n0 1 0\nTriangles 1\n1 2 3 0\n"
                           "vertices 3\n0 0 0\n2 0 0\n0 2 0\n";
  expect_input_error([&] { read_mesh_from_string(text, "v.mesh"); },
                     {"v.mesh: line 8: second 'vertices' (the first is on line 2"});
}

TEST(ReadMedit, BadNumber) {
  expect_input_error([] { read_mesh_from_string("Dimension 3\nVertices\n1\n0 x 0 0\n", "n.mesh"); },
                     {"n.mesh", "line 4", "expected a number", "'x'"});
}

// ---------------------------------------------------------------------------------------
// Formats and files

TEST(MeshFormat, UnknownExtension) {
  expect_input_error([] { read_mesh_from_string("solid x", "part.stl"); },
                     {"part.stl", "unknown mesh format '.stl' (use .obj, .off or .mesh)"});
  expect_input_error([] { read_mesh("/nonexistent/part.stl"); }, {"unknown mesh format '.stl'"});
  expect_input_error([] { read_mesh_from_string("", "noext"); }, {"noext", "no file extension"});
  expect_input_error([] { read_mesh_from_string("ply", "x.ply"); }, {"x.ply", "reading .ply is not supported"});
}

TEST(MeshFormat, ExtensionIsCaseInsensitive) {
  EXPECT_EQ(read_mesh_from_string(kSquareObj, "SQUARE.OBJ").num_elements(), 2);
}

TEST(MeshFormat, MissingFile) {
  expect_input_error([] { read_mesh("/nonexistent/dir/x.obj"); }, {"cannot read /nonexistent/dir/x.obj", "No such file"});
}

TEST_F(TempDir, ReadFromDisk) {
  spit(path("square.obj"), kSquareObj);
  EXPECT_EQ(read_mesh(path("square.obj")).num_elements(), 2);
}

// ---------------------------------------------------------------------------------------
// Round trips

TEST_F(TempDir, ObjRoundTripIsExact) {
  const Mesh m = awkward_mesh();
  write_mesh(path("a.obj"), m);
  const Mesh r = read_mesh(path("a.obj"));
  EXPECT_EQ(r.V, m.V);
  EXPECT_EQ(r.F, m.F);
  EXPECT_FALSE(r.has_uv());
  EXPECT_EQ(listing(), std::vector<std::string>{"a.obj"});
}

TEST_F(TempDir, ObjRoundTripWithUv) {
  Mesh m = awkward_mesh();
  m.UV.resize(3, 2);
  m.UV << 0.1, 0.2, 0.7, 1.0 / 7.0, 0.5, 0.9;
  m.FUV.resize(2, 3);
  m.FUV << 0, 1, 2, 0, 2, 1;
  write_mesh(path("uv.obj"), m);
  const std::string text = slurp(path("uv.obj"));
  EXPECT_NE(text.find("\nvt "), std::string::npos);
  EXPECT_NE(text.find("f 1/1 3/3 4/2"), std::string::npos);
  const Mesh r = read_mesh(path("uv.obj"));
  ASSERT_TRUE(r.has_uv());
  EXPECT_EQ(r.UV, m.UV);
  EXPECT_EQ(r.FUV, m.FUV);
  EXPECT_EQ(r.V, m.V);
}

TEST_F(TempDir, Planar2dMeshIsWrittenWithZeroZ) {
  const Mesh grid = make_grid(3, 2);
  for (const std::string ext : {".obj", ".off", ".ply"}) {
    write_mesh(path("g" + ext), grid);
  }
  for (const std::string ext : {".obj", ".off"}) {
    const Mesh r = read_mesh(path("g" + ext));
    ASSERT_EQ(r.dim(), 3);
    EXPECT_TRUE(r.V.col(2).isZero(0.0));
    EXPECT_EQ(to_planar(r).V, grid.V);
    EXPECT_EQ(r.F, grid.F);
  }
}

TEST_F(TempDir, OffRoundTripIsExact) {
  const Mesh m = awkward_mesh();
  write_mesh(path("a.off"), m);
  EXPECT_EQ(slurp(path("a.off")).substr(0, 4), "OFF\n");
  const Mesh r = read_mesh(path("a.off"));
  EXPECT_EQ(r.V, m.V);
  EXPECT_EQ(r.F, m.F);
}

TEST_F(TempDir, MeditTetRoundTrip) {
  Mesh box = make_tet_box(2, 3, 1, 1.5, 1.0 / 3.0, 0.7);
  write_mesh(path("box.mesh"), box);
  const std::string text = slurp(path("box.mesh"));
  EXPECT_NE(text.find("Triangles\n"), std::string::npos);
  EXPECT_NE(text.find("Tetrahedra\n36\n"), std::string::npos);
  const Mesh r = read_mesh(path("box.mesh"));
  EXPECT_EQ(r.element_type(), ElementType::Tetrahedron);
  EXPECT_EQ(r.V, box.V);
  EXPECT_EQ(r.F, box.F);
  // The Triangles section is the outward boundary: read it alone as a triangle mesh.
  const std::string boundary_only = text.substr(0, text.find("Tetrahedra")) + "End\n";
  const Mesh surface = read_mesh_from_string(boundary_only, "boundary.mesh");
  EXPECT_EQ(surface.F, tet_boundary_faces(box.F));
}

TEST_F(TempDir, MeditTriangleRoundTrip) {
  const Mesh grid = make_grid(4, 3, 2.0, 1.0 / 3.0);
  write_mesh(path("grid.mesh"), grid);
  EXPECT_NE(slurp(path("grid.mesh")).find("Dimension 2\n"), std::string::npos);
  const Mesh r = read_mesh(path("grid.mesh"));
  EXPECT_EQ(r.element_type(), ElementType::Triangle);
  EXPECT_EQ(r.V, grid.V);
  EXPECT_EQ(r.F, grid.F);

  const Mesh m = awkward_mesh();
  write_mesh(path("a.mesh"), m);
  const Mesh a = read_mesh(path("a.mesh"));
  EXPECT_EQ(a.V, m.V);
  EXPECT_EQ(a.F, m.F);
}

TEST_F(TempDir, PlyHeaderAndQuality) {
  const Mesh grid = make_grid(2, 1);
  Eigen::VectorXd quality(grid.num_elements());
  quality << 0.1, 0.25, 1.0 / 3.0, 7.5;
  MeshWriteOptions options;
  options.element_quality = &quality;
  write_mesh(path("q.ply"), grid, options);
  const Ply ply = read_ply(path("q.ply"));
  const std::vector<std::string> expected_header = {"ply",
                                                    "format ascii 1.0",
                                                    "comment written by strictmin",
                                                    "element vertex 6",
                                                    "property double x",
                                                    "property double y",
                                                    "property double z",
                                                    "element face 4",
                                                    "property list uchar int vertex_indices",
                                                    "property float quality"};
  EXPECT_EQ(ply.header, expected_header);
  EXPECT_EQ(ply.F, grid.F);
  EXPECT_EQ(ply.V.leftCols(2), grid.V);
  ASSERT_EQ(ply.quality.size(), 4u);
  for (int f = 0; f < 4; ++f) EXPECT_EQ(static_cast<float>(ply.quality[f]), static_cast<float>(quality(f)));

  write_mesh(path("plain.ply"), grid);
  const Ply plain = read_ply(path("plain.ply"));
  EXPECT_EQ(std::count(plain.header.begin(), plain.header.end(), "property float quality"), 0);
  EXPECT_TRUE(plain.quality.empty());
}

TEST_F(TempDir, TetMeshAsSurfaceCarriesTetQuality) {
  const Mesh box = make_tet_box(2, 2, 2);
  Eigen::VectorXd quality(box.num_elements());
  for (int t = 0; t < box.num_elements(); ++t) quality(t) = t;  // quality = tet index
  MeshWriteOptions options;
  options.element_quality = &quality;
  write_mesh(path("box.ply"), box, options);
  const Ply ply = read_ply(path("box.ply"));
  Eigen::VectorXi owner;
  const Eigen::MatrixXi boundary = tet_boundary_faces(box.F, &owner);
  ASSERT_EQ(ply.F, boundary);
  ASSERT_EQ(ply.quality.size(), static_cast<size_t>(boundary.rows()));
  for (Eigen::Index f = 0; f < boundary.rows(); ++f) {
    EXPECT_EQ(ply.quality[f], owner(f));
    for (int k = 0; k < 3; ++k) EXPECT_TRUE((box.F.row(owner(f)).array() == boundary(f, k)).any());
  }
  write_mesh(path("box.obj"), box, options);
  const Mesh surface = read_mesh(path("box.obj"));
  EXPECT_EQ(surface.F, boundary);
  write_mesh(path("box.off"), box);
  EXPECT_EQ(read_mesh(path("box.off")).F, boundary);
}

TEST(TetBoundary, BoxBoundaryIsClosedAndOutward) {
  const Mesh box = make_tet_box(2, 3, 4, 2.0, 3.0, 4.0);
  const Eigen::MatrixXi B = tet_boundary_faces(box.F);
  EXPECT_EQ(B.rows(), 2 * 2 * (2 * 3 + 3 * 4 + 2 * 4));
  // Divergence theorem: the signed volume enclosed by outward faces is the box volume.
  double volume = 0.0;
  for (Eigen::Index f = 0; f < B.rows(); ++f) {
    const Eigen::Vector3d a = box.V.row(B(f, 0)), b = box.V.row(B(f, 1)), c = box.V.row(B(f, 2));
    volume += a.dot(b.cross(c)) / 6.0;
  }
  EXPECT_NEAR(volume, 24.0, 1e-12);
}

TEST(TetBoundary, SingleTet) {
  Eigen::MatrixXi tet(1, 4);
  tet << 0, 1, 2, 3;
  Eigen::VectorXi owner;
  const Eigen::MatrixXi B = tet_boundary_faces(tet, &owner);
  Eigen::MatrixXi expected(4, 3);
  expected << 1, 2, 3, 0, 3, 2, 0, 1, 3, 0, 2, 1;
  EXPECT_EQ(B, expected);
  EXPECT_EQ(owner, Eigen::VectorXi::Zero(4));
}

// ---------------------------------------------------------------------------------------
// Failing writes

TEST_F(TempDir, WriteIntoMissingDirectoryLeavesNothing) {
  const std::string target = path("missing/x.obj");
  expect_input_error([&] { write_mesh(target, make_grid(1, 1)); }, {"cannot write " + target});
  EXPECT_FALSE(fs::exists(target));
  EXPECT_TRUE(listing().empty());
}

TEST_F(TempDir, ThrowingWriterLeavesTargetUnchanged) {
  spit(path("keep.txt"), "original\n");
  expect_input_error(
      [&] {
        write_file_atomically(path("keep.txt"), [](std::ostream& os) {
          os << "half written";
          throw std::runtime_error("disk on fire");
        });
      },
      {"cannot write " + path("keep.txt"), "disk on fire"});
  EXPECT_EQ(slurp(path("keep.txt")), "original\n");
  EXPECT_EQ(listing(), std::vector<std::string>{"keep.txt"});
}

TEST_F(TempDir, AtomicWriteReplacesTheTarget) {
  spit(path("t.txt"), "old");
  write_file_atomically(path("t.txt"), [](std::ostream& os) { os << "new"; });
  EXPECT_EQ(slurp(path("t.txt")), "new");
  EXPECT_EQ(listing(), std::vector<std::string>{"t.txt"});
}

// Writing to /dev/null (a common way to drop an output) must leave the device in place: the
// rename of the temporary replaced it with a regular file (as root), and every later
// `> /dev/null` on the machine filled that file. A FIFO is written in place too; a symbolic
// link keeps being a link, the file it names gets the content.
TEST_F(TempDir, AtomicWriteKeepsDevicesFifosAndLinks) {
  write_file_atomically("/dev/null", [](std::ostream& os) { os << "dropped"; });
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  const std::string fifo = path("pipe");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] { received = slurp(fifo); });
  write_file_atomically(fifo, [](std::ostream& os) { os << "through the pipe"; });
  reader.join();
  EXPECT_EQ(received, "through the pipe");
  EXPECT_TRUE(fs::is_fifo(fifo));
  spit(path("real.txt"), "old");
  fs::create_symlink(path("real.txt"), path("link.txt"));
  write_file_atomically(path("link.txt"), [](std::ostream& os) { os << "new"; });
  EXPECT_TRUE(fs::is_symlink(path("link.txt")));
  EXPECT_EQ(slurp(path("real.txt")), "new");
}

TEST_F(TempDir, WriteOntoADirectoryFailsCleanly) {
  fs::create_directories(path("sub.obj"));
  expect_input_error([&] { write_mesh(path("sub.obj"), make_grid(1, 1)); }, {"cannot write " + path("sub.obj")});
  EXPECT_EQ(listing(), std::vector<std::string>{"sub.obj"});
  EXPECT_TRUE(fs::is_empty(path("sub.obj")));
}

TEST_F(TempDir, WriteRejectsUnknownExtensionAndBadQuality) {
  expect_input_error([&] { write_mesh(path("x.stl"), make_grid(1, 1)); }, {"unknown mesh format '.stl'", ".ply"});
  Eigen::VectorXd quality(3);
  MeshWriteOptions options;
  options.element_quality = &quality;
  expect_input_error([&] { write_mesh(path("x.ply"), make_grid(1, 1), options); },
                     {"cannot write", "element_quality has 3 values, the mesh has 2 elements"});
  EXPECT_TRUE(listing().empty());
}

TEST_F(TempDir, WriteRefusesCoordinatesAndUvsThatAreNotFinite) {
  // "nan" and "inf" are read back by no reader (ours included): refused before any file.
  Mesh m = make_grid(2, 2);
  m.V(4, 1) = std::numeric_limits<double>::quiet_NaN();
  for (const char* name : {"n.obj", "n.off", "n.ply", "n.mesh"})
    expect_input_error([&] { write_mesh(path(name), m); },
                       {"cannot write " + path(name), "vertex 4 (0-based)", "non-finite coordinate (nan)"});
  Mesh tets = make_tet_box(1, 1, 1, 1.0, 1.0, 1.0);
  tets.V(2, 0) = -std::numeric_limits<double>::infinity();
  expect_input_error([&] { write_mesh(path("t.mesh"), tets); }, {"vertex 2 (0-based)", "(-inf)"});
  Mesh uv = make_grid(2, 2);
  uv.UV = uv.V;
  uv.FUV = uv.F;
  uv.UV(5, 0) = std::numeric_limits<double>::infinity();
  expect_input_error([&] { write_mesh(path("u.obj"), uv); },
                     {"cannot write " + path("u.obj"), "texture coordinate 5 (0-based)", "non-finite value (inf)"});
  EXPECT_TRUE(listing().empty());
}

// ---------------------------------------------------------------------------------------
// The shared real meshes

TEST(SharedData, EveryMeshReads) {
  const fs::path root = STRICTMIN_SHARED_DATA;
  if (!fs::is_directory(root)) GTEST_SKIP() << "no shared data at " << root;
  int count = 0;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".obj" && ext != ".off" && ext != ".mesh") continue;
    ++count;
    std::vector<std::string> warnings;
    Mesh m;
    EXPECT_NO_THROW(m = read_mesh(entry.path().string(), &warnings)) << entry.path();
    EXPECT_TRUE(warnings.empty()) << entry.path() << ": " << (warnings.empty() ? "" : warnings[0]);
    EXPECT_GT(m.num_elements(), 0) << entry.path();
    if (entry.path().parent_path().filename() == "planar") {
      EXPECT_TRUE(m.is_planar()) << entry.path();
    }
    if (ext == ".mesh") {
      // The file's Triangles section is exactly our outward boundary.
      EXPECT_EQ(m.element_type(), ElementType::Tetrahedron);
      const std::string text = slurp(entry.path());
      const Mesh surface = read_mesh_from_string(text.substr(0, text.find("Tetrahedra")), "boundary.mesh");
      const Eigen::MatrixXi boundary = tet_boundary_faces(m.F);
      ASSERT_EQ(surface.F.rows(), boundary.rows()) << entry.path();
      // Same oriented triangles, up to rotation of the corners and order.
      auto canonical = [](const Eigen::MatrixXi& F) {
        std::set<std::array<int, 3>> s;
        for (Eigen::Index f = 0; f < F.rows(); ++f) {
          int k = 0;
          for (int j = 1; j < 3; ++j)
            if (F(f, j) < F(f, k)) k = j;
          s.insert({F(f, k), F(f, (k + 1) % 3), F(f, (k + 2) % 3)});
        }
        return s;
      };
      EXPECT_EQ(canonical(surface.F), canonical(boundary)) << entry.path();
    }
  }
  EXPECT_GT(count, 0);
}

TEST(SharedData, CamelheadSliversPass) {
  const fs::path file = fs::path(STRICTMIN_SHARED_DATA) / "disk" / "camelhead.obj";
  if (!fs::exists(file)) GTEST_SKIP() << "no " << file;
  EXPECT_EQ(read_mesh(file.string()).num_elements(), 22704);
}

TEST(ReadLimits, HugeCountsAndIndicesAreErrorsNotCrashes) {
  expect_input_error([] { read_mesh_from_string("OFF\n999999999999 1 0\n0 0 0\n", "big.off"); },
                     {"big.off", "line 2", "more than the file can hold"});
  expect_input_error([] { read_mesh_from_string("Dimension 3\nVertices 999999999999\n", "big.mesh"); },
                     {"big.mesh", "line 2", "more than the file can hold"});
  expect_input_error(
      [] { read_mesh_from_string("Dimension 3\nVertices 3\n0 0 0 0\n1 0 0 0\n0 1 0 0\nTriangles 1\n1 2 4294967299 0\n", "i.mesh"); },
      {"i.mesh", "line 7", "vertex index 4294967299 out of range"});
  expect_input_error([] { read_mesh_from_string("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4294967299\n", "i.obj"); },
                     {"i.obj", "line 4", "vertex index 4294967299 out of range"});
}
