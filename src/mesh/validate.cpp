// Mesh validation: each check is one function, run in the order documented in validate.h.
// Adjacency checks sort edge / face keys: O(n log n), no per-element allocation.
#include "strictmin/mesh/validate.h"

#include "image_sizes.h"  // beside this file: the fuzz targets build it without src/ on the include path

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <utility>

#include "strictmin/io/input_error.h"

namespace strictmin {
namespace {

// Relative thresholds below which an element counts as degenerate: area <= eps * d^2,
// volume <= eps * d^3, d the bounding-box diagonal of the used vertices. Real slivers
// (0.06-degree angles) are far above this; exactly collinear/coplanar corners are below.
constexpr double kDegenerateEps = 1e-14;
constexpr double kMinSize = kSmallestSize, kMaxSize = kLargestSize;

class Validator {
 public:
  Validator(const Mesh& mesh, const std::string& source)
      : mesh_(mesh), source_(source), tets_(mesh.F.cols() == 4), noun_(tets_ ? "tet" : "face") {}

  void run(std::vector<std::string>* warnings, bool check_geometry) {
    check_not_empty();
    check_structure(true);
    // With the geometry checks the bounding box bounds V's sizes (check_measures); an image
    // (a map's MAPPED mesh, an interpolation target) and UVs are held to the same limit here.
    check_sizes(!check_geometry);
    if (check_geometry) check_measures();
    check_duplicates();
    if (tets_)
      check_tet_faces();
    else
      check_triangle_edges();
    if (check_geometry) check_signs();
    if (warnings) warn_unreferenced(*warnings);
  }

  // Corner and coordinate counts, finite coordinates (when asked), indices in range: what
  // every function taking a Mesh relies on (check_mesh_structure).
  void check_structure(bool require_finite) const {
    check_counts();
    if (require_finite) check_finite();
    check_indices();
  }

 private:
  [[noreturn]] void fail(const std::string& reason) const { throw InputError(located(source_, 0, reason)); }

  std::string element(long e) const { return std::string(noun_) + " " + std::to_string(e) + " (0-based)"; }

  std::string corner_list(long e) const {
    std::string s;
    for (Eigen::Index k = 0; k < mesh_.F.cols(); ++k) s += (k ? ", " : "") + std::to_string(mesh_.F(e, k));
    return s;
  }

  void check_not_empty() const {
    if (mesh_.V.rows() == 0 && mesh_.F.rows() == 0) fail("empty file (no vertices and no faces)");
    if (mesh_.F.rows() == 0)
      fail("no faces (" + std::to_string(mesh_.V.rows()) + " vertices but no triangles or tetrahedra)");
  }

  // (An empty mesh, which check_mesh_structure lets through, has no counts to check.)
  void check_counts() const {
    const auto& V = mesh_.V;
    const auto& F = mesh_.F;
    if (F.rows() > 0 && F.cols() != 3 && F.cols() != 4)
      fail("elements have " + std::to_string(F.cols()) + " corners (need 3: triangles, or 4: tetrahedra)");
    if (V.rows() > 0 && V.cols() != 2 && V.cols() != 3)
      fail("vertices have " + std::to_string(V.cols()) + " coordinates (need 2 or 3)");
    if (F.rows() > 0 && tets_ && V.cols() != 3) fail("tetrahedra need 3D vertex coordinates, the vertices are 2D");
    check_uv_counts();
  }

  // UV #UV by 2 and FUV one corner per element corner (mesh.h): the writers and
  // map_distortion read FUV(e, k) for every corner of F and two texture coordinates.
  void check_uv_counts() const {
    if (!mesh_.has_uv()) return;
    if (mesh_.FUV.cols() != mesh_.F.cols())
      fail("texture faces have " + std::to_string(mesh_.FUV.cols()) + " corners, the elements " +
           std::to_string(mesh_.F.cols()));
    if (mesh_.UV.cols() != 2)
      fail("texture coordinates have " + std::to_string(mesh_.UV.cols()) + " values (need 2)");
  }

