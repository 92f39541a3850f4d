// The quad mesh as OBJ (include/strictmin/tasks/quad_extraction.h, write_quad_obj).
#include <iomanip>

#include "strictmin/io/atomic_file.h"
#include "strictmin/tasks/quad_extraction.h"

namespace strictmin {

void write_quad_obj(const std::string& path, const QuadMesh& q) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << std::setprecision(17);
    out << "# strictmin quad mesh: " << q.num_vertices() << " vertices, " << q.num_quads() << " quads\n";
    for (int i = 0; i < q.num_vertices(); ++i) out << "v " << q.V(i, 0) << ' ' << q.V(i, 1) << ' ' << q.V(i, 2) << '\n';
    for (int i = 0; i < q.UV.rows(); ++i) out << "vt " << q.UV(i, 0) << ' ' << q.UV(i, 1) << '\n';
    for (int i = 0; i < q.num_quads(); ++i) {
      out << 'f';
      for (int k = 0; k < 4; ++k) out << ' ' << q.Q(i, k) + 1 << '/' << q.QUV(i, k) + 1;
      out << '\n';
    }
  });
}

}  // namespace strictmin
