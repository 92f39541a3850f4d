#include "demo_param.h"

#include <cstdio>
#include <filesystem>

#include "report_output.h"
#include "common.h"
#include "strictmin/io/mesh_io.h"
#include "strictmin/mesh/surface_generators.h"
#include "strictmin/tasks/param.h"

namespace strictmin::cli {

Mesh demo_spherical_cap() { return make_spherical_cap(12, 36, 1.3); }

ReportSection write_param_demo_section(const std::string& dir, const ComparisonOptions& options,
                                       const OutputOptions& output, bool& all_solved) {
  namespace fs = std::filesystem;
  const Mesh cap = demo_spherical_cap();
  SectionInput in;
  in.id = "param";
  in.title = "Parametrization: a spherical cap flattened";
  in.description =
      "A spherical cap (828 triangles, up to 75\u00b0 from the pole) mapped to the plane with a free boundary, "
      "starting from Tutte's embedding. No flat map of a sphere is an isometry, so every method stretches it; the "
      "distortion is ARAP (distance of each triangle's differential to the closest rotation). L2 ARAP (Liu et al. "
      "2008) stretches the rim most; L\u221e ARAP and the strict minimizer spread the stretch over the cap. The "
      "checkerboards show the maps: square checks mean little distortion.";
  in.measure = "ARAP distortion";
  in.rest = &cap;
  fs::create_directories(fs::path(dir) / "param");
  for (const Method m : {Method::L2, Method::Linf, Method::Relax}) {
    ParamOptions o;
    o.solver.method = m;
    const ParamOutcome p = parametrize(cap, o, "spherical cap");
    const std::string name = method_name(m);
    const fs::path folder = fs::path(dir) / "param";
    write_mesh((folder / (name + ".obj")).string(), p.mapped);
    // The result as `param -o --distortion --summary` writes it (strictmin report reads these).
    OutputOptions files;
    files.summary = (folder / (name + ".json")).string();
    files.distortion = (folder / (name + ".txt")).string();
    write_outputs(files, param_summary(cap, o, p, {"example:spherical-cap", name + ".obj", name + ".txt"}),
                  p.measured.distortion);
    MethodRun run = method_run(name, p, o.measure);
    run.order_tolerance = order_tolerance(o.solver);
    run.links = {{"summary", "param/" + name + ".json"}, {"UV mesh", "param/" + name + ".obj"}};
    all_solved = all_solved && p.result.ok();
    char line[200];
    std::snprintf(line, sizeof line, "demo: param   %-7s max %.5f  L2 %.5f  flips %d  %.2f s  %s", name.c_str(),
                  p.measured.stats.max, p.measured.stats.l2, p.flips, p.result.time_s,
                  status_name(p.result.status).c_str());
    progress(output, line);
    in.runs.push_back(std::move(run));
  }
  return write_section(dir, in, options);
}

}  // namespace strictmin::cli