  static std::string non_finite_name(double value) { return std::isnan(value) ? "nan" : value > 0 ? "inf" : "-inf"; }

  void check_finite() const {
    const auto& V = mesh_.V;
    for (Eigen::Index i = 0; i < V.rows(); ++i)
      for (Eigen::Index k = 0; k < V.cols(); ++k)
        if (!std::isfinite(V(i, k)))
          fail("vertex " + std::to_string(i) + " (0-based) has a non-finite coordinate (" + non_finite_name(V(i, k)) +
               ")");
    if (!mesh_.has_uv()) return;
    for (Eigen::Index i = 0; i < mesh_.UV.rows(); ++i)
      for (Eigen::Index k = 0; k < mesh_.UV.cols(); ++k)
        if (!std::isfinite(mesh_.UV(i, k)))
          fail("texture coordinate " + std::to_string(i) + " (0-based) has a non-finite value (" +
               non_finite_name(mesh_.UV(i, k)) + ")");
  }

  void check_indices() const {
    const auto& F = mesh_.F;
    const long nv = mesh_.V.rows();
    for (Eigen::Index e = 0; e < F.rows(); ++e)
      for (Eigen::Index k = 0; k < F.cols(); ++k) {
        const int v = F(e, k);
        if (v < 0 || v >= nv)
          fail(element(e) + " has vertex index " + std::to_string(v) + " out of range (the mesh has " +
               std::to_string(nv) + " vertices)");
        for (Eigen::Index j = 0; j < k; ++j)
          if (F(e, j) == v) fail(element(e) + " uses vertex " + std::to_string(v) + " twice");
      }
    if (mesh_.has_uv()) {
      const long nt = mesh_.UV.rows();
      for (Eigen::Index e = 0; e < mesh_.FUV.rows(); ++e)
        for (Eigen::Index k = 0; k < mesh_.FUV.cols(); ++k)
          if (mesh_.FUV(e, k) < 0 || mesh_.FUV(e, k) >= nt)
            fail(element(e) + " has texture coordinate index " + std::to_string(mesh_.FUV(e, k)) +
                 " out of range (the mesh has " + std::to_string(nt) + ")");
    }
  }

  // Coordinates (when `vertices`) and UVs within kLargestSize: beyond it a map's distortion
  // overflows to inf (reported as a flip) or its solve to NaN (an interpolation target of 1e200
  // came out "solved" with no finite distortion).
 public:
  void check_sizes(bool vertices) const {
    if (vertices) check_values_within_sizes(mesh_.V, source_, "vertex");
    if (mesh_.has_uv()) check_values_within_sizes(mesh_.UV, source_, "texture coordinate");
  }

