// strictmin demo [--out DIR]: the built-in examples (the paper's Figure 2 square, a planar
// bar, the Figure 11 tet bar) solved with L2, L-infinity and the strict minimizer, written as
// one report (DIR/index.html) that shows the paper's story side by side.
#include <filesystem>
#include <iostream>
#include <memory>

#include "commands.h"
#include "common.h"
#include "demo_gparam.h"
#include "demo_param.h"
#include "report_output.h"
#include "solver_options.h"
#include "strictmin/io/atomic_file.h"
#include "strictmin/io/input_error.h"
#include "strictmin/io/mesh_io.h"
#include "strictmin/report/html_report.h"
#include "strictmin/tasks/deform.h"
#include "strictmin/tasks/examples.h"

namespace strictmin::cli {
namespace {

namespace fs = std::filesystem;

struct DemoArgs {
  std::string out = "strictmin-demo";
  double scale = 0;  // 0: per example, auto_colour_scale
  OutputOptions output;
};

struct DemoExample {
  std::string name, title, description;
  std::vector<Method> methods;
};

std::vector<DemoExample> demo_examples() {
  const std::vector<Method> three{Method::L2, Method::Linf, Method::Relax};
  return {
      {"square", "Figure 2: the centre of a square pulled sideways",
       "A 20 \u00d7 20 grid on the unit square (800 triangles) with its whole boundary fixed; the centre vertex is "
       "moved sideways by 0.15. As in the paper's Figure 2, compare where each method puts the distortion around "
       "the pulled vertex. The strict minimizer is computed twice: by relaxation (Algorithm 3, fast) and by the "
       "direct algorithm (Algorithm 2). Both approximate it, differently: direct fixes the elements a level at a "
       "time in bands delta-k wide (Section 5.2), relaxation improves one vertex's ring at a time; so either may "
       "come out slightly ahead of the other in the strict order; neither is ever behind L-infinity.",
       {Method::L2, Method::Linf, Method::Relax, Method::Direct}},
      {"bar", "A bar bent upwards",
       "A planar 8 \u00d7 1 bar (1024 triangles): the left end is held in place; the right end is lifted by 2 and "
       "turned by 45\u00b0 about its midpoint. L2 lets the elements at the turned end take the bend.",
       three},
      {"tetbar", "Figure 11: a twisted tetrahedral bar",
       "A 4 \u00d7 1 \u00d7 1 bar of 1536 tetrahedra: one end is held, the other is moved up by 1 and turned 45\u00b0 "
       "about the bar's axis. The pictures show the bar's surface, each face coloured by the distortion of its "
       "tetrahedron, seen from the front, above and right.",
       three},
  };
}

std::vector<std::string> story() {
  return {
      "strictmin computes maps of meshes \u2014 here, deformations that move a few handle vertices \u2014 whose "
      "distortion is as low as possible where it is highest. This page solves three built-in examples with three "
      "kinds of method, as in Levi & Zorin 2014, \u201cStrict Minimizers for Geometric Optimization\u201d "
      "(Figures 2 and 11). The distortion of an element is its field deviation \u2016J \u2212 I\u2016: how far the "
      "map's differential on it is from the identity.",
      "L2 (least squares) minimizes the average distortion, and so it concentrates distortion: a few elements near "
      "the handles take the brunt (the red spots, and the thin spike at the top of its histogram).",
      "L\u221e minimizes the largest distortion. Its maximum is the lowest any map can have \u2014 the solver proves "
      "it with a certified lower bound \u2014 so it caps the distortion. But it looks only at the maximum: it leaves a "
      "large area at or near that level (the wide band at the top of its histogram).",
      "The strict minimizer keeps L\u221e's maximum and then, going down level by level, makes the area at each level "
      "as small as possible: it spreads the distortion out, with far less of the mesh near the maximum. Its average "
      "(L2) distortion is a little higher than L2's \u2014 the price of the best worst case.",
      "Reading a histogram: distortion goes up the vertical axis, coloured like the pictures; the horizontal axis is "
      "the share of the mesh's area in each distortion bin, on a log scale. The higher a curve reaches, the worse the "
      "method's worst element; the further right a curve is near the top, the more of the mesh is badly distorted.",
  };
}

nlohmann::json run_summary(const std::string& example, const SolverOptions& options, const DeformOutcome& d,
                           const std::string& output, const std::string& distortion_file, int handles) {
  nlohmann::json s;
  s["task"] = "deform";
  s["input"] = "example:" + example;
  s["output"] = output;
  s["distortion_file"] = distortion_file;
  s["method"] = method_name(options.method);
  s["measure"] = "fd";
  s["elements"] = d.deformed.num_elements();
  s["vertices"] = d.deformed.num_vertices();
  s["handles"] = handles;
  s["dimension"] = d.problem.image_dim;
  add_distortion_summary(s, d.measured.stats);
  add_status_summary(s, d.result);
  add_solver_summary(s, options, d.result);
  s["solver_time_s"] = d.result.time_s;
  return s;
}

int run_demo(const DemoArgs& a) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto threads = limit_threads(a.output.threads);
  open_report_folder(a.out);
  std::error_code ec;

