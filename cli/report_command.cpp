// strictmin report DIR [--scale S] --run SUMMARY.json ...: a side-by-side report of results
// already computed. Each result is a summary JSON written by `deform --summary` (or `eval
// --summary`): its `output` (or `map`) is the mapped mesh, its `distortion_file` the
// per-element distortion (`--distortion`), its `input` the rest mesh ("example:NAME" or a
// file). Results with the same input are compared in one section.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <sstream>

#include "commands.h"
#include "common.h"
#include "demo_gparam.h"
#include "demo_param.h"
#include "report_output.h"
#include "strictmin/io/atomic_file.h"
#include "strictmin/io/input_error.h"
#include "strictmin/io/mesh_io.h"
#include "strictmin/measures/measures.h"
#include "strictmin/problem/problem.h"
#include "strictmin/report/html_report.h"
#include "strictmin/tasks/examples.h"
#include "strictmin/tasks/map_distortion.h"
#include "io/text_parse.h"

namespace strictmin::cli {
namespace {

namespace fs = std::filesystem;

struct ReportCommandArgs {
  std::string dir;
  std::vector<std::string> runs, positional;
  double scale = kDefaultColourScale;
  std::string title = "strictmin report";
  OutputOptions out;
};

// A relative path from a summary: beside the summary when it exists there, else as given
// (relative to the current folder). In that order, a run made in its own folder keeps its
// own files when another run's of the same name sit in the current folder (it read those).
std::string resolve(const std::string& path, const std::string& summary_file) {
  if (path.empty() || fs::path(path).is_absolute()) return path;
  const fs::path beside = fs::path(summary_file).parent_path() / path;
  return fs::exists(beside) ? beside.string() : path;
}

Eigen::VectorXd read_distortion_file(const std::string& path, int expected) {
  std::ifstream in(path);
  if (!in) throw InputError("cannot read " + path + ": " + std::strerror(errno));
  std::vector<double> values;
  std::string token;
  while (in >> token) {
    char* end = nullptr;
    const double v = std::strtod(token.c_str(), &end);
    if (end == token.c_str() || *end != '\0')
      throw InputError(located(path, static_cast<long>(values.size()) + 1, "not a number: '" + token + "'"));
    // A distortion is >= 0 or +inf (a flipped element under qc / iso); NaN or a negative value
    // is not one, and would make the verdicts meaningless.
    if (std::isnan(v) || v < 0)
      throw InputError(located(path, static_cast<long>(values.size()) + 1, "not a distortion (>= 0 or inf): '" + token + "'"));
    values.push_back(v);
  }
  if (static_cast<int>(values.size()) != expected)
    throw InputError(path + ": " + std::to_string(values.size()) + " values for " + std::to_string(expected) +
                     " elements of the mapped mesh");
  return Eigen::Map<Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

// Vertex positions of a result whose elements may be flipped (an L2 map can fold over, and
// read_mesh rejects inconsistent orientation): OBJ `v` lines, MEDIT `Vertices`, OFF vertices.
Eigen::MatrixXd read_positions(const std::string& path) {
  const std::string text = io_detail::read_text_file(path);  // "cannot read PATH: the reason"
  io_detail::LineReader lines(text);  // '\n', "\r\n" or '\r' line ends
  std::string_view view;
  const std::string ext = lowercase_extension(path);
  if (ext != ".obj" && ext != ".off" && ext != ".mesh")
    throw InputError(path + ": the report reads results written as .obj, .off or .mesh ('" + ext +
                     "' is written by the tasks but not read back; run the task with -o OUT.obj)");
  std::vector<Eigen::Vector3d> points;
  if (ext == ".obj") {
    while (lines.next(view)) {
      std::istringstream ls{std::string(view)};
      std::string key;
      Eigen::Vector3d p = Eigen::Vector3d::Zero();
      if (ls >> key && key == "v" && ls >> p.x() >> p.y()) {
        ls >> p.z();
        points.push_back(p);
      }
    }
  } else {
    std::vector<std::string> tokens;  // whitespace-separated, comments dropped
    while (lines.next(view)) {
      std::istringstream ls{std::string(view.substr(0, view.find('#')))};
      for (std::string t; ls >> t;) tokens.push_back(t);
    }
    std::size_t i = 0, n = 0, per = 3;
    try {
      if (ext == ".mesh") {
        while (i < tokens.size() && tokens[i] != "Vertices") ++i;
        if (i + 1 < tokens.size()) n = std::stoul(tokens[i + 1]), i += 2;
        per = 4;  // x y z ref
      } else if (ext == ".off" && !tokens.empty()) {
        i = 1;
        if (i < tokens.size()) n = std::stoul(tokens[i]);
        i += 3;
      }
      for (std::size_t k = 0; k < n && i + 3 <= tokens.size(); ++k, i += per)
        points.emplace_back(std::stod(tokens[i]), std::stod(tokens[i + 1]), std::stod(tokens[i + 2]));
    } catch (const std::logic_error&) {  // std::stod / std::stoul: not a number, or out of range
      throw InputError(path + ": a vertex count or coordinate is not a number");
    }
  }
  if (points.empty()) throw InputError(path + ": no vertices found");
  Eigen::MatrixXd V(points.size(), 3);
  for (std::size_t k = 0; k < points.size(); ++k) V.row(static_cast<Eigen::Index>(k)) = points[k].transpose();
  return V;
}

// The input as one absolute path (a built-in example as its name).
std::string input_location(const std::string& input, const std::string& file) {
  if (input.empty() || input.rfind("example:", 0) == 0) return input;
  std::error_code ec;
  const fs::path resolved = fs::weakly_canonical(fs::absolute(resolve(input, file), ec), ec);
  return ec ? input : resolved.string();
}

// Runs are compared (ranked, one colour scale, one histogram) only when they map one problem:
// the same input file (wherever the summaries are: two "m.obj" in two folders are two
// meshes), task, measure and element count, and the same handles (their count), field and
// edge length where the task has them.
std::string problem_key(const nlohmann::json& s, const std::string& location) {
  std::string key = location;
  for (const char* part : {"task", "measure", "elements", "handles", "field", "edge_length"})
    key += std::string("\n") + (s.contains(part) ? s[part].dump() : std::string("-"));
  return key;
}

// A summary is checked against its own files before anything of it is shown: a hand-edited or
// mismatched summary would otherwise put a wrong count, maximum or bound on the page (a
// "certified lower bound" above the map's own maximum, a negative qc distortion).
// tolerance: relative, for max_distortion (a map read back from its file carries its digits'
// round-off into a recomputed distortion).
void check_summary_figures(const nlohmann::json& s, const std::string& file, const std::string& distortion_path,
                           const Eigen::VectorXd& values, const std::string& measure, double tolerance = 1e-9) {
  auto number = [&](const char* key) { return s.contains(key) && s[key].is_number() ? s[key].get<double>() : NAN; };
  double file_max = 0;
  for (double v : values) file_max = std::max(file_max, v);
  const double summary_max = number("max_distortion");
  if (std::isfinite(summary_max) && std::isfinite(file_max) &&
      std::abs(summary_max - file_max) > tolerance * std::max(1.0, std::abs(file_max)))
    throw InputError(file + ": max_distortion " + shown_number(summary_max, 10) + " disagrees with " +
                     distortion_path + ", whose largest value is " + shown_number(file_max, 10));
  const double bound = number("lower_bound");
  if (std::isfinite(bound) && bound > file_max + 1e-6 * std::max(1.0, std::abs(file_max)))
    throw InputError(file + ": lower_bound " + shown_number(bound, 10) + " is above the map's own maximum " +
                     shown_number(file_max, 10) + " (a lower bound on the least maximum cannot exceed a map's)");
  if ((measure == "qc" || measure == "iso") && values.size() > 0 && values.minCoeff() < 1 - 1e-9)
    throw InputError(distortion_path + ": a " + measure + " distortion is at least 1, and this file has " +
                     shown_number(values.minCoeff(), 10) + " (a distortion file of another measure?)");
}

// The summary's words that name what it is: a task this report shows (interp's frames are
// refused later with their own message) and a status the tools write. Others were taken
// without a word ("task": "banana" exit 0).
void check_summary_words(const nlohmann::json& s, const std::string& file) {
  if (s.contains("task")) {
    const std::string task = s["task"].is_string() ? s["task"].get<std::string>() : std::string();
    static const std::set<std::string> tasks{"deform", "param", "gparam", "eval", "interp", "quads"};
    if (!tasks.count(task))
      throw InputError(file + ": unknown task " + s["task"].dump() + " (report shows the summaries of deform, param, "
                              "gparam and eval)");
  }
  if (s.contains("status")) {
    const std::string status = s["status"].is_string() ? s["status"].get<std::string>() : std::string();
    bool known = false;
    for (SolveStatus x : {SolveStatus::Solved, SolveStatus::AlmostSolved, SolveStatus::MaxIterations,
                          SolveStatus::Stalled, SolveStatus::NumericalError, SolveStatus::Infeasible})
      known = known || status == status_name(x);
    if (!known)
      throw InputError(file + ": unknown status " + s["status"].dump() + " (docs/formats.md, \"Statuses\")");
  }
  // The verdicts tie direct's values within it: a bad one would decide them.
  if (s.contains("delta_k") && !(s["delta_k"].is_number() && s["delta_k"].get<double>() > 0 &&
                                 std::isfinite(s["delta_k"].get<double>())))
    throw InputError(file + ": delta_k " + s["delta_k"].dump() + " is not a positive number (direct's --delta-k)");
}

// The summary's counts against the map's.
void check_summary_counts(const nlohmann::json& s, const std::string& file, const std::string& mapped_path,
                          int elements) {
  if (s.contains("elements") && s["elements"].is_number() && s["elements"].get<double>() != elements)
    throw InputError(file + ": elements " + s["elements"].dump() + " disagrees with " + mapped_path + ", which has " +
                     std::to_string(elements));
  if (s.contains("flipped") && s["flipped"].is_number() &&
      !(s["flipped"].get<double>() >= 0 && s["flipped"].get<double>() <= elements))
    throw InputError(file + ": flipped " + s["flipped"].dump() + " is not a count of the map's " +
                     std::to_string(elements) + " elements");
}

// The summary's `flipped` against the map's own flipped elements (det J <= 0, collapsed
// ones included: the same count every task makes), where the rest mesh is at hand: a
// hand-edited or mismatched summary put its own count on the card.
void check_summary_flips(const nlohmann::json& s, const std::string& file, const Mesh& rest, const Mesh& map,
                         const std::string& rest_name, const std::string& mapped_path) {
  if (!s.contains("flipped") || !s["flipped"].is_number()) return;  // null: a surface mapped in 3D
  const Mesh mapped = map.has_uv() ? map : to_planar(map);
  const int flipped = map_distortion(to_planar(rest), mapped, Measure::Arap, rest_name, mapped_path).stats.flipped;
  if (flipped >= 0 && s["flipped"].get<double>() != flipped)
    throw InputError(file + ": flipped " + s["flipped"].dump() + " disagrees with " + mapped_path + ", which has " +
                     std::to_string(flipped) + " flipped elements");
}

struct LoadedRun {
  std::string file;     // the summary file
  std::string input;    // the summary's input (names the section)
  std::string location; // the input as one path (input_location)
  std::string problem;  // what makes two runs rivals: one section each (problem_key)
  nlohmann::json summary;
  MethodRun run;
  std::shared_ptr<Mesh> rest;
  std::vector<Handle> handles;
};

// The rest mesh and handles of "example:NAME": deform's examples, and the surfaces of demo's
// param and gparam sections, whose summaries say "example:spherical-cap",
// "example:bulged-frame" and "example:bulged-frame-window".
void load_example_rest(const std::string& name, LoadedRun& r) {
  if (name == "spherical-cap" || name == "bulged-frame" || name == "bulged-frame-window") {
    r.rest = std::make_shared<Mesh>(name == "spherical-cap"  ? demo_spherical_cap()
                                    : name == "bulged-frame" ? demo_bulged_frame()
                                                             : demo_bulged_frame_window());
    return;
  }
  Example ex = make_example(name);
  r.rest = std::make_shared<Mesh>(std::move(ex.mesh));
  r.handles = std::move(ex.handles);
}

LoadedRun load_run(const std::string& file, const OutputOptions& out) {
  std::ifstream in(file);
  if (!in) throw InputError("cannot read " + file + ": " + std::strerror(errno));
  LoadedRun r;
  try {
    r.summary = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file + ": not a JSON summary: " + e.what());
  }
  const auto& s = r.summary;
  if (!s.is_object()) throw InputError(file + ": not a JSON summary (an object expected)");
  auto text = [&](const char* key) {
    return s.contains(key) && s[key].is_string() ? s[key].get<std::string>() : std::string();
  };
  auto number = [&](const char* key) {
    return s.contains(key) && s[key].is_number() ? s[key].get<double>() : std::nan("");
  };
  check_summary_words(s, file);
  r.file = file;
  r.input = text("input");
  r.location = input_location(r.input, file);
  r.problem = problem_key(s, r.location);
  const std::string mapped_path = resolve(text("map").empty() ? text("output") : text("map"), file);
  if (mapped_path.empty() && text("task") == "interp")
    throw InputError(file + ": an interp summary (several frames) is not one result; its frames are in interp's own "
                     "report (strictmin interp ... --report DIR)");
  if (mapped_path.empty())
    throw InputError(file + ": the summary names no output mesh (run the task with -o OUT.obj, or .mesh for tets)");
  // The rest mesh: a built-in example, or the input file.
  if (r.input.rfind("example:", 0) == 0) {
    load_example_rest(r.input.substr(8), r);
  } else if (!r.input.empty() && fs::exists(resolve(r.input, file))) {
    r.rest = std::make_shared<Mesh>(read_mesh(resolve(r.input, file)));
  }
  std::vector<std::string> warnings;
  try {
    r.run.mapped = read_mesh(mapped_path, &warnings);
  } catch (const InputError& e) {
    // A map with flipped elements is a result too: take its positions over the rest mesh.
    if (!r.rest) throw;
    const Eigen::MatrixXd V = read_positions(mapped_path);
    if (V.rows() != r.rest->num_vertices()) throw;
    r.run.mapped = *r.rest;
    r.run.mapped.V = V.leftCols(r.rest->dim());
  }
  for (const auto& w : warnings) progress(out, "warning: " + w);
  const int elements = r.run.mapped.num_elements();
  check_summary_counts(s, file, mapped_path, elements);
  if (r.rest && r.rest->num_elements() != elements)  // not one map's rest and image (it was filed under the input's section)
    throw InputError(file + ": its input '" + r.input + "' has " + std::to_string(r.rest->num_elements()) +
                     " elements and its output '" + mapped_path + "' " + std::to_string(elements) +
                     ": they are not one map's rest and image (an edited summary, or a file replaced since the run?)");
  if (r.rest) check_summary_flips(s, file, *r.rest, r.run.mapped, r.input, mapped_path);

  const std::string measure_text = text("measure").empty() ? "fd" : text("measure");
  // "-": the task wrote its distortions to stdout, so there is no file to read.
  const std::string distortion_name = text("distortion_file") == "-" ? std::string() : text("distortion_file");
  const std::string distortion_path = resolve(distortion_name, file);
  if (!distortion_path.empty()) {
    r.run.distortion = read_distortion_file(distortion_path, elements);
    check_summary_figures(s, file, distortion_path, r.run.distortion, measure_text);
    if (const auto m = parse_measure(measure_text)) r.run.distortion = report_values(*m, r.run.distortion);
  } else if (r.rest) {
    const auto measure = parse_measure(measure_text);
    if (!measure) throw InputError(file + ": unknown measure '" + measure_text + "'");
    Mesh mapped = r.run.mapped;
    // A parametrization's fd is against the task's own frames (gparam's field, param's
    // starting map), which the files do not carry: only the task's distortion file has it.
    if (*measure == Measure::FieldDeviation && (mapped.has_uv() || text("task") == "param" || text("task") == "gparam"))
      throw InputError(file + ": the summary names no distortion_file, and a parametrization's fd (against the "
                              "task's frames) cannot be recomputed from the map: run the task with --distortion FILE");
    if (!mapped.has_uv()) mapped = to_planar(mapped);
    // gparam's OBJ holds the map divided by its edge length h (UV in grid units); its
    // distortion is the map's against unit targets, so the UVs are scaled back by h. eval
    // measured its map's UVs times its --uv-scale.
    if (text("task") == "eval" && std::isfinite(number("uv_scale")) && number("uv_scale") > 0 && mapped.has_uv())
      mapped.UV *= number("uv_scale");
    if (text("task") == "gparam") {
      const double h = number("edge_length");
      if (!(h > 0) || !std::isfinite(h))
        throw InputError(file + ": a gparam summary needs its edge_length (a positive number) to recompute the "
                                "distortion from " + mapped_path + ": run the task with --distortion FILE");
      mapped.UV *= h;
    }
    const Eigen::VectorXd recomputed = map_distortion(to_planar(*r.rest), mapped, *measure, r.input, mapped_path).distortion;
    check_summary_figures(s, file, mapped_path + " (its distortion recomputed)", recomputed, measure_text, 1e-6);
    r.run.distortion = report_values(*measure, recomputed);
    progress(out, "warning: " + file + ": no distortion_file (run with --distortion FILE); recomputed from " +
                      mapped_path);
  } else {
    throw InputError(file + ": the summary names no distortion_file (run the task with --distortion FILE) and its "
                            "input mesh '" + r.input + "' cannot be read to recompute it");
  }
  if (r.rest) {
    r.run.weights = make_problem(*r.rest).weights;
  } else {
    r.run.weights = make_problem(r.run.mapped.has_uv() ? r.run.mapped : to_planar(r.run.mapped)).weights.cwiseAbs();
    progress(out, "warning: " + file + ": input mesh not found; histogram areas are the output's");
  }
  r.run.method = text("method").empty() ? "result" : text("method");
  // null: not defined (a surface in 3D); absent (older summaries): taken as none.
  r.run.flipped = s.contains("flipped") && s["flipped"].is_number_integer() ? s["flipped"].get<int>()
                  : s.contains("flipped") && s["flipped"].is_null()     ? -1
                                                                        : 0;
  // Certified for the convex measure only (docs/report.md); under arap / asap it is null.
  r.run.lower_bound = measure_text == "fd" ? number("lower_bound") : std::nan("");
  r.run.time_s = std::isfinite(number("solver_time_s")) ? number("solver_time_s") : number("time_s");
  r.run.status = text("status").empty() ? "solved" : text("status");
  r.run.message = text("message");
  // direct is compared with the others at its delta-k (a summary from before the key: the
  // default, 1e-3).
  if (r.run.method == "direct") r.run.order_tolerance = std::isfinite(number("delta_k")) ? number("delta_k") : 1e-3;
  return r;
}

std::string section_id(const std::string& input, std::set<std::string>& used) {
  std::string id;
  for (char c : input_title(input)) id += std::isalnum(static_cast<unsigned char>(c)) ? c : '-';
  if (id.empty()) id = "results";
  std::string unique = id;
  for (int k = 2; used.count(unique); ++k) unique = id + "-" + std::to_string(k);
  used.insert(unique);
  return unique;
}

// The section's title: its input, and where several sections share the input (another
// measure, task, field...), what sets this one apart.
std::string section_title(const LoadedRun& run, const std::vector<LoadedRun>& all) {
  bool shared = false, elsewhere = false;
  for (const auto& r : all) {
    if (r.input != run.input || r.problem == run.problem) continue;
    shared = true;
    elsewhere = elsewhere || r.location != run.location;
  }
  if (!shared) return input_title(run.input);
  if (elsewhere) return run.location;  // two files of one name: the path tells them apart
  const std::string title = input_title(run.input);
  const auto& s = run.summary;
  auto part = [&](const char* key) {
    return s.contains(key) && s[key].is_string() ? s[key].get<std::string>() : std::string();
  };
  std::string what = part("task");
  if (!part("measure").empty()) what += (what.empty() ? "" : ", ") + std::string("measure ") + part("measure");
  if (s.contains("handles") && s["handles"].is_number()) what += ", " + s["handles"].dump() + " handles";
  if (!part("field").empty()) what += ", field " + part("field");
  if (s.contains("edge_length") && s["edge_length"].is_number()) what += ", edge length " + s["edge_length"].dump();
  return title + " (" + what + ")";
}

// One summary given twice would be compared with itself as if it were two runs.
void refuse_repeated_summaries(const std::vector<std::string>& files) {
  for (std::size_t j = 0; j < files.size(); ++j)
    for (std::size_t i = 0; i < j; ++i)
      if (same_file(files[i], files[j]))
        throw InputError(files[j] + ": this summary is given twice (also as " + files[i] + ")");
}

int run_report(ReportCommandArgs a) {
  a.runs.insert(a.runs.end(), a.positional.begin(), a.positional.end());
  if (a.runs.empty()) throw InputError("report needs at least one result: --run SUMMARY.json (written by --summary)");
  refuse_repeated_summaries(a.runs);
  std::vector<LoadedRun> loaded;
  for (const auto& f : a.runs) loaded.push_back(load_run(f, a.out));

  // Sections in order of first appearance of each problem (problem_key).
  std::vector<std::string> problems;
  for (const auto& r : loaded)
    if (std::find(problems.begin(), problems.end(), r.problem) == problems.end()) problems.push_back(r.problem);
  open_report_folder(a.dir);
  std::error_code ec;

  HtmlReport report;
  report.title = a.title;
  report.scale = a.scale;
  report.intro.push_back(
      "Results compared side by side: each picture is one method's map with every element coloured by its "
      "distortion, each histogram shows how the distortion is spread over the mesh, and the strict-order verdict says "
      "which of two maps is less distorting in the sense of the paper (lower maximum first, then less area at each "
      "level going down).");
  ComparisonOptions options;
  options.scale = a.scale;
  std::set<std::string> used_ids;
  bool all_solved = true;
  for (const auto& problem : problems) {
    const LoadedRun& first =
        *std::find_if(loaded.begin(), loaded.end(), [&](const LoadedRun& r) { return r.problem == problem; });
    const std::string input = first.input;
    // A method run twice: each run named by its file's name, or by its path where two such
    // files share a name (in two folders).
    std::map<std::string, int> runs_of_method;
    std::map<std::pair<std::string, std::string>, int> same_name;  // (method, file name) -> runs
    for (const auto& r : loaded)
      if (r.problem == problem) {
        ++runs_of_method[r.run.method];
        ++same_name[{r.run.method, fs::path(r.file).filename().string()}];
      }
    SectionInput in;
    in.id = section_id(input, used_ids);
    in.title = section_title(first, loaded);
    std::set<std::string> stems;
    std::string measure;
    for (std::size_t i = 0; i < loaded.size(); ++i) {
      LoadedRun& r = loaded[i];
      if (r.problem != problem) continue;
      if (!in.rest && r.rest) {
        in.rest = r.rest.get();
        in.handles = r.handles;
      }
      if (measure.empty()) measure = r.summary.value("measure", std::string("fd"));
      std::string stem = r.run.method;
      for (int k = 2; stems.count(stem) || stem == "input" || stem == "histogram"; ++k)
        stem = r.run.method + "-" + std::to_string(k);
      stems.insert(stem);
      r.run.view_name = stem;
      // Two runs of one method on one problem (other options): told apart by their files.
      if (runs_of_method[r.run.method] > 1) {
        const std::string name = fs::path(r.file).filename().string();
        r.run.label = method_label(r.run.method) + " (" + (same_name[{r.run.method, name}] > 1 ? r.file : name) + ")";
      }
      fs::create_directories(fs::path(a.dir) / in.id, ec);
      if (ec) throw InputError("cannot create " + (fs::path(a.dir) / in.id).string() + ": " + ec.message());
      write_file_atomically((fs::path(a.dir) / in.id / (stem + ".json")).string(),
                            [&](std::ostream& os) { os << r.summary.dump(2) << '\n'; });
      r.run.links.emplace_back("summary", in.id + "/" + stem + ".json");
      all_solved = all_solved && r.run.status == "solved";
      in.runs.push_back(r.run);
    }
    describe_measure(in, measure, first.summary.value("task", std::string("deform")));
    in.description = std::to_string(in.runs.size()) + " result" + (in.runs.size() == 1 ? "" : "s") + " for input " +
                     (input.empty() ? std::string("(unknown)") : input) + ".";
    report.sections.push_back(write_section(a.dir, in, options));
  }
  report.footer = "Made by strictmin report from " + std::to_string(a.runs.size()) + " result summaries.";
  const std::string index = (fs::path(a.dir) / "index.html").string();
  write_index_html(index, report);
  std::cout << "report: open " << file_url(index) << " in a browser" << std::endl;
  return all_solved ? kExitSuccess : kExitNotConverged;
}

}  // namespace

void add_report_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ReportCommandArgs>();
  CLI::App* cmd = app.add_subcommand(
      "report",
      "Compare results already computed, side by side, in a folder of static files (open DIR/index.html): "
      "colour-coded pictures, an overlaid log-scale histogram and the strict-order verdicts.\n"
      "Each result is a summary JSON written with --summary, by a run that also wrote its mesh (-o) and its "
      "distortion (--distortion), e.g.\n"
      "  strictmin deform --example square --method l2 -o l2.obj --distortion l2.txt --summary l2.json\n"
      "  strictmin deform --example square --method linf -o linf.obj --distortion linf.txt --summary linf.json\n"
      "  strictmin report out --run l2.json --run linf.json");
  cmd->add_option("dir", args->dir, "Folder to write the report into (created when missing)")->required();
  cmd->add_option("results", args->positional, "Result summaries (JSON), the same as --run");
  cmd->add_option("--run", args->runs, "A result's summary JSON (repeat for each method)")->type_name("SUMMARY");
  cmd->add_option("--scale", args->scale, "The distortion shown red (dark blue is 0)")
      ->capture_default_str()
      ->check(greater_than(0));
  cmd->add_option("--title", args->title, "Title of the page")->capture_default_str();
  cmd->add_flag("--quiet,-q", args->out.quiet, "No warnings on stderr");
  cmd->callback([args, &exit_code] { exit_code = run_report(*args); });
}

}  // namespace strictmin::cli
