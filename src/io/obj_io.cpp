// Wavefront OBJ: v, vt and triangular f statements; everything else is ignored.
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "formats.h"
#include "text_parse.h"

namespace strictmin::io_detail {
namespace {

// Statements that carry nothing strictmin uses (normals, groups, materials, free-form
// geometry, lines and points): skipped without a word.
bool is_ignored_statement(std::string_view keyword) {
  static const std::set<std::string_view> ignored = {
      "vn",    "vp",      "g",       "o",       "s",        "usemtl",     "mtllib", "l",    "p",
      "maplib", "usemap", "lod",     "shadow_obj", "trace_obj", "bevel",   "c_interp", "d_interp",
      "ctech", "stech",   "cstype",  "deg",     "bmat",     "step",       "curv",   "curv2", "surf",
      "parm",  "trim",    "hole",    "scrv",    "sp",       "end",        "con",    "call", "csh"};
  return ignored.count(keyword) > 0;
}

// One "i", "i/t", "i/t/n" or "i//n" corner: parses the vertex and (optional) texture
// index as written (1-based, or negative = relative). t == 0 when absent.
bool parse_corner(std::string_view token, long& v, long& t) {
  const size_t slash = token.find('/');
  if (!parse_long(token.substr(0, slash), v) || v == 0) return false;
  t = 0;
  if (slash == std::string_view::npos) return true;
  std::string_view rest = token.substr(slash + 1);
  const size_t slash2 = rest.find('/');
  const std::string_view tex = rest.substr(0, slash2);
  if (!tex.empty() && (!parse_long(tex, t) || t == 0)) return false;
  if (slash2 != std::string_view::npos) {
    long n = 0;
    const std::string_view normal = rest.substr(slash2 + 1);
    if (!normal.empty() && !parse_long(normal, n)) return false;
  }
  return true;
}

// 1-based or negative (relative to `count` items read so far) index to 0-based; -1 when a
// relative index points before the first item.
long resolve_index(long index, long count) { return index > 0 ? index - 1 : count + index; }

// Indices are stored as int.
constexpr long kMaxIndex = std::numeric_limits<int>::max();

}  // namespace

Mesh read_obj(std::string_view text, const std::string& name, std::vector<std::string>* warnings) {
  std::vector<double> coords;  // 3 per vertex (z = 0 for 2D)
  std::vector<double> uvs;     // 2 per vt
  std::vector<int> faces;      // 3 per face, 0-based
  std::vector<int> face_uvs;   // 3 per face, 0-based, -1 when the face has none
  std::vector<long> face_lines;
  int dim = 0;
  long dim_line = 0;
  long faces_with_uv = 0;
  std::set<std::string> warned_keywords;

  LineReader lines(text);
  std::string_view line;
  while (lines.next(line)) {
    const long ln = lines.line_number();
    Tokens tokens(line);
    std::string_view keyword;
    if (!tokens.next(keyword)) continue;  // blank or comment

    if (keyword == "v") {
      double xyz[3] = {0.0, 0.0, 0.0};
      int n = 0;
      std::string_view token;
      while (tokens.next(token)) {
        double value;
        if (!parse_double(token, value)) fail(name, ln, "expected a number, found " + quote_token(token));
        if (n < 3) xyz[n] = value;
        ++n;  // a 4th value (w) or colours after x y z are ignored
      }
      if (n < 2) fail(name, ln, "vertex with " + std::to_string(n) + " coordinate(s) (need 2 or 3)");
      const int this_dim = n == 2 ? 2 : 3;
      if (dim == 0) {
        dim = this_dim;
        dim_line = ln;
      } else if (this_dim != dim) {
        fail(name, ln, "vertex has " + std::to_string(this_dim) + " coordinates but the vertex on line " +
                           std::to_string(dim_line) + " has " + std::to_string(dim) +
                           " (all vertices need the same number)");
      }
      coords.insert(coords.end(), xyz, xyz + 3);
    } else if (keyword == "vt") {
      double uv[2] = {0.0, 0.0};
      int n = 0;
      std::string_view token;
      while (tokens.next(token)) {
        double value;
        if (!parse_double(token, value)) fail(name, ln, "expected a number, found " + quote_token(token));
        if (n < 2) uv[n] = value;
        ++n;
      }
      if (n < 1) fail(name, ln, "texture coordinate without values");
      uvs.insert(uvs.end(), uv, uv + 2);
    } else if (keyword == "f") {
      const long num_v = static_cast<long>(coords.size() / 3);
      const long num_t = static_cast<long>(uvs.size() / 2);
      long v[3], t[3];
      int corners = 0;
      bool all_tex = true;
      std::string_view token;
      while (tokens.next(token)) {
        long vi, ti;
        if (!parse_corner(token, vi, ti))
          fail(name, ln, "bad face corner " + quote_token(token) + " (expected i, i/t, i/t/n or i//n with indices from 1)");
        if (corners < 3) {
          v[corners] = resolve_index(vi, num_v);
          if (v[corners] >= kMaxIndex)
            fail(name, ln, "vertex index " + std::to_string(vi) + " out of range (too large)");
          if (v[corners] < 0)
            fail(name, ln, "relative vertex index " + std::to_string(vi) + " points before the first vertex (" +
                               std::to_string(num_v) + " vertices so far)");
          t[corners] = ti == 0 ? -1 : resolve_index(ti, num_t);
          if (t[corners] >= kMaxIndex)
            fail(name, ln, "texture coordinate index " + std::to_string(ti) + " out of range (too large)");
          if (ti != 0 && t[corners] < 0)
            fail(name, ln, "relative texture index " + std::to_string(ti) +
                               " points before the first vt (" + std::to_string(num_t) + " so far)");
        }
        all_tex = all_tex && ti != 0;
        ++corners;
      }
      if (corners > 3)
        fail(name, ln, "face with " + std::to_string(corners) +
                           " corners; strictmin needs triangles (triangulate the mesh first)");
      if (corners < 3) fail(name, ln, "face with " + std::to_string(corners) + " corner(s) (a face needs 3)");
      for (int k = 0; k < 3; ++k) {
        faces.push_back(static_cast<int>(v[k]));
        face_uvs.push_back(all_tex ? static_cast<int>(t[k]) : -1);
      }
      faces_with_uv += all_tex ? 1 : 0;
      face_lines.push_back(ln);
    } else if (!is_ignored_statement(keyword)) {
      const std::string word(keyword);
      if (warnings && warned_keywords.insert(word).second)
        warnings->push_back(located(name, ln, "unknown statement " + quote_token(word) + " ignored"));
    }
  }

  // Positive indices may refer to vertices defined later in the file: check at the end.
  const long num_v = static_cast<long>(coords.size() / 3);
  const long num_t = static_cast<long>(uvs.size() / 2);
  const long num_f = static_cast<long>(face_lines.size());
  for (long f = 0; f < num_f; ++f) {
    for (int k = 0; k < 3; ++k) {
      const long vi = faces[3 * f + k];
      if (vi >= num_v)
        fail(name, face_lines[f], "vertex index " + std::to_string(vi + 1) + " out of range (the file has " +
                                      std::to_string(num_v) + " vertices)");
      const long ti = face_uvs[3 * f + k];
      if (ti >= num_t)
        fail(name, face_lines[f], "texture coordinate index " + std::to_string(ti + 1) +
                                      " out of range (the file has " + std::to_string(num_t) + " vt lines)");
    }
    const int* c = &faces[3 * f];
    if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2])
      fail(name, face_lines[f], "face uses vertex " + std::to_string((c[0] == c[1] || c[0] == c[2] ? c[0] : c[1]) + 1) +
                                    " twice");
  }

  Mesh mesh;
  const int d = dim == 0 ? 3 : dim;
  mesh.V.resize(num_v, d);
  for (long i = 0; i < num_v; ++i)
    for (int k = 0; k < d; ++k) mesh.V(i, k) = coords[3 * i + k];
  mesh.F.resize(num_f, 3);
  for (long f = 0; f < num_f; ++f)
    for (int k = 0; k < 3; ++k) mesh.F(f, k) = faces[3 * f + k];

  if (num_f > 0 && faces_with_uv == num_f) {
    mesh.UV.resize(num_t, 2);
    for (long i = 0; i < num_t; ++i) mesh.UV.row(i) << uvs[2 * i], uvs[2 * i + 1];
    mesh.FUV.resize(num_f, 3);
    for (long f = 0; f < num_f; ++f)
      for (int k = 0; k < 3; ++k) mesh.FUV(f, k) = face_uvs[3 * f + k];
  } else if (faces_with_uv > 0 && warnings) {
    warnings->push_back(located(name, 0, "texture coordinates ignored: only " + std::to_string(faces_with_uv) +
                                             " of " + std::to_string(num_f) + " faces have them"));
  }
  return mesh;
}