  // Zero area / volume relative to the mesh size; records the signs for check_signs().
  void check_measures() {
    const auto& V = mesh_.V;
    const auto& F = mesh_.F;
    const Eigen::Index dim = V.cols();
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (Eigen::Index e = 0; e < F.rows(); ++e)
      for (Eigen::Index k = 0; k < F.cols(); ++k)
        for (Eigen::Index d = 0; d < dim; ++d) {
          lo[d] = std::min(lo[d], V(F(e, k), d));
          hi[d] = std::max(hi[d], V(F(e, k), d));
        }
    // The test is scale-free, so it is made on the used vertices moved into the unit box
    // (largest side 1): areas and volumes of far larger or smaller meshes (coordinates of
    // 1e160 or 1e-170) neither overflow nor underflow into "zero area". Half extents first:
    // hi - lo itself may overflow.
    double half_extent = 0.0;
    for (Eigen::Index d = 0; d < dim; ++d) half_extent = std::max(half_extent, 0.5 * hi[d] - 0.5 * lo[d]);
    if (half_extent == 0.0) {
      half_extent = 1.0;  // all used vertices coincide: every element is zero
    } else if (half_extent > 0.5 * kMaxSize || half_extent < 0.5 * kMinSize) {
      const double side = 2.0 * half_extent;  // inf only past the largest double
      char text[32];
      std::snprintf(text, sizeof text, "%.3g", side);
      fail(std::string("the mesh is too ") + (side > kMaxSize ? "large" : "small") +
           ": its bounding box's largest side is " + (std::isinf(side) ? "above 1.8e308" : text) +
           " (strictmin takes sizes from 1e-150 to 1e150: scale the coordinates)");
    }
    auto unit_box = [&](int v) {
      Eigen::Vector3d p = Eigen::Vector3d::Zero();
      for (Eigen::Index d = 0; d < dim; ++d) p(d) = (0.5 * V(v, d) - 0.5 * lo[d]) / half_extent;
      return p;
    };
    double diagonal2 = 0.0;
    for (Eigen::Index d = 0; d < dim; ++d) diagonal2 += std::pow((0.5 * hi[d] - 0.5 * lo[d]) / half_extent, 2);
    const double diagonal = std::sqrt(diagonal2);
    planar_ = !tets_ && mesh_.is_planar();
    for (Eigen::Index e = 0; e < F.rows(); ++e) {
      double measure, signed_measure = 0.0;
      if (tets_) {
        Eigen::Matrix3d edges;  // rows: v1 - v0, v2 - v0, v3 - v0
        for (int k = 0; k < 3; ++k) edges.row(k) = (unit_box(F(e, k + 1)) - unit_box(F(e, 0))).transpose();
        signed_measure = edges.determinant() / 6.0;
        measure = std::abs(signed_measure);
        if (measure <= kDegenerateEps * diagonal * diagonal * diagonal)
          fail(element(e) + " has zero volume (vertices " + corner_list(e) + " are coplanar)");
      } else {
        Eigen::Vector3d p[3];
        for (int k = 0; k < 3; ++k) p[k] = unit_box(F(e, k));
        const Eigen::Vector3d normal = (p[1] - p[0]).cross(p[2] - p[0]);
        measure = 0.5 * normal.norm();
        signed_measure = 0.5 * normal.z();
        if (measure <= kDegenerateEps * diagonal * diagonal)
          fail(element(e) + " has zero area (vertices " + corner_list(e) + " are collinear or coincide)");
      }
      if (signed_measure > 0 && first_positive_ < 0) first_positive_ = e;
      if (signed_measure < 0 && first_negative_ < 0) first_negative_ = e;
    }
  }

  // Two elements over the same vertex set (in any order).
 private:
  void check_duplicates() const {
    const Eigen::Index n = mesh_.F.rows(), m = mesh_.F.cols();
    std::vector<std::pair<std::array<int, 4>, int>> keys(n);
    for (Eigen::Index e = 0; e < n; ++e) {
      std::array<int, 4> c = {-1, -1, -1, -1};
      for (Eigen::Index k = 0; k < m; ++k) c[k] = mesh_.F(e, k);
      for (Eigen::Index k = 1; k < m; ++k)  // insertion sort of 3 or 4 corners
        for (Eigen::Index j = k; j > 0 && c[j - 1] > c[j]; --j) std::swap(c[j - 1], c[j]);
      keys[e] = {c, static_cast<int>(e)};
    }
    std::sort(keys.begin(), keys.end());
    for (size_t i = 1; i < keys.size(); ++i)
      if (keys[i].first == keys[i - 1].first)
        fail(std::string(noun_) + "s " + std::to_string(keys[i - 1].second) + " and " +
             std::to_string(keys[i].second) + " (0-based) have the same vertices (" +
             corner_list(keys[i].second) + ")");
  }

