// ASCII PLY (write only): double vertex coordinates, triangles, optional per-face
// `property float quality` (MeshLab shows it as face quality).
#include <string>

#include "formats.h"
#include "text_parse.h"

namespace strictmin::io_detail {

void write_ply(std::ostream& os, const SurfaceRef& s) {
  ChunkWriter out(os);
  std::string& b = out.buffer();
  b += "ply\nformat ascii 1.0\ncomment written by strictmin\nelement vertex ";
  append_number(b, static_cast<long>(s.V.rows()));
  b += "\nproperty double x\nproperty double y\nproperty double z\nelement face ";
  append_number(b, static_cast<long>(s.F.rows()));
  b += "\nproperty list uchar int vertex_indices\n";
  if (s.quality) b += "property float quality\n";
  b += "end_header\n";
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
    if (s.quality) {
      b += ' ';
      // Declared float: the shortest text of the float value.
      append_number(b, static_cast<float>((*s.quality)(f)));
    }
    b += '\n';
    out.maybe_flush();
  }
  out.flush();
}

}  // namespace strictmin::io_detail
