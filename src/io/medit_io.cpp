// MEDIT ASCII .mesh: keyword sections (case-insensitive), numbers free across lines,
// 1-based indices, a trailing reference number on every row (ignored).
#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "formats.h"
#include "strictmin/io/mesh_io.h"
#include "text_parse.h"

namespace strictmin::io_detail {
namespace {

// Whitespace-separated tokens over the whole text, '#' comments to the end of the line,
// with the line number of the last token. A line ends at '\n', "\r\n" or a '\r' alone
// (LineReader's rule, text_parse.h).
class TokenStream {
 public:
  explicit TokenStream(std::string_view text) : text_(text) {}
  bool next(std::string_view& token) {
    for (;;) {
      while (pos_ < text_.size() && (is_space(text_[pos_]) || text_[pos_] == '\n')) {
        if (ends_line(pos_)) ++line_;
        ++pos_;
      }
      if (pos_ >= text_.size()) return false;
      if (text_[pos_] == '#') {
        while (pos_ < text_.size() && text_[pos_] != '\n' && text_[pos_] != '\r') ++pos_;
        continue;
      }
      const size_t start = pos_;
      while (pos_ < text_.size() && !is_space(text_[pos_]) && text_[pos_] != '\n') ++pos_;
      token = text_.substr(start, pos_ - start);
      return true;
    }
  }
  long line() const { return line_; }

 private:
  // The character at i ends a line: '\n', or a '\r' not followed by '\n'.
  bool ends_line(size_t i) const {
    return text_[i] == '\n' || (text_[i] == '\r' && (i + 1 == text_.size() || text_[i + 1] != '\n'));
  }

  std::string_view text_;
  size_t pos_ = 0;
  long line_ = 1;
};

// Sections we may skip: name and numbers per entry (d = the mesh dimension).
int skipped_section_width(const std::string& keyword, int dim) {
  if (keyword == "edges") return 3;
  if (keyword == "corners" || keyword == "ridges" || keyword == "requiredvertices" || keyword == "requirededges" ||
      keyword == "requiredtriangles" || keyword == "requiredtetrahedra")
    return 1;
  if (keyword == "normals" || keyword == "tangents") return dim;
  if (keyword == "normalatvertices" || keyword == "tangentatedges" || keyword == "tangentatvertices") return 2;
  if (keyword == "normalattrianglevertices") return 3;
  return -1;
}

// Element sections strictmin cannot mesh with.
bool is_unsupported_element(const std::string& keyword) {
  static const std::array<const char*, 12> names = {
      "quadrilaterals", "hexahedra",        "prisms",       "pyramids",       "edgesp2",         "trianglesp2",
      "tetrahedrap2",   "quadrilateralsq2", "hexahedraq2",  "trianglesp3",    "tetrahedrap3",    "polygons"};
  return std::find(names.begin(), names.end(), keyword) != names.end();
}

class MeditParser {
 public:
  MeditParser(std::string_view text, const std::string& name) : tokens_(text), text_size_(text.size()), name_(name) {}

  Mesh parse() {
    std::string_view token;
    bool any = false;
    while (tokens_.next(token)) {
      any = true;
      const long ln = tokens_.line();
      const std::string keyword = lowercase(token);
      if (keyword == "end") break;
      check_once(keyword, token, ln);
      if (keyword == "meshversionformatted") {
        const long version = read_long("version");
        if (version < 1 || version > 4) fail(name_, ln, "unsupported MeshVersionFormatted " + std::to_string(version));
      } else if (keyword == "dimension") {
        const long dim = read_long("dimension");
        if (dim != 2 && dim != 3) fail(name_, ln, "Dimension " + std::to_string(dim) + " (need 2 or 3)");
        dim_ = static_cast<int>(dim);
      } else if (keyword == "vertices") {
        read_vertices();
      } else if (keyword == "triangles") {
        read_elements(3, triangles_, triangle_lines_, "Triangles");
      } else if (keyword == "tetrahedra") {
        read_elements(4, tets_, tet_lines_, "Tetrahedra");
      } else if (is_unsupported_element(keyword)) {
        const long count = read_long("entries");
        if (count > 0)
          fail(name_, ln, "mixed element types: section " + quote_token(token) +
                              " is not supported (strictmin needs only triangles or only tetrahedra)");
      } else if (const int width = skipped_section_width(keyword, dim_); width > 0) {
        const long count = read_count("entries");
        for (long i = 0; i < count * width; ++i)
          if (!tokens_.next(token)) fail(name_, 0, "unexpected end of file in section " + quote_token(keyword));
      } else {
        fail(name_, ln, "unknown section " + quote_token(token) + " (a .mesh file has Vertices, Triangles, Tetrahedra, ...)");
      }
    }
    if (!any) fail(name_, 0, "empty file");
    return assemble();
  }