  HtmlReport report;
  report.title = "strictmin demo: L2 concentrates distortion, L\u221e caps it, the strict minimizer spreads it";
  report.intro = story();
  report.scale = a.scale > 0 ? a.scale : kDefaultColourScale;
  ComparisonOptions options;
  options.scale = a.scale;
  bool all_solved = true;
  for (const DemoExample& ex : demo_examples()) {
    const Example example = make_example(ex.name);
    SectionInput in;
    in.id = ex.name;
    in.title = ex.title;
    in.description = ex.description;
    in.rest = &example.mesh;
    in.handles = example.handles;
    const fs::path folder = fs::path(a.out) / ex.name;
    fs::create_directories(folder, ec);
    if (ec) throw InputError("cannot create " + folder.string() + ": " + ec.message());
    for (const Method m : ex.methods) {
      DeformOptions opt;
      opt.solver.method = m;
      const DeformOutcome d = deform(example.mesh, example.handles, opt);
      const std::string name = method_name(m);
      const bool tets = example.mesh.element_type() == ElementType::Tetrahedron;
      const std::string mesh_file = name + (tets ? ".mesh" : ".obj"), dist_file = name + ".txt";
      // The result as `deform -o --distortion --summary` writes it (strictmin report reads these).
      write_mesh((folder / mesh_file).string(), d.deformed);
      OutputOptions files;
      files.summary = (folder / (name + ".json")).string();
      files.distortion = (folder / dist_file).string();
      write_outputs(files, run_summary(ex.name, opt.solver, d, mesh_file, dist_file,
                                       static_cast<int>(example.handles.size())),
                    d.measured.distortion);
      MethodRun run = method_run(name, d, opt.measure);
      run.order_tolerance = order_tolerance(opt.solver);
      run.links = {{"summary", ex.name + "/" + name + ".json"},
                   {"mesh", ex.name + "/" + mesh_file},
                   {"distortion", ex.name + "/" + dist_file}};
      all_solved = all_solved && d.result.ok();
      char line[200];
      std::snprintf(line, sizeof line, "demo: %-7s %-7s max %.5f  L2 %.5f  flipped %d  %.2f s  %s", ex.name.c_str(),
                    name.c_str(), d.measured.stats.max, d.measured.stats.l2, d.measured.stats.flipped, d.result.time_s,
                    status_name(d.result.status).c_str());
      progress(a.output, line);
      in.runs.push_back(std::move(run));
    }
    report.sections.push_back(write_section(a.out, in, options));
  }
  report.sections.push_back(write_param_demo_section(a.out, options, a.output, all_solved));
  report.sections.push_back(write_gparam_demo_section(a.out, options, a.output, all_solved));
  report.sections.push_back(write_gparam_boundary_demo_section(a.out, options, a.output, all_solved));
  char footer[160];
  std::snprintf(footer, sizeof footer, "Made by `strictmin demo` in %.1f s. Compare your own results with `strictmin "
                "report DIR --run RESULT.json ...` (docs/report.md).", seconds_since(t0));
  report.footer = footer;
  const std::string index = (fs::path(a.out) / "index.html").string();
  write_index_html(index, report);
  std::cout << "demo: open " << file_url(index) << " in a browser" << std::endl;
  return all_solved ? kExitSuccess : kExitNotConverged;
}

}  // namespace

void add_demo_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<DemoArgs>();
  CLI::App* cmd = app.add_subcommand(
      "demo",
      "Solve the built-in examples (deformations: the paper's Figure 2 square, a bar, the Figure 11 tet bar; a "
      "spherical cap parametrized under ARAP; a closed genus-1 frame parametrized seamlessly along its cross field, and the same frame with a window cut in it, a surface with boundary) "
      "with L2, L-infinity and the strict minimizer, and write a report to open in a browser: colour-coded "
      "pictures, log-scale histograms and the strict-order verdicts side by side.");
  cmd->add_option("--out,-o", args->out, "Folder for the report (created when missing)")->capture_default_str();
  cmd->add_option("--scale", args->scale,
                  "The distortion shown red (dark blue is 0); default: per example, 1.5 times its least maximum "
                  "distortion, rounded up (the paper uses 0.6)")
      ->check(greater_than(0));
  cmd->add_flag("--quiet,-q", args->output.quiet, "No progress messages on stderr");
  cmd->add_option("--threads", args->output.threads, "Number of threads (default: all cores)")
      ->check(at_least(0));
  cmd->callback([args, &exit_code] { exit_code = run_demo(*args); });
}

}  // namespace strictmin::cli
