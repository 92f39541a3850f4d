#include "demo_gparam.h"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "gparam_report.h"
#include "quad_output.h"
#include "strictmin/report/quad_view.h"
#include "strictmin/tasks/quad_extraction.h"
#include "common.h"
#include "strictmin/io/mesh_io.h"
#include "strictmin/mesh/polycube.h"
#include "strictmin/tasks/gparam.h"

namespace strictmin::cli {

Mesh demo_bulged_frame() { return make_bulged_frame_surface(4, 7); }

namespace {

// The frame's integer-grid map (linf, the L-infinity guide) and its quad mesh, linked from the
// linf run: gparam/grid.obj, gparam/quads.obj and gparam/quads.png.
void add_quad_mesh_demo(const std::string& dir, const Mesh& frame, MethodRun& linf_run, const OutputOptions& output) {
  namespace fs = std::filesystem;
  GParamOptions o;
  o.solver.method = Method::Linf;
  o.quads = 400;
  o.field_options.pin_face = 0;
  o.integer_grid = true;
  o.grid_guide = GParamOptions::GridGuide::Linf;
  const GParamOutcome g = global_parametrize(frame, o, "bulged frame");
  const fs::path folder = fs::path(dir) / "gparam";
  write_mesh((folder / "grid.obj").string(), g.mapped);
  const QuadExtraction x = extract_quads(g.mapped, {}, "bulged frame");
  write_quad_obj((folder / "quads.obj").string(), x.mesh);
  RasterOptions r;
  r.width = 560;
  r.height = 420;
  r.frame_points = frame.V;
  write_png((folder / "quads.png").string(), render_quad_mesh(x.mesh, r));
  linf_run.links.push_back({"integer-grid map", "gparam/grid.obj"});
  linf_run.links.push_back({"its quad mesh", "gparam/quads.png"});
  linf_run.links.push_back({"quads (OBJ)", "gparam/quads.obj"});
  progress(output, "demo: gparam  integer grid (linf): " + std::to_string(g.measured.stats.flipped) + " flipped, " +
                       quad_extraction_phrase(x));
}

}  // namespace

ReportSection write_gparam_demo_section(const std::string& dir, const ComparisonOptions& options,
                                        const OutputOptions& output, bool& all_solved) {
  namespace fs = std::filesystem;
  const Mesh frame = demo_bulged_frame();
  SectionInput in;
  in.id = "gparam";
  in.title = "Global parametrization: a closed genus-1 surface";
  in.description =
      "A polycube frame (3 x 3 x 1 cubes without the centre, " + std::to_string(frame.num_elements()) +
      " triangles) with its flat sides bulged, mapped seamlessly to the plane along its smoothest cross field "
      "(strictmin gparam, docs/gparam.md). The 8 convex corners have index +1/4, the 8 saddle corners -1/4 (they "
      "sum to the Euler characteristic 0). The distortion is the field deviation: how far each triangle's "
      "differential is from the rotation that takes the field to the u and v axes. The links show each map's "
      "seams (dark red), singularities (dots) and unit grid; the linf run also links an integer-grid map (cones and "
      "seam translations rounded to the grid, strictmin gparam --integer-grid) and its quad mesh (strictmin quads).";
  in.measure = "field deviation";
  in.rest = &frame;
  fs::create_directories(fs::path(dir) / "gparam");
  std::vector<GParamOutcome> outcomes;  // for the pictures drawn after the loop
  for (const Method m : {Method::L2, Method::Linf, Method::Relax}) {
    GParamOptions o;
    o.solver.method = m;
    o.quads = 400;
    o.field_options.pin_face = 0;  // the global angle: along the cubes' edges (else any angle)
    const GParamOutcome g = global_parametrize(frame, o, "bulged frame");
    const std::string name = method_name(m);
    const fs::path folder = fs::path(dir) / "gparam";
    write_mesh((folder / (name + ".obj")).string(), g.mapped);
    // The result as `gparam -o --distortion --summary` writes it (strictmin report reads these).
    OutputOptions files;
    files.summary = (folder / (name + ".json")).string();
    files.distortion = (folder / (name + ".txt")).string();
    write_outputs(files,
                  gparam_summary(frame, o, g, o.field_kind(), {"example:bulged-frame", name + ".obj", name + ".txt"}),
                  g.measured.distortion);
    MethodRun run = method_run(name, g);
    run.links = {{"summary", "gparam/" + name + ".json"}, {"UV mesh", "gparam/" + name + ".obj"}};
    outcomes.push_back(g);
    all_solved = all_solved && g.result.ok();
    char line[200];
    std::snprintf(line, sizeof line, "demo: gparam  %-7s max %.5f  L2 %.5f  flipped %d  seam error %.1e  %.2f s  %s",
                  name.c_str(), g.measured.stats.max, g.measured.stats.l2, g.measured.stats.flipped, g.seam_error,
                  g.solve_time_s, status_name(g.result.status).c_str());
    progress(output, line);
    in.runs.push_back(std::move(run));
  }
  // The seams-and-singularities pictures on the section's colour scale (known once every
  // run is in).
  const double scale = section_colour_scale(in.runs, options.scale);
  for (std::size_t i = 0; i < in.runs.size(); ++i) {
    const std::string& name = in.runs[i].method;
    const auto pictures = write_gparam_pictures((fs::path(dir) / "gparam").string(), name, frame, outcomes[i], scale);
    in.runs[i].links.push_back({"seams and singularities", "gparam/" + pictures[0]});
    in.runs[i].links.push_back({"unit grid", "gparam/" + pictures[1]});
  }
  add_quad_mesh_demo(dir, frame, in.runs[1], output);
  return write_section(dir, in, options);
}

}  // namespace strictmin::cli