 private:
  // The header keywords and the sections read may appear once: a second Vertices section
  // would silently replace the first, a second Dimension reinterpret the vertices read.
  void check_once(const std::string& keyword, std::string_view token, long line) {
    if (keyword != "meshversionformatted" && keyword != "dimension" && keyword != "vertices" &&
        keyword != "triangles" && keyword != "tetrahedra")
      return;
    const auto [it, first] = first_line_.try_emplace(keyword, line);
    if (!first)
      fail(name_, line, "second " + quote_token(token) + " (the first is on line " + std::to_string(it->second) +
                            "; a .mesh file has each section once)");
  }

  // A section's entry count, bounded by the text size (each entry takes several tokens).
  long read_count(const char* what) {
    const long count = read_long(what);
    if (count > static_cast<long>(text_size_))
      fail(name_, tokens_.line(), "section announces " + std::to_string(count) + " entries, more than the file can hold");
    return count;
  }

  long read_long(const char* what) {
    std::string_view token;
    long value;
    if (!tokens_.next(token)) fail(name_, tokens_.line(), std::string("unexpected end of file, expected ") + what);
    if (!parse_long(token, value) || value < 0)
      fail(name_, tokens_.line(), std::string("expected ") + what + " (a non-negative integer), found " + quote_token(token));
    return value;
  }

  void read_vertices() {
    if (dim_ == 0) fail(name_, tokens_.line(), "Vertices before Dimension");
    const long count = read_count("the number of vertices");
    const long first_line = tokens_.line();
    vertices_.resize(static_cast<size_t>(count) * dim_);
    std::string_view token;
    for (long i = 0; i < count; ++i) {
      for (int k = 0; k <= dim_; ++k) {  // dim coordinates, then the reference
        if (!tokens_.next(token))
          fail(name_, first_line, "unexpected end of file: Vertices announces " + std::to_string(count) +
                                      " vertices, found " + std::to_string(i));
        double value;
        if (!parse_double(token, value))
          fail(name_, tokens_.line(), "expected a number in Vertices, found " + quote_token(token));
        if (k < dim_) vertices_[static_cast<size_t>(i) * dim_ + k] = value;
      }
    }
  }

  void read_elements(int corners, std::vector<int>& out, std::vector<long>& lines, const char* section) {
    const long count = read_count("the number of elements");
    const long first_line = tokens_.line();
    out.resize(static_cast<size_t>(count) * corners);
    lines.resize(count);
    std::string_view token;
    for (long e = 0; e < count; ++e) {
      for (int k = 0; k <= corners; ++k) {  // corners indices, then the reference
        if (!tokens_.next(token))
          fail(name_, first_line, std::string("unexpected end of file: ") + section + " announces " +
                                      std::to_string(count) + " elements, found " + std::to_string(e));
        long value;
        if (!parse_long(token, value))
          fail(name_, tokens_.line(), std::string("expected an integer in ") + section + ", found " + quote_token(token));
        if (k == 0) lines[e] = tokens_.line();
        if (k < corners && (value < 1 || value > std::numeric_limits<int>::max()))
          fail(name_, tokens_.line(), "vertex index " + std::to_string(value) + " out of range (indices start at 1)");
        if (k < corners) out[static_cast<size_t>(e) * corners + k] = static_cast<int>(value - 1);
      }
    }
  }

