#include "common.h"

#include <tbb/global_control.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <sstream>

#include "strictmin/io/atomic_file.h"
#include "strictmin/io/input_error.h"
#include "strictmin/mesh/validate.h"

// OpenBLAS's thread control, when CHOLMOD runs on OpenBLAS (weak: absent with other BLAS).
extern "C" void openblas_set_num_threads(int) __attribute__((weak));

namespace strictmin::cli {

void add_output_options(CLI::App& cmd, OutputOptions& out) {
  cmd.add_option("--summary", out.summary, "Write a JSON summary to FILE ('-' for stdout)")->type_name("FILE");
  cmd.add_option("--distortion", out.distortion, "Write each element's distortion to FILE, one per line, input order ('-' for stdout)")
      ->type_name("FILE");
  cmd.add_flag("--quiet,-q", out.quiet, "No progress messages or warnings on stderr (errors are still printed; the summary keeps the warnings it has keys for)");
  cmd.add_option("--threads", out.threads, "Number of threads (default 0: all cores)")->check(at_least(0));
}

namespace {
CLI::Validator number_check(std::function<bool(double)> ok, const std::string& range) {
  return CLI::Validator(
      [ok, range](std::string& text) -> std::string {
        double v = 0;
        size_t used = 0;
        try {
          v = std::stod(text, &used);
        } catch (const std::exception&) {
          return "'" + text + "' is not a number";
        }
        if (used != text.size()) return "'" + text + "' is not a number";
        // inf passes "> 0" as a comparison: say why it is refused (every flag takes finite values).
        if (!std::isfinite(v)) return "value " + text + " is not a finite number (must be " + range + ")";
        if (!ok(v)) return "value " + text + " is out of range: must be " + range;
        return "";
      },
      range);
}
std::string fmt(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}
}  // namespace

CLI::Validator greater_than(double low) {
  return number_check([low](double v) { return v > low; }, "> " + fmt(low));
}
CLI::Validator at_least(double low) {
  return number_check([low](double v) { return v >= low; }, ">= " + fmt(low));
}
CLI::Validator open_range(double low, double high) {
  return number_check([low, high](double v) { return v > low && v < high; }, "in (" + fmt(low) + ", " + fmt(high) + ")");
}
CLI::Validator less_than(double high) {
  return number_check([high](double v) { return v < high; }, "< " + fmt(high));
}
CLI::Validator half_open_range(double low, double high) {
  return number_check([low, high](double v) { return v >= low && v < high; },
                      "in [" + fmt(low) + ", " + fmt(high) + ")");
}

std::shared_ptr<void> limit_threads(int threads) {
  if (threads <= 0) return nullptr;
  if (openblas_set_num_threads) openblas_set_num_threads(threads);
  return std::make_shared<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                               static_cast<size_t>(threads));
}

void write_outputs(const OutputOptions& out, const nlohmann::json& summary, const Eigen::VectorXd& distortion) {
  const auto write_distortions = [&](std::ostream& os) {
    char buf[64];
    for (Eigen::Index i = 0; i < distortion.size(); ++i) {
      std::snprintf(buf, sizeof buf, "%.17g\n", distortion(i));
      os << buf;
    }
  };
  if (out.distortion == "-") {
    write_distortions(std::cout);
    std::cout.flush();
  } else if (!out.distortion.empty()) {
    write_file_atomically(out.distortion, write_distortions);
  }
  if (out.summary.empty()) return;
  nlohmann::json s = summary;
  add_provenance_summary(s);  // every summary says which strictmin wrote it, on which kernels
  if (out.summary == "-") {
    std::cout << s.dump(2) << std::endl;
  } else {
    write_file_atomically(out.summary, [&](std::ostream& os) { os << s.dump(2) << '\n'; });
  }
}