  // Triangles: an edge in more than two faces is non-manifold; an edge in two faces must be
  // traversed in opposite directions.
  void check_triangle_edges() const {
    const auto& F = mesh_.F;
    // key = (min << 32 | max), value = face * 2 + (1 if the face goes max -> min).
    std::vector<std::pair<uint64_t, int64_t>> edges(static_cast<size_t>(F.rows()) * 3);
    for (Eigen::Index f = 0; f < F.rows(); ++f)
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = static_cast<uint32_t>(F(f, k)), b = static_cast<uint32_t>(F(f, (k + 1) % 3));
        const uint64_t key = (static_cast<uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
        edges[f * 3 + k] = {key, static_cast<int64_t>(f) * 2 + (a > b ? 1 : 0)};
      }
    std::sort(edges.begin(), edges.end());
    std::string inconsistent;
    for (size_t i = 0; i < edges.size();) {
      size_t j = i + 1;
      while (j < edges.size() && edges[j].first == edges[i].first) ++j;
      const std::string edge = "edge (" + std::to_string(edges[i].first >> 32) + ", " +
                               std::to_string(edges[i].first & 0xffffffffu) + ")";
      if (j - i > 2) {
        std::string faces;
        for (size_t k = i; k < j && k < i + 6; ++k) faces += (k > i ? ", " : "") + std::to_string(edges[k].second / 2);
        if (j - i > 6) faces += ", ...";
        fail(edge + " is shared by " + std::to_string(j - i) + " faces (non-manifold): faces " + faces + " (0-based)");
      }
      if (j - i == 2 && inconsistent.empty() && (edges[i].second & 1) == (edges[i + 1].second & 1))
        inconsistent = "faces " + std::to_string(edges[i].second / 2) + " and " + std::to_string(edges[i + 1].second / 2) +
                       " (0-based) have inconsistent orientation across " + edge;
      i = j;
    }
    if (!inconsistent.empty()) fail(inconsistent);
  }

  // Tets: a triangle in more than two tets is non-manifold; two tets sharing a triangle must
  // induce opposite orientations on it (else one is inverted, or they overlap).
  void check_tet_faces() const {
    static constexpr int kFaces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
    struct Key {
      std::array<int, 3> corners;  // sorted
      int tet;
      int parity;  // of the permutation sorting the oriented face
      bool operator<(const Key& o) const { return corners != o.corners ? corners < o.corners : tet < o.tet; }
    };
    const auto& F = mesh_.F;
    std::vector<Key> keys(static_cast<size_t>(F.rows()) * 4);
    for (Eigen::Index t = 0; t < F.rows(); ++t)
      for (int l = 0; l < 4; ++l) {
        std::array<int, 3> c = {F(t, kFaces[l][0]), F(t, kFaces[l][1]), F(t, kFaces[l][2])};
        int parity = 0;  // bubble sort of 3 items, counting swaps
        for (int pass = 0; pass < 2; ++pass)
          for (int k = 0; k + 1 < 3 - pass; ++k)
            if (c[k] > c[k + 1]) {
              std::swap(c[k], c[k + 1]);
              parity ^= 1;
            }
        keys[t * 4 + l] = {c, static_cast<int>(t), parity};
      }
    std::sort(keys.begin(), keys.end());
    std::string inconsistent;
    for (size_t i = 0; i < keys.size();) {
      size_t j = i + 1;
      while (j < keys.size() && keys[j].corners == keys[i].corners) ++j;
      const auto& c = keys[i].corners;
      const std::string face = "face (" + std::to_string(c[0]) + ", " + std::to_string(c[1]) + ", " +
                               std::to_string(c[2]) + ")";
      if (j - i > 2) {
        std::string tets;
        for (size_t k = i; k < j && k < i + 6; ++k) tets += (k > i ? ", " : "") + std::to_string(keys[k].tet);
        if (j - i > 6) tets += ", ...";
        fail(face + " is shared by " + std::to_string(j - i) + " tets (non-manifold): tets " + tets + " (0-based)");
      }
      if (j - i == 2 && inconsistent.empty() && keys[i].parity == keys[i + 1].parity)
        inconsistent = "tets " + std::to_string(keys[i].tet) + " and " + std::to_string(keys[i + 1].tet) +
                       " (0-based) have inconsistent orientation across " + face +
                       " (one is inverted, or they overlap)";
      i = j;
    }
    if (!inconsistent.empty()) fail(inconsistent);
  }

