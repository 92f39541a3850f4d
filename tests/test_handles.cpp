// Handle files (JSON and text): good input, real files, one test per kind of bad input.
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>

#include "expect_input_error.h"
#include "strictmin/io/handles_io.h"
#include "strictmin/io/input_error.h"

using namespace strictmin;

namespace {

using test_support::expect_input_error;

void expect_bad(const std::string& text, const std::string& name, int dim, const std::vector<std::string>& words) {
  expect_input_error([&] { parse_handles(text, name, 10, dim); }, words);
}

}  // namespace

TEST(Handles, TextWithCommentsAndBlankLines) {
  const std::string text =
      "# vertex x y\n"
      "\n"
      "3 0.5 -1   # trailing comment\r\n"
      "   7 +1e-3 2\n"
      "3 0.5 -1\n";  // same target again: merged
  const std::vector<Handle> h = parse_handles(text, "h.txt", 10, 2);
  ASSERT_EQ(h.size(), 2u);
  EXPECT_EQ(h[0].vertex, 3);
  EXPECT_EQ(h[0].position, Eigen::Vector2d(0.5, -1));
  EXPECT_EQ(h[1].vertex, 7);
  EXPECT_EQ(h[1].position, Eigen::Vector2d(1e-3, 2));
}

TEST(Handles, CarriageReturnsAloneEndLines) {
  const std::vector<Handle> h = parse_handles("# vertex x y\r3 0.5 -1\r7 1 2\r", "h.txt", 10, 2);
  ASSERT_EQ(h.size(), 2u);
  EXPECT_EQ(h[1].vertex, 7);
  expect_bad("3 0.5 -1\r\r7 x 2\r", "h.txt", 2, {"h.txt", "line 3"});
}

// A byte-order mark is skipped in text from memory as by read_handles (the first line was
// "expected a vertex index").
TEST(Handles, ByteOrderMarkInAString) {
  const std::vector<Handle> h = parse_handles("\xEF\xBB\xBF" "3 0.5 -1\n", "h.txt", 10, 2);
  ASSERT_EQ(h.size(), 1u);
  EXPECT_EQ(h[0].vertex, 3);
}

// The map's dimension is 2 or 3: 0 gave handles without coordinates, 4 four-coordinate ones.
TEST(Handles, DimensionOtherThanTwoOrThreeIsRefused) {
  EXPECT_THROW(parse_handles("0\n", "h.txt", 5, 0), InputError);
  EXPECT_THROW(parse_handles("0 1 1 1 1\n", "h.txt", 5, 4), InputError);
}

TEST(Handles, Json) {
  const std::string text = R"(  {"handles": [{"vertex": 2, "position": [0.25, 1, -3]},
                                  {"vertex": 9, "position": [0, 0, 0]}]})";
  const std::vector<Handle> h = parse_handles(text, "h.json", 10, 3);
  ASSERT_EQ(h.size(), 2u);
  EXPECT_EQ(h[0].vertex, 2);
  EXPECT_EQ(h[0].position, Eigen::Vector3d(0.25, 1, -3));
  EXPECT_EQ(h[1].vertex, 9);
}

TEST(Handles, BadJson) {
  expect_bad(R"({"handles": [{"vertex": 1,}]})", "bad.json", 2, {"bad.json", "invalid JSON", "parse error"});
}

// Found by fuzzing (fuzz/fuzz_handles.cpp): a number too large for a double is not a
// parse_error but an out_of_range exception, which escaped without the file name.
TEST(Handles, JsonNumberOverflow) {
  expect_bad(R"({"handles": [{"vertex": 1, "position": [1e400, 0]}]})", "o.json", 2,
             {"o.json", "invalid JSON", "1e400"});
}

// Found by fuzzing: the JSON parser's message quotes the bytes it last read, control
// characters included; they are escaped.
TEST(Handles, JsonMessageHasNoControlCharacters) {
  expect_bad(std::string("{\"n\x7f(\x01") + "\x82", "c.json", 2, {"c.json", "invalid JSON", "\\x7f"});
  expect_bad("0 0 0\n1 \x1b[31m 0\n", "c.txt", 2, {"c.txt: line 2", "'\\x1b[31m'"});
}

TEST(Handles, JsonWithoutHandlesKey) {
  expect_bad(R"({"constraints": []})", "k.json", 2, {"k.json", "no \"handles\" key"});
  expect_bad(R"({"handles": 3})", "k.json", 2, {"k.json", "\"handles\" is not an array"});
}

TEST(Handles, JsonEntryWithoutVertex) {
  expect_bad(R"({"handles": [{"vertex": 1, "position": [0, 0]}, {"position": [1, 1]}]})", "v.json", 2,
             {"v.json", "handle entry 1 (0-based)", "missing \"vertex\""});
}

TEST(Handles, JsonEntryWithoutPosition) {
  expect_bad(R"({"handles": [{"vertex": 1}]})", "p.json", 2, {"p.json", "handle entry 0 (0-based)", "missing \"position\""});
}

TEST(Handles, JsonEntryWithBadTypes) {
  expect_bad(R"({"handles": [{"vertex": 1.5, "position": [0, 0]}]})", "t.json", 2, {"entry 0", "not an integer"});
  expect_bad(R"({"handles": [{"vertex": 1, "position": [0, "a"]}]})", "t.json", 2,
             {"entry 0", "\"position\" is not an array of numbers"});
  expect_bad(R"({"handles": [[1, 0, 0]]})", "t.json", 2, {"entry 0", "not an object"});
  expect_bad(R"({"handles": [{"vertex": 1, "position": [0, "a"]}]})", "t.json", 2, {"item 1 is the string 'a'"});
  expect_bad(R"({"handles": [{"vertex": [1], "position": [0, 0]}]})", "t.json", 2, {"\"vertex\" is not an integer: an array"});
}