void print_iteration(const std::string& label, const IterationRecord& r) {
  std::string line = label;
  char buf[96];
  std::snprintf(buf, sizeof buf, " %3d  max %.10g", r.iteration, r.max_distortion);
  line += buf;
  auto field = [&](const char* name, double v, const char* fmt) {
    if (std::isnan(v)) return;
    std::snprintf(buf, sizeof buf, fmt, name, v);
    line += buf;
  };
  field("lower bound", r.lower_bound, "  %s %.10g");
  field("gap", r.certified_gap, "  %s %.2e");
  field("relative change", r.relative_change, "  %s %.2e");
  field("largest move", r.largest_move, "  %s %.2e");
  field("decrement", r.decrement, "  %s %.2e");
  if (r.accelerated_accepted >= 0) {
    std::snprintf(buf, sizeof buf, "  accelerated %d taken / %d rejected", r.accelerated_accepted, r.accelerated_rejected);
    line += buf;
  }
  std::snprintf(buf, sizeof buf, "  %.2f s", r.time_s);
  line += buf;
  std::cerr << line << std::endl;
}

void print_local_global_progress(const IterationRecord& r, const std::string& indent) {
  print_iteration(indent + "local-global step", r);
}

void check_output_paths(const std::vector<std::pair<std::string, std::string>>& outputs) {
  namespace fs = std::filesystem;
  for (const auto& [flag, path] : outputs) {
    if (path.empty() || path == "-") continue;
    const fs::path parent = fs::path(path).parent_path();
    std::error_code ec;
    if (!parent.empty() && !fs::is_directory(parent, ec))
      throw InputError(flag + " " + path + ": the folder " + parent.string() + " does not exist");
    if (fs::is_directory(path, ec)) throw InputError(flag + " " + path + ": is a folder, not a file");
  }
}

std::string shown_number(double value, int significant) {
  char text[40];
  std::snprintf(text, sizeof text, "%.*g", significant, value);
  return text;
}

std::string flipped_phrase(int flipped, int elements) {
  if (flipped < 0) return "flips not defined (surface)";
  return std::to_string(flipped) + " flipped" + (elements >= 0 ? " of " + std::to_string(elements) : "");
}

std::string lowercase_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

void check_uv_output_path(const std::string& path) {
  if (path.empty()) return;
  if (lowercase_extension(path) != ".obj")
    throw InputError("--output " + path + ": the map is written as per-corner texture coordinates (vt, f v/vt), "
                     "which only .obj holds; use a .obj name");
}

void check_output_paths(const OutputOptions& out) {
  check_output_paths({{"--summary", out.summary}, {"--distortion", out.distortion}});
}

namespace {

// One name for a path, whichever way it was written (relative, with .., through a link).
std::filesystem::path path_key(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path key = fs::weakly_canonical(fs::absolute(path, ec), ec);
  if (ec) key = fs::absolute(path).lexically_normal();
  return key;
}

// The files a report writes in its folder (docs/report.md): summary.json, index.html, its
// list of files and its pictures.
bool written_by_report(const std::filesystem::path& name) {
  const std::string ext = lowercase_extension(name.string());
  return name == "summary.json" || name == "index.html" || name == ".strictmin-report" || ext == ".png" ||
         ext == ".svg";
}

// '-' is stdout for --summary and --distortion only; the task's own outputs (-o, --field-out,
// --cones-out) are files (a file named '-' was written before).
void refuse_stdout_for_files(const std::vector<std::pair<std::string, std::string>>& task_outputs) {
  for (const auto& [flag, path] : task_outputs)
    if (path == "-")
      throw InputError(flag + " -: writes a file ('-' for stdout is taken by --summary and --distortion only); "
                       "give a file name");
}

// The report folder, before the solve: it is or can become a folder (its nearest existing
// ancestor is a folder), no other output is that path, and no other output is one of the
// files the report writes there (it would replace it; --summary DIR/summary.json excepted:
// the report writes the same summary).
void check_report_folder(const std::string& dir, const std::vector<std::pair<std::string, std::string>>& outputs) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) throw InputError("--report " + dir + ": is a file, not a folder");
  for (fs::path up = fs::absolute(dir, ec).lexically_normal(); !up.empty(); up = up.parent_path()) {
    if (fs::exists(up, ec)) {
      if (!fs::is_directory(up, ec))
        throw InputError("--report " + dir + ": cannot be created: " + up.string() + " is a file, not a folder");
      break;
    }
    if (up == up.parent_path()) break;
  }
  fs::path folder = path_key(dir);
  if (!folder.has_filename()) folder = folder.parent_path();  // "DIR/"
  for (const auto& [flag, path] : outputs) {
    if (path.empty() || path == "-") continue;
    const fs::path key = path_key(path);
    if (key == folder) throw InputError(flag + " " + path + ": is the --report folder; choose another name");
    if (key.parent_path() != folder || !written_by_report(key.filename())) continue;
    if (flag == "--summary" && key.filename() == "summary.json") continue;
    throw InputError(flag + " " + path + ": the --report folder's own " + key.filename().string() +
                     " (the report writes summary.json, index.html and its .png and .svg pictures there); "
                     "choose another name");
  }
}

}  // namespace

