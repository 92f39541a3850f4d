#include "gparam_report.h"

#include <filesystem>

#include "common.h"
#include "strictmin/io/input_error.h"
#include "strictmin/report/html_report.h"
#include "strictmin/report/quad_view.h"

namespace strictmin::cli {

GParamMarks gparam_marks(const Mesh& mesh, const GParamOutcome& g) {
  GParamMarks m;
  const int F = mesh.num_elements();
  m.seam_side.assign(static_cast<size_t>(F) * 3, 0);
  m.corner_index.assign(static_cast<size_t>(F) * 3, 0);
  for (int f = 0; f < F; ++f)
    for (int i = 0; i < 3; ++i) {
      m.seam_side[f * 3 + i] = g.cut.cut[g.graph.face_edges(f, i)];
      m.corner_index[f * 3 + i] = g.quarters[mesh.F(f, i)];
    }
  return m;
}

MethodRun method_run(const std::string& method, const GParamOutcome& g) {
  MethodRun r;
  r.method = method;
  r.mapped = g.mapped;
  r.distortion = g.measured.distortion;
  r.weights = g.measured.weights;
  r.flipped = g.measured.stats.flipped;
  r.lower_bound = g.result.lower_bound;
  r.time_s = g.result.time_s;
  r.status = status_name(g.result.status);
  r.message = g.result.message;
  return r;
}

std::vector<std::string> write_gparam_pictures(const std::string& dir, const std::string& name, const Mesh& mesh,
                                               const GParamOutcome& g, double scale) {
  const GParamMarks marks = gparam_marks(mesh, g);
  RasterOptions r;
  r.width = 560;
  r.height = 420;
  r.edge_width = 0;
  const std::string field = name + "_field.png", grid = name + "_grid.png";
  write_png((std::filesystem::path(dir) / field).string(), render_gparam_distortion(mesh, g.measured.distortion, marks, scale, r));
  write_png((std::filesystem::path(dir) / grid).string(), render_gparam_grid(g.mapped, marks, r));
  return {field, grid};
}

std::string write_gparam_report(const ReportArgs& a, const nlohmann::json& summary, const std::string& input,
                                const Mesh& mesh, const GParamOutcome& g, const QuadMesh* quads) {
  open_report_folder(a.dir);
  const std::string method = summary.value("method", std::string("l2"));
  MethodRun run = method_run(method, g);
  const auto pictures = write_gparam_pictures(a.dir, method, mesh, g, section_colour_scale({run}, a.scale));
  SectionInput in;
  in.title = method_label(method) + " global parametrization of " + input_title(input);
  in.description = "Task gparam, measure " + summary.value("measure", std::string("fd")) + ", " +
                   std::to_string(mesh.num_elements()) + " triangles, Euler characteristic " +
                   std::to_string(g.graph.euler_characteristic()) + ", " + std::to_string(g.singular.size()) +
                   " singularities (white dots: positive index, black dots: negative), " + std::to_string(g.cut.num_cut_edges) +
                   " seam edges (dark red), seam error " + shown_number(g.seam_error, 2) + "." +
                   (summary.value("integer_grid", false)
                        ? " Integer-grid map: singular vertices and seam translations rounded to the grid (" +
                              std::to_string(g.rounding.singularities) + " and " +
                              std::to_string(g.rounding.translations) +
                              "), off it by at most " + shown_number(g.integer_error, 2) + " grid units."
                        : std::string());
  describe_measure(in, summary.value("measure", std::string("fd")), "gparam");
  in.rest = &mesh;
  run.view_name = "view";
  run.links.emplace_back("surface with seams and singularities", pictures[0]);
  run.links.emplace_back("unit grid through the map", pictures[1]);
  if (quads) {
    RasterOptions r;
    r.width = 560;
    r.height = 420;
    r.frame_points = mesh.V;  // framed as the surface's pictures
    const std::string name = method + "_quads.png";
    write_png((std::filesystem::path(a.dir) / name).string(), render_quad_mesh(*quads, r));
    run.links.emplace_back("quad mesh (white dots: valence 3 or less, black: 5 or more)", name);
  }
  run.links.emplace_back("summary.json", "summary.json");
  in.runs.push_back(std::move(run));
  return write_report_folder(a, summary, in.title, {in});
}

}  // namespace strictmin::cli
