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
Mesh demo_bulged_frame_window() { return frame_with_a_window(demo_bulged_frame()); }

namespace {

// One gparam section: its surface and what the page says of it.
struct GParamDemo {
  std::string id;       // the section's folder
  std::string example;  // its summaries' input ("example:NAME", which strictmin report reads again)
  std::string title, description;
  Mesh surface;
  bool pin_field = false;  // the field's global angle along the cubes' edges (closed surfaces only)
  bool quad_mesh = false;  // also the integer-grid map and its quad mesh (closed surfaces only)
};

GParamOptions demo_options(const GParamDemo& demo, Method m) {
  GParamOptions o;
  o.solver.method = m;
  o.quads = 400;
  if (demo.pin_field) o.field_options.pin_face = 0;  // else any angle
  return o;
}

// The frame's integer-grid map (linf, the L-infinity guide) and its quad mesh, linked from the
// linf run: ID/grid.obj, ID/quads.obj and ID/quads.png.
void add_quad_mesh_demo(const std::string& dir, const GParamDemo& demo, MethodRun& linf_run, const OutputOptions& output) {
  namespace fs = std::filesystem;
  GParamOptions o = demo_options(demo, Method::Linf);
  o.integer_grid = true;
  o.grid_guide = GParamOptions::GridGuide::Linf;
  const GParamOutcome g = global_parametrize(demo.surface, o, demo.example);
  const fs::path folder = fs::path(dir) / demo.id;
  write_mesh((folder / "grid.obj").string(), g.mapped);
  const QuadExtraction x = extract_quads(g.mapped, {}, demo.example);
  write_quad_obj((folder / "quads.obj").string(), x.mesh);
  RasterOptions r;
  r.width = 560;
  r.height = 420;
  r.frame_points = demo.surface.V;
  write_png((folder / "quads.png").string(), render_quad_mesh(x.mesh, r));
  linf_run.links.push_back({"integer-grid map", demo.id + "/grid.obj"});
  linf_run.links.push_back({"its quad mesh", demo.id + "/quads.png"});
  linf_run.links.push_back({"quads (OBJ)", demo.id + "/quads.obj"});
  progress(output, "demo: " + demo.id + "  integer grid (linf): " + std::to_string(g.measured.stats.flipped) +
                       " flipped, " + quad_extraction_phrase(x));
}

ReportSection write_section_of(const GParamDemo& demo, const std::string& dir, const ComparisonOptions& options,
                               const OutputOptions& output, bool& all_solved) {
  namespace fs = std::filesystem;
  SectionInput in;
  in.id = demo.id;
  in.title = demo.title;
  in.description = demo.description;
  in.measure = "field deviation";
  in.rest = &demo.surface;
  const fs::path folder = fs::path(dir) / demo.id;
  fs::create_directories(folder);
  const std::string example = demo.example.substr(demo.example.find(':') + 1);
  std::vector<GParamOutcome> outcomes;  // for the pictures drawn after the loop
  for (const Method m : {Method::L2, Method::Linf, Method::Relax}) {
    const GParamOptions o = demo_options(demo, m);
    const GParamOutcome g = global_parametrize(demo.surface, o, example);
    const std::string name = method_name(m);
    write_mesh((folder / (name + ".obj")).string(), g.mapped);
    // The result as `gparam -o --distortion --summary` writes it (strictmin report reads these).
    OutputOptions files;
    files.summary = (folder / (name + ".json")).string();
    files.distortion = (folder / (name + ".txt")).string();
    write_outputs(files, gparam_summary(demo.surface, o, g, o.field_kind(), {demo.example, name + ".obj", name + ".txt"}),
                  g.measured.distortion);
    MethodRun run = method_run(name, g);
    run.order_tolerance = order_tolerance(o.solver);
    run.links = {{"summary", demo.id + "/" + name + ".json"}, {"UV mesh", demo.id + "/" + name + ".obj"}};
    outcomes.push_back(g);
    all_solved = all_solved && g.result.ok();
    char line[240];
    std::snprintf(line, sizeof line, "demo: %s  %-7s max %.5f  L2 %.5f  flipped %d  seam error %.1e  %.2f s  %s",
                  demo.id.c_str(), name.c_str(), g.measured.stats.max, g.measured.stats.l2, g.measured.stats.flipped,
                  g.seam_error, g.solve_time_s, status_name(g.result.status).c_str());
    progress(output, line);
    in.runs.push_back(std::move(run));
  }
  // The seams-and-singularities pictures on the section's colour scale (known once every
  // run is in).
  const double scale = section_colour_scale(in.runs, options.scale);
  for (std::size_t i = 0; i < in.runs.size(); ++i) {
    const std::string& name = in.runs[i].method;
    const auto pictures = write_gparam_pictures(folder.string(), name, demo.surface, outcomes[i], scale);
    in.runs[i].links.push_back({"seams and singularities", demo.id + "/" + pictures[0]});
    in.runs[i].links.push_back({"unit grid", demo.id + "/" + pictures[1]});
  }
  if (demo.quad_mesh) add_quad_mesh_demo(dir, demo, in.runs[1], output);
  return write_section(dir, in, options);
}

}  // namespace

ReportSection write_gparam_demo_section(const std::string& dir, const ComparisonOptions& options,
                                        const OutputOptions& output, bool& all_solved) {
  Mesh frame = demo_bulged_frame();
  const std::string triangles = std::to_string(frame.num_elements());
  return write_section_of(
      {.id = "gparam",
       .example = "example:bulged-frame",
       .title = "Global parametrization: a closed genus-1 surface",
       .description =
           "A polycube frame (3 x 3 x 1 cubes without the centre, " + triangles +
           " triangles) with its flat sides bulged, mapped seamlessly to the plane along its smoothest cross field "
           "(strictmin gparam, docs/gparam.md). The 8 convex corners have index +1/4, the 8 saddle corners -1/4 (they "
           "sum to the Euler characteristic 0). The distortion is the field deviation: how far each triangle's "
           "differential is from the rotation that takes the field to the u and v axes. The links show each map's "
           "seams (dark red), singularities (dots) and unit grid; the linf run also links an integer-grid map (cones "
           "and seam translations rounded to the grid, strictmin gparam --integer-grid) and its quad mesh (strictmin "
           "quads).",
       .surface = std::move(frame),
       .pin_field = true,
       .quad_mesh = true},
      dir, options, output, all_solved);
}

ReportSection write_gparam_boundary_demo_section(const std::string& dir, const ComparisonOptions& options,
                                                 const OutputOptions& output, bool& all_solved) {
  Mesh windowed = demo_bulged_frame_window();
  const std::string triangles = std::to_string(windowed.num_elements());
  return write_section_of(
      {.id = "gparam-boundary",
       .example = "example:bulged-frame-window",
       .title = "Global parametrization: a surface with boundary",
       .description =
           "The bulged frame with a square window cut in one outer side (" + triangles +
           " triangles, genus 1, one boundary loop), mapped seamlessly along its smoothest cross field, which follows "
           "the boundary (docs/gparam.md, \"Surfaces with boundary\"). The window's four corners are reflex: boundary "
           "indices of -1/4, so that with the 16 frame corners the indices sum to the Euler characteristic -1. The "
           "map's boundary is free; the cut joins the window to the singularities and the handles' loops.",
       .surface = std::move(windowed)},
      dir, options, output, all_solved);
}

}  // namespace strictmin::cli
