// strictmin eval REST [MAPPED] [--measure M]: distortion of a map made by any tool.
#include <memory>

#include "commands.h"
#include "common.h"
#include "strictmin/io/input_error.h"
#include "strictmin/io/mesh_io.h"
#include "strictmin/tasks/map_distortion.h"

namespace strictmin::cli {
namespace {

struct EvalArgs {
  std::string rest, mapped, measure = "auto", output;
  OutputOptions out;
};

int run_eval(const EvalArgs& a) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto threads = limit_threads(a.out.threads);
  std::vector<std::string> warnings;
  const Mesh rest = read_mesh(a.rest, &warnings);
  Mesh mapped;
  if (a.mapped.empty()) {
    if (!rest.has_uv())
      throw InputError(a.rest + ": no map to evaluate: give a MAPPED mesh, or an OBJ with texture coordinates (vt)");
    mapped = rest;
  } else {
    MeshReadOptions image;
    image.check_geometry = false;  // the map may flip or collapse elements: that is what eval reports
    mapped = read_mesh(a.mapped, &warnings, image);
  }
  for (const auto& w : warnings) progress(a.out, "warning: " + w);
  const bool parametrization = mapped.has_uv() || (rest.element_type() == ElementType::Triangle && !rest.is_planar() &&
                                                   mapped.dim() == 2);
  std::string measure_text = a.measure;
  if (measure_text == "auto") measure_text = parametrization ? "arap" : "fd";
  const auto measure = parse_measure(measure_text);
  if (!measure) throw InputError("unknown measure '" + a.measure + "' (use auto, fd, arap, asap, qc or iso)");

  const MapDistortion d = map_distortion(rest, mapped, *measure, a.rest, a.mapped.empty() ? a.rest : a.mapped);
  if (!a.output.empty()) {
    MeshWriteOptions w;
    w.element_quality = &d.distortion;
    write_mesh(a.output, parametrization ? rest : mapped, w);
  }
  nlohmann::json s;
  s["task"] = "eval";
  s["method"] = "given";
  s["input"] = a.rest;
  s["map"] = a.mapped.empty() ? a.rest : a.mapped;
  s["map_kind"] = parametrization ? "parametrization" : "deformation";
  s["measure"] = measure_name(*measure);
  s["elements"] = rest.num_elements();
  s["vertices"] = rest.num_vertices();
  s["max_distortion"] = number_or_null(d.stats.max);
  s["max_element"] = d.stats.max_element;
  s["l2_distortion"] = number_or_null(d.stats.l2);
  s["mean_distortion"] = number_or_null(d.stats.mean);
  s["flipped"] = d.stats.flipped;
  s["status"] = "solved";
  s["time_s"] = seconds_since(t0);
  write_outputs(a.out, s, d.distortion);
  progress(a.out, "eval (" + measure_name(*measure) + "): max " + std::to_string(d.stats.max) + ", L2 " +
                      std::to_string(d.stats.l2) + ", " + std::to_string(d.stats.flipped) + " flipped of " +
                      std::to_string(d.stats.elements));
  return kExitSuccess;
}

}  // namespace

void add_eval_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<EvalArgs>();
  CLI::App* cmd = app.add_subcommand(
      "eval",
      "Measure the distortion of a map made by any tool: REST and MAPPED share their connectivity, or REST alone is "
      "an OBJ with texture coordinates (its UV layout is the map).");
  cmd->add_option("rest", args->rest, "Rest mesh (.obj, .off, .mesh)")->required();
  cmd->add_option("mapped", args->mapped, "Mapped mesh: same elements; an OBJ with vt counts as a UV map of REST");
  cmd->add_option("--measure", args->measure,
                  "fd, arap, asap, qc or iso; auto = arap for parametrizations, fd for deformations")
      ->capture_default_str();
  cmd->add_option("-o,--output", args->output, "Write the mesh with per-element distortion (.ply: 'quality')");
  add_output_options(*cmd, args->out);
  cmd->callback([args, &exit_code] { exit_code = run_eval(*args); });
}

}  // namespace strictmin::cli
