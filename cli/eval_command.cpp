// strictmin eval REST [MAPPED] [--measure M]: distortion of a map made by any tool.
#include <memory>

#include "commands.h"
#include "common.h"
#include "report_output.h"
#include "io/text_parse.h"
#include "strictmin/io/input_error.h"
#include "strictmin/io/mesh_io.h"
#include "strictmin/tasks/map_distortion.h"

namespace strictmin::cli {
namespace {

struct EvalArgs {
  std::string rest, mapped, measure = "auto", output;
  double uv_scale = 1;  // the UVs are multiplied by it (gparam's OBJ: the map / its edge length)
  bool uv_scale_given = false;
  OutputOptions out;
  ReportArgs report;
};

// The map as a report draws it: a deformation is the mapped mesh itself; a parametrization
// is REST carrying the map as UVs (from MAPPED's vt, or from its planar positions).
Mesh report_mesh(const Mesh& rest, const Mesh& mapped, bool parametrization) {
  if (!parametrization) return mapped;
  Mesh m = rest;
  if (mapped.has_uv()) {
    m.UV = mapped.UV;
    m.FUV = mapped.FUV;
  } else {
    m.UV = mapped.V.leftCols(2);
    m.FUV = rest.F;
  }
  return m;
}

// eval --report DIR: the given map's card (no solver: no bound, time or iterations).
std::string write_eval_report(const EvalArgs& a, const nlohmann::json& summary, const Mesh& rest, const Mesh& mapped,
                              bool parametrization, const MapDistortion& d) {
  SectionInput in;
  in.title = "The map " + input_title(a.mapped.empty() ? a.rest : a.mapped) + " of " + input_title(a.rest);
  in.description = "Task eval, " + summary.value("map_kind", std::string("deformation")) + ", measure " +
                   summary.value("measure", std::string("fd")) + ", " + std::to_string(rest.num_elements()) +
                   " elements, " + flipped_phrase(d.stats.flipped) + ".";
  describe_measure(in, summary.value("measure", std::string("fd")), "eval");
  in.rest = &rest;
  MethodRun run;
  run.method = "given";
  run.label = "given map";
  run.mapped = report_mesh(rest, mapped, parametrization);
  run.distortion = report_values(parse_measure(summary.value("measure", std::string("fd"))).value_or(Measure::Arap),
                                 d.distortion);
  run.weights = d.weights;
  run.flipped = d.stats.flipped;
  run.view_name = "view";
  run.links.emplace_back("summary.json", "summary.json");
  in.runs.push_back(std::move(run));
  return write_report_folder(a.report, summary, in.title, {in});
}

int run_eval(const EvalArgs& a) {
  const auto t0 = std::chrono::steady_clock::now();
  check_run_outputs(a.out, {{"--output", a.output}}, a.report.dir,
                    {{"the rest mesh", a.rest}, {"the mapped mesh", a.mapped}});
  const auto threads = limit_threads(a.out.threads);
  std::vector<std::string> warnings;
  const Mesh rest = read_mesh(a.rest, &warnings);
  Mesh mapped;
  if (a.mapped.empty()) {
    if (!rest.has_uv()) {
      std::string why = a.rest + ": no map to evaluate: give a MAPPED mesh, or an OBJ with texture coordinates (vt)";
      for (const auto& w : warnings)  // the reader's reason when some faces have vt and some not
        if (w.find("texture coordinates ignored") != std::string::npos) why += " (" + w + ")";
      throw InputError(why);
    }
    mapped = rest;
  } else {
    MeshReadOptions image;
    image.check_geometry = false;  // the map may flip or collapse elements: that is what eval reports
    mapped = read_mesh(a.mapped, &warnings, image);
  }
  for (const auto& w : warnings) progress(a.out, "warning: " + w);
  if (a.uv_scale_given) {
    if (!mapped.has_uv())
      throw InputError("--uv-scale: " + (a.mapped.empty() ? a.rest : a.mapped) +
                       " has no texture coordinates (vt) to scale");
    mapped.UV *= a.uv_scale;
    if (!mapped.UV.allFinite() || mapped.UV.cwiseAbs().maxCoeff() > 1e150)
      throw InputError("--uv-scale " + io_detail::exact_text(a.uv_scale) + ": the texture coordinates times it are " +
                       "beyond 1e150 (strictmin takes sizes up to 1e150)");
  } else if (mapped.has_uv() && mapped.UV.rows() != mapped.num_vertices() && a.measure != "qc" && a.measure != "iso") {
    // A seamed (per-corner) layout is most likely gparam's, whose vt are in grid units.
    progress(a.out, "warning: " + (a.mapped.empty() ? a.rest : a.mapped) +
                        " has seams (texture coordinates per corner): if it is gparam's output, its UVs are the map "
                        "divided by the edge length, so give --uv-scale EDGE_LENGTH (the summary's edge_length) "
                        "to measure the map gparam measured");
  }
  const bool parametrization = mapped.has_uv() || (rest.element_type() == ElementType::Triangle && !rest.is_planar() &&
                                                   mapped.dim() == 2);
  std::string measure_text = a.measure;
  if (measure_text == "auto") measure_text = parametrization ? "arap" : "fd";
  const auto measure = parse_measure(measure_text);
  if (!measure) throw InputError("--measure: unknown measure '" + a.measure + "' (use auto, fd, arap, asap, qc or iso)");
  // The library's reason (map_distortion) with the flag and the file it is about.
  if (*measure == Measure::FieldDeviation && parametrization && !rest.is_planar())
    throw InputError("--measure fd: " +
                     (a.mapped.empty() ? "the texture coordinates of " + a.rest + " are" : a.mapped + " is") +
                     " a parametrization of a surface, and fd of a parametrization needs its target frames (gparam's "
                     "field, param's starting map), which a map alone does not carry; evaluate it with arap, asap, qc "
                     "or iso");

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
  s["output"] = a.output;  // the -o mesh with its per-element distortion, as every task's summary says it
  s["map_kind"] = parametrization ? "parametrization" : "deformation";
  s["measure"] = measure_name(*measure);
  s["uv_scale"] = a.uv_scale;
  s["elements"] = rest.num_elements();
  s["vertices"] = rest.num_vertices();
  add_distortion_summary(s, d.stats);
  // Nothing is solved: the keys every summary has, for readers that expect them.
  s["status"] = "solved";
  s["usable"] = d.distortion.size() > 0;
  s["stop_reason"] = "evaluated the given map (no solve)";
  s["distortion_file"] = a.out.distortion;
  s["time_s"] = seconds_since(t0);
  write_outputs(a.out, s, d.distortion);
  if (!a.report.dir.empty())
    progress(a.out, "report: " + file_url(write_eval_report(a, s, rest, mapped, parametrization, d)));
  progress(a.out, "eval (" + measure_name(*measure) + "): max " + std::to_string(d.stats.max) + ", L2 " +
                      std::to_string(d.stats.l2) + ", " + flipped_phrase(d.stats.flipped, d.stats.elements));
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
  const CLI::Option* uv_scale = cmd->add_option("--uv-scale", args->uv_scale,
                  "Multiply the texture coordinates by this before measuring (> 0). gparam's OBJ holds the map "
                  "divided by its edge length: give the summary's edge_length to measure what gparam measured")
      ->check(greater_than(0))
      ->capture_default_str();
  cmd->add_option("-o,--output", args->output, "Write the mesh with per-element distortion (.ply: 'quality')");
  add_output_options(*cmd, args->out);
  add_report_options(*cmd, args->report);
  cmd->callback([args, uv_scale, &exit_code] {
    args->uv_scale_given = uv_scale->count() > 0;
    exit_code = run_eval(*args);
  });
}

}  // namespace strictmin::cli
