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
  std::function<void(std::string&, Eigen::Index)> quality;
  if (s.quality)
    quality = [&](std::string& line, Eigen::Index f) {
      line += ' ';
      // Declared float: the shortest text of the float value.
      append_number(line, static_cast<float>((*s.quality)(f)));
    };
  append_vertex_and_face_lines(out, s, quality);
  out.flush();
}

}  // namespace strictmin::io_detail