void write_obj(std::ostream& os, const SurfaceRef& s) {
  ChunkWriter out(os);
  std::string& b = out.buffer();
  b += "# written by strictmin\n";
  for (Eigen::Index i = 0; i < s.V.rows(); ++i) {
    b += "v";
    for (Eigen::Index k = 0; k < 3; ++k) {
      b += ' ';
      append_number(b, k < s.V.cols() ? s.V(i, k) : 0.0);
    }
    b += '\n';
    out.maybe_flush();
  }
  const bool uv = s.UV && s.FUV && s.UV->rows() > 0 && s.FUV->rows() == s.F.rows();
  if (uv) {
    for (Eigen::Index i = 0; i < s.UV->rows(); ++i) {
      b += "vt ";
      append_number(b, (*s.UV)(i, 0));
      b += ' ';
      append_number(b, (*s.UV)(i, 1));
      b += '\n';
      out.maybe_flush();
    }
  }
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
    b += 'f';
    for (int k = 0; k < 3; ++k) {
      b += ' ';
      append_number(b, s.F(f, k) + 1);
      if (uv) {
        b += '/';
        append_number(b, (*s.FUV)(f, k) + 1);
      }
    }
    b += '\n';
    out.maybe_flush();
  }
  out.flush();
}

}  // namespace strictmin::io_detail