// A message used to print the offending value whole, and printing is recursive: a deeply
// nested value overflowed the stack (a crash, exit 139, instead of exit 1).
TEST(Handles, DeeplyNestedValueIsDescribedNotPrinted) {
  const std::string deep = std::string(200000, '[') + std::string(200000, ']');
  expect_bad(R"({"handles": [{"vertex": 1, "position": )" + deep + "}]}", "n.json", 2,
             {"n.json", "entry 0", "its item 0 is an array"});
  expect_bad(R"({"handles": [{"vertex": )" + deep + R"(, "position": [0, 0]}]})", "n.json", 2,
             {"n.json", "entry 0", "\"vertex\" is not an integer: an array"});
}

// An index past the range of long is named as written, not wrapped to a negative number.
TEST(Handles, HugeVertexIndexIsNamedAsWritten) {
  expect_bad(R"({"handles": [{"vertex": 18446744073709551615, "position": [0, 0]}]})", "h.json", 2,
             {"h.json", "entry 0", "vertex 18446744073709551615 out of range"});
  expect_bad("99999999999999999999999 0 0\n", "h.txt", 2, {"h.txt: line 1: vertex '99999999999999999999999' out of range"});
}

TEST(Handles, VertexOutOfRange) {
  expect_bad("1 0 0\n10 0 0\n", "r.txt", 2, {"r.txt: line 2: vertex 10 out of range (the mesh has 10 vertices"});
  expect_bad("-1 0 0\n", "r.txt", 2, {"r.txt: line 1: vertex -1 out of range"});
  expect_bad(R"({"handles": [{"vertex": 12, "position": [0, 0]}]})", "r.json", 2,
             {"r.json", "handle entry 0 (0-based)", "vertex 12 out of range"});
}

TEST(Handles, WrongDimension) {
  expect_bad("# c\n\n1 0 0\n2 0 0 0\n", "d.txt", 2, {"d.txt: line 4: handle has 3 coordinates, the mesh is 2D"});
  expect_bad("1 0 0\n", "d.txt", 3, {"line 1: handle has 2 coordinates, the mesh is 3D"});
  expect_bad(R"({"handles": [{"vertex": 1, "position": [0]}]})", "d.json", 2,
             {"d.json", "entry 0", "handle has 1 coordinates, the mesh is 2D"});
}

TEST(Handles, NonFiniteValues) {
  expect_bad("1 0 nan\n", "n.txt", 2, {"n.txt: line 1", "non-finite coordinate (nan)"});
  expect_bad("1 -inf 0\n", "n.txt", 2, {"line 1", "non-finite coordinate (-inf)"});
  expect_bad("1 1e999 0\n", "n.txt", 2, {"line 1", "non-finite coordinate (inf)"});
}

TEST(Handles, SameVertexWithTwoTargets) {
  expect_bad("4 0 0\n5 1 1\n4 0 1\n", "dup.txt", 2, {"dup.txt: line 3: vertex 4 has two different targets", "line 1"});
  expect_bad(R"({"handles": [{"vertex": 4, "position": [0, 0]}, {"vertex": 4, "position": [1, 0]}]})", "dup.json", 2,
             {"dup.json", "entry 1", "vertex 4 has two different targets", "entry 0"});
}

TEST(Handles, NoHandles) {
  expect_bad("", "e.txt", 2, {"e.txt: no handles"});
  expect_bad("# only a comment\n\n", "e.txt", 2, {"e.txt: no handles"});
  expect_bad(R"({"handles": []})", "e.json", 2, {"e.json: no handles"});
}

TEST(Handles, TextSyntaxErrors) {
  expect_bad("1 0 0\nx 0 0\n", "s.txt", 2, {"s.txt: line 2: expected a vertex index (an integer), found 'x'"});
  expect_bad("1.5 0 0\n", "s.txt", 2, {"line 1", "found '1.5'"});
  expect_bad("1 0 zero\n", "s.txt", 2, {"s.txt: line 1: expected a number, found 'zero'"});
}

TEST(Handles, MissingFile) {
  expect_input_error([] { read_handles("/nonexistent/h.txt", 10, 2); }, {"cannot read /nonexistent/h.txt"});
}

TEST(Handles, RealConstraintFiles) {
  const std::filesystem::path root = STRICTMIN_SHARED_DATA;
  const auto gecko = root / "planar" / "gecko.constraints.txt";
  const auto boy = root / "tet" / "boy.constraints.txt";
  if (!std::filesystem::exists(gecko) || !std::filesystem::exists(boy)) GTEST_SKIP() << "no shared data at " << root;
  const std::vector<Handle> g = read_handles(gecko.string(), 804, 2);
  EXPECT_EQ(g.size(), 60u);
  EXPECT_EQ(g[0].vertex, 0);
  EXPECT_EQ(g[0].position, Eigen::Vector2d(-279.86530635911436, 410.87498028251127));
  const std::vector<Handle> b = read_handles(boy.string(), 9389, 3);
  ASSERT_EQ(b.size(), 7u);
  EXPECT_EQ(b[0].vertex, 4004);
  EXPECT_EQ(b[6].vertex, 8487);
  EXPECT_EQ(b[6].position.size(), 3);
}
