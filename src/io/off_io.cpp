// OFF (Object File Format): header [ST][C][N]OFF, counts, vertex lines, face lines.
// Extra columns (colours, normals, texture coordinates) are ignored; only triangles.
#include <string>
#include <vector>

#include "formats.h"
#include "text_parse.h"

namespace strictmin::io_detail {
namespace {

// Next line with something on it (comments stripped); false at the end of the text.
bool next_content_line(LineReader& lines, Tokens& tokens) {
  std::string_view line;
  while (lines.next(line)) {
    tokens = Tokens(line);
    if (!tokens.empty()) return true;
  }
  return false;
}

bool is_off_keyword(std::string_view word) {
  if (word.size() < 3 || word.substr(word.size() - 3) != "OFF") return false;
  // Prefix letters: ST (texture), C (colour), N (normal); 4 and n (other dimensions) are
  // rejected by the caller.
  for (char c : word.substr(0, word.size() - 3))
    if (c != 'S' && c != 'T' && c != 'C' && c != 'N' && c != '4' && c != 'n') return false;
  return true;
}

long read_count(Tokens& tokens, const std::string& name, long line, const char* what) {
  std::string_view token;
  long value;
  if (!tokens.next(token)) fail(name, line, std::string("missing the number of ") + what);
  if (!parse_long(token, value) || value < 0)
    fail(name, line, std::string("bad number of ") + what + ": " + quote_token(token));
  return value;
}

}  // namespace

Mesh read_off(std::string_view text, const std::string& name) {
  LineReader lines(text);
  Tokens tokens{std::string_view{}};
  if (!next_content_line(lines, tokens)) fail(name, 0, "empty file");

  std::string_view keyword;
  tokens.next(keyword);
  if (!is_off_keyword(keyword))
    fail(name, lines.line_number(), "expected the OFF header (OFF, COFF or NOFF), found " + quote_token(keyword));
  if (keyword.find('4') != std::string_view::npos || keyword.find('n') != std::string_view::npos)
    fail(name, lines.line_number(), "header " + quote_token(keyword) + ": only 3D OFF files are supported");
  std::string_view token;
  Tokens after_keyword = tokens;
  if (after_keyword.next(token) && lowercase(token) == "binary")
    fail(name, lines.line_number(), "binary OFF is not supported (write it as ASCII)");
  // The counts follow on the header line or on the next line.
  if (tokens.empty() && !next_content_line(lines, tokens))
    fail(name, lines.line_number(), "missing the counts line (#vertices #faces #edges)");
  const long counts_line = lines.line_number();
  const long nv = read_count(tokens, name, counts_line, "vertices");
  const long nf = read_count(tokens, name, counts_line, "faces");
  // Every vertex and face takes a line: larger counts cannot be right (and must not be
  // allocated).
  if (nv > static_cast<long>(text.size()) || nf > static_cast<long>(text.size()))
    fail(name, counts_line, "the header announces " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
                                " faces, more than the file can hold");

  Mesh mesh;
  mesh.V.resize(nv, 3);
  for (long i = 0; i < nv; ++i) {
    if (!next_content_line(lines, tokens))
      fail(name, 0, "unexpected end of file: the header announces " + std::to_string(nv) + " vertices, found " +
                        std::to_string(i));
    for (int k = 0; k < 3; ++k) {
      double value;
      if (!tokens.next(token)) fail(name, lines.line_number(), "vertex with fewer than 3 coordinates");
      if (!parse_double(token, value))
        fail(name, lines.line_number(), "expected a number, found " + quote_token(token));
      mesh.V(i, k) = value;
    }
  }
  mesh.F.resize(nf, 3);
  for (long f = 0; f < nf; ++f) {
    if (!next_content_line(lines, tokens))
      fail(name, 0, "unexpected end of file: the header announces " + std::to_string(nf) + " faces, found " +
                        std::to_string(f));
    const long ln = lines.line_number();
    long corners;
    tokens.next(token);
    if (!parse_long(token, corners) || corners < 0)
      fail(name, ln, "expected the number of corners of a face, found " + quote_token(token));
    if (corners > 3)
      fail(name, ln, "polygon with " + std::to_string(corners) +
                         " corners; strictmin needs triangles (triangulate the mesh first)");
    if (corners < 3) fail(name, ln, "polygon with " + std::to_string(corners) + " corner(s) (a face needs 3)");
    for (int k = 0; k < 3; ++k) {
      long index;
      if (!tokens.next(token)) fail(name, ln, "face announces 3 corners but lists fewer");
      if (!parse_long(token, index)) fail(name, ln, "expected a vertex index, found " + quote_token(token));
      if (index < 0 || index >= nv)
        fail(name, ln, "vertex index " + std::to_string(index) + " out of range (the file has " +
                           std::to_string(nv) + " vertices, indices from 0)");
      mesh.F(f, k) = static_cast<int>(index);
    }
    // Anything after the three indices (a face colour) is ignored.
    const auto c = mesh.F.row(f);
    if (c(0) == c(1) || c(1) == c(2) || c(0) == c(2))
      fail(name, ln, "face uses vertex " + std::to_string(c(0) == c(1) || c(0) == c(2) ? c(0) : c(1)) + " twice");
  }
  return mesh;
}

void append_vertex_and_face_lines(ChunkWriter& out, const SurfaceRef& s,
                                  const std::function<void(std::string&, Eigen::Index)>& after_face) {
  std::string& b = out.buffer();
  for (Eigen::Index i = 0; i < s.V.rows(); ++i) {
    for (Eigen::Index k = 0; k < 3; ++k) {
      if (k) b += ' ';
      append_number(b, k < s.V.cols() ? s.V(i, k) : 0.0);
    }
    b += '\n';
    out.maybe_flush();
  }
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
    b += '3';
    for (int k = 0; k < 3; ++k) {
      b += ' ';
      append_number(b, s.F(f, k));
    }
    if (after_face) after_face(b, f);
    b += '\n';
    out.maybe_flush();
  }
}

void write_off(std::ostream& os, const SurfaceRef& s) {
  ChunkWriter out(os);
  std::string& b = out.buffer();
  b += "OFF\n";
  append_number(b, static_cast<long>(s.V.rows()));
  b += ' ';
  append_number(b, static_cast<long>(s.F.rows()));
  b += " 0\n";
  append_vertex_and_face_lines(out, s, nullptr);
  out.flush();
}

}  // namespace strictmin::io_detail