bool same_file(const std::string& a, const std::string& b) {
  if (path_key(a) == path_key(b)) return true;
  std::error_code ec;
  return std::filesystem::equivalent(a, b, ec) && !ec;
}

void check_run_outputs(const OutputOptions& out, const std::vector<std::pair<std::string, std::string>>& task_outputs,
                       const std::string& report_dir, const std::vector<std::pair<std::string, std::string>>& inputs) {
  namespace fs = std::filesystem;
  std::vector<std::pair<std::string, std::string>> all = task_outputs;
  all.push_back({"--summary", out.summary});
  all.push_back({"--distortion", out.distortion});
  if (out.summary == "-" && out.distortion == "-")
    throw InputError("--summary - and --distortion - would both write to stdout; give one of them a file name");
  check_output_paths(all);
  for (const auto& [flag, path] : task_outputs) {  // a mesh output's format, known before the solve
    if (flag != "--output" || path.empty()) continue;
    const std::string ext = lowercase_extension(path);
    if (ext != ".obj" && ext != ".off" && ext != ".ply" && ext != ".mesh")
      throw InputError("--output " + path + ": unknown mesh format '" + ext + "' (use .obj, .off, .ply or .mesh)");
  }
  std::vector<std::pair<fs::path, std::string>> seen;
  for (const auto& [flag, path] : all) {
    if (path.empty() || path == "-") continue;
    const fs::path key = path_key(path);
    for (const auto& [other, other_flag] : seen)
      if (other == key) throw InputError(flag + " " + path + ": " + other_flag + " writes the same file");
    seen.push_back({key, flag});
    for (const auto& [what, input] : inputs)
      if (!input.empty() && input != "-" && same_file(path, input))
        throw InputError(flag + " " + path + ": is " + what + " (writing it would destroy it); choose another name");
  }
  refuse_stdout_for_files(task_outputs);
  if (!report_dir.empty()) check_report_folder(report_dir, all);
}

void progress(const OutputOptions& out, const std::string& line) {
  if (!out.quiet) std::cerr << line << std::endl;
}

int exit_code_for(SolveStatus status) { return status == SolveStatus::Solved ? kExitSuccess : kExitNotConverged; }

std::string write_map(const std::string& path, const Mesh& map, SolveStatus status, const MeshWriteOptions& options) {
  if (path.empty()) return "";
  if (!coordinates_are_finite(map)) {
    std::cerr << "strictmin: warning: map not written to " << path << ": its coordinates are not finite (status "
              << status_name(status) << ")" << std::endl;
    return "";
  }
  write_mesh(path, map, options);
  return path;
}

}  // namespace strictmin::cli