  // Planar triangles and tets: one sign for all signed areas / volumes. All-clockwise planar
  // meshes are accepted (maps are measured against the rest shape, whatever its
  // orientation); all-negative tets are rejected (MEDIT and strictmin's boundary
  // orientation assume positive tets).
  void check_signs() const {
    if (!tets_ && !planar_) return;
    if (first_positive_ >= 0 && first_negative_ >= 0) {
      if (tets_)
        fail("tets have inconsistent orientation: " + element(first_positive_) + " has positive volume and " +
             element(first_negative_) + " negative volume");
      fail("faces have inconsistent orientation in the plane: " + element(first_positive_) +
           " is counter-clockwise and " + element(first_negative_) + " clockwise");
    }
    if (tets_ && first_positive_ < 0)
      fail("all tets are inverted (negative volume, e.g. tet 0 (0-based) with vertices " + corner_list(0) +
           "); swap two corners of every tet (e.g. the last two)");
  }

  void warn_unreferenced(std::vector<std::string>& warnings) const {
    const std::vector<int> unused = unreferenced_vertices(mesh_);
    if (unused.empty()) return;
    const std::string first = std::to_string(unused.front());
    if (unused.size() == 1)
      warnings.push_back(located(source_, 0, "1 vertex is used by no " + std::string(noun_) + " (vertex " + first +
                                                 ", 0-based); it is ignored"));
    else
      warnings.push_back(located(source_, 0, std::to_string(unused.size()) + " vertices are used by no " + noun_ +
                                                 " (first: " + first + ", 0-based); they are ignored"));
  }

  const Mesh& mesh_;
  const std::string& source_;
  const bool tets_;
  const char* noun_;
  bool planar_ = false;
  long first_positive_ = -1, first_negative_ = -1;
};

}  // namespace

void validate_mesh(const Mesh& mesh, const std::string& source, std::vector<std::string>* warnings,
                   bool check_geometry) {
  Validator(mesh, source).run(warnings, check_geometry);
}

void check_mesh_structure(const Mesh& mesh, const std::string& source, bool require_finite) {
  Validator(mesh, source.empty() ? std::string("mesh") : source).check_structure(require_finite);
}

// Every entry finite and within kLargestSize: beyond it a map's distortion overflows to inf
// (reported as a flip) or its solve to NaN (an interpolation target of 1e200 came out
// "solved" with no finite distortion). Names `source`, the row (as `row_name` i) and the value.
void check_values_within_sizes(const Eigen::MatrixXd& values, const std::string& source, const std::string& row_name) {
  for (Eigen::Index i = 0; i < values.rows(); ++i)
    for (Eigen::Index k = 0; k < values.cols(); ++k) {
      const double x = values(i, k);
      if (std::abs(x) <= kMaxSize) continue;
      char text[32];
      std::snprintf(text, sizeof text, "%g", x);
      const std::string row = source + ": " + row_name + " " + std::to_string(i) + " (0-based) has ";
      if (!std::isfinite(x)) throw InputError(row + "a non-finite coordinate (" + text + ")");
      throw InputError(row + "the coordinate " + text +
                       ", beyond 1e150 (strictmin takes sizes up to 1e150: scale the coordinates)");
    }
}

void check_image_sizes(const Mesh& mesh, const std::string& source) {
  Validator(mesh, source.empty() ? std::string("mesh") : source).check_sizes(true);
}

void check_element_measures(const Mesh& mesh, const std::string& source) {
  Validator v(mesh, source.empty() ? std::string("mesh") : source);
  v.check_structure(true);
  v.check_measures();
}

bool coordinates_are_finite(const Mesh& mesh) {
  return mesh.V.allFinite() && (!mesh.has_uv() || mesh.UV.allFinite());
}

std::vector<int> unreferenced_vertices(const Mesh& mesh) {
  std::vector<char> used(mesh.V.rows(), 0);
  for (Eigen::Index e = 0; e < mesh.F.rows(); ++e)
    for (Eigen::Index k = 0; k < mesh.F.cols(); ++k) {
      const int v = mesh.F(e, k);
      if (v >= 0 && v < mesh.V.rows()) used[v] = 1;
    }
  std::vector<int> unused;
  for (size_t v = 0; v < used.size(); ++v)
    if (!used[v]) unused.push_back(static_cast<int>(v));
  return unused;
}

}  // namespace strictmin
