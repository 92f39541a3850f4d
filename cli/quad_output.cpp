#include "quad_output.h"

#include "report/summary.h"
#include "strictmin/io/input_error.h"

namespace strictmin::cli {

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
