#include "quad_output.h"

#include "report/summary.h"
#include "strictmin/io/input_error.h"

namespace strictmin::cli {

std::string quad_extraction_phrase(const QuadExtraction& x) {
  std::string line = std::to_string(x.mesh.num_quads()) + " quads, " + std::to_string(x.mesh.num_vertices()) +
                     " vertices, Euler characteristic " + std::to_string(x.euler_characteristic);
  if (x.complete && x.filled_squares > 0)
    return line + ", complete after filling " + std::to_string(x.filled_holes) + " hole(s) with " +
           std::to_string(x.filled_squares) + " squares";
  if (x.complete) return line + ", complete";
  if (x.filled_squares > 0)
    line += ", " + std::to_string(x.filled_holes) + " hole(s) filled with " + std::to_string(x.filled_squares) +
            " squares";
  if (x.holes == 0)  // closed, yet not the surface: no squares at all, or a part of it missing
    return line + ", incomplete: the surface's Euler characteristic is " + std::to_string(x.surface_euler_characteristic) +
           ", the map's UV area " + std::to_string(std::llround(x.uv_area)) + ", " + std::to_string(x.flipped_triangles) +
           " flipped triangles, " + std::to_string(x.dropped_squares) + " unit squares left out";
  return line + ", " + std::to_string(x.holes) + " hole(s): " + std::to_string(x.dropped_squares) +
         " unit squares left out (" + std::to_string(x.squares_touching_flips) + " touch the map's " +
         std::to_string(x.flipped_triangles) + " flipped triangles, " + std::to_string(x.squares_wrapped) +
         " wrap onto themselves, " + std::to_string(x.squares_not_covered_once) + " are not covered once, " +
         std::to_string(x.squares_overlapping) + " overlap others)";
}

QuadOutput write_quad_mesh(const Mesh& map, const std::string& path, const std::string& source,
                           const QuadExtractionOptions& options) {
  QuadOutput out;
  QuadExtraction x;
  try {
    x = extract_quads(map, options, source);
  } catch (const InputError& e) {
    out.summary = {{"status", "not-extracted"}, {"reason", e.what()}, {"file", ""}};
    return out;
  }
  if (!path.empty()) write_quad_obj(path, x.mesh);
  out.summary = quad_extraction_summary(x, options);
  out.summary["file"] = path;
  out.complete = x.complete;
  out.mesh = std::move(x.mesh);
  return out;
}

}  // namespace strictmin::cli