  // Indices are 1-based in the file; checked here because Vertices may come later.
  void check_indices(const std::vector<int>& elements, const std::vector<long>& lines, int corners,
                     long num_vertices) const {
    for (size_t e = 0; e < lines.size(); ++e) {
      const int* c = &elements[e * corners];
      for (int k = 0; k < corners; ++k) {
        if (c[k] < 0 || c[k] >= num_vertices)
          fail(name_, lines[e], "vertex index " + std::to_string(static_cast<long>(c[k]) + 1) +
                                    " out of range (the file has " + std::to_string(num_vertices) +
                                    " vertices, indices from 1)");
        for (int j = 0; j < k; ++j)
          if (c[j] == c[k]) fail(name_, lines[e], "element uses vertex " + std::to_string(c[k] + 1) + " twice");
      }
    }
  }

  Mesh assemble() const {
    const int dim = dim_ == 0 ? 3 : dim_;
    const long nv = static_cast<long>(vertices_.size()) / dim;
    Mesh mesh;
    mesh.V.resize(nv, dim);
    for (long i = 0; i < nv; ++i)
      for (int k = 0; k < dim; ++k) mesh.V(i, k) = vertices_[static_cast<size_t>(i) * dim + k];
    // With tetrahedra the triangles are (at most) the boundary: ignored.
    const bool tets = !tet_lines_.empty();
    const int corners = tets ? 4 : 3;
    const std::vector<int>& elements = tets ? tets_ : triangles_;
    const std::vector<long>& lines = tets ? tet_lines_ : triangle_lines_;
    check_indices(elements, lines, corners, nv);
    if (tets && dim != 3) fail(name_, 0, "tetrahedra need Dimension 3");
    mesh.F.resize(static_cast<Eigen::Index>(lines.size()), corners);
    for (size_t e = 0; e < lines.size(); ++e)
      for (int k = 0; k < corners; ++k) mesh.F(static_cast<Eigen::Index>(e), k) = elements[e * corners + k];
    return mesh;
  }

  TokenStream tokens_;
  size_t text_size_;
  const std::string& name_;
  int dim_ = 0;
  std::vector<double> vertices_;
  std::vector<int> triangles_, tets_;
  std::vector<long> triangle_lines_, tet_lines_;
  std::map<std::string, long> first_line_;  // keyword -> line of its first appearance
};

void append_element_section(std::string& b, const char* section, const Eigen::MatrixXi& elements, int ref,
                            ChunkWriter& out) {
  b += section;
  b += '\n';
  append_number(b, static_cast<long>(elements.rows()));
  b += '\n';
  for (Eigen::Index e = 0; e < elements.rows(); ++e) {
    for (Eigen::Index k = 0; k < elements.cols(); ++k) {
      append_number(b, elements(e, k) + 1);
      b += ' ';
    }
    append_number(b, ref);
    b += '\n';
    out.maybe_flush();
  }
}

}  // namespace

Mesh read_medit(std::string_view text, const std::string& name) { return MeditParser(text, name).parse(); }

void write_medit(std::ostream& os, const Mesh& mesh) {
  ChunkWriter out(os);
  std::string& b = out.buffer();
  const int dim = mesh.element_type() == ElementType::Tetrahedron ? 3 : (mesh.dim() == 2 ? 2 : 3);
  b += "MeshVersionFormatted 1\nDimension ";
  append_number(b, dim);
  b += "\nVertices\n";
  append_number(b, static_cast<long>(mesh.V.rows()));
  b += '\n';
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
    for (int k = 0; k < dim; ++k) {
      append_number(b, k < mesh.V.cols() ? mesh.V(i, k) : 0.0);
      b += ' ';
    }
    b += "0\n";
    out.maybe_flush();
  }
  if (mesh.element_type() == ElementType::Tetrahedron) {
    append_element_section(b, "Triangles", tet_boundary_faces(mesh.F), 1, out);
    append_element_section(b, "Tetrahedra", mesh.F, 1, out);
  } else {
    append_element_section(b, "Triangles", mesh.F, 1, out);
  }
  b += "End\n";
  out.flush();
}

}  // namespace strictmin::io_detail
