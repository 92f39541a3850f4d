#pragma once
// What every subcommand shares: output options, the summary JSON, the distortion file,
// progress on stderr, thread count and exit codes.
#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <chrono>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "strictmin/io/mesh_io.h"
#include "strictmin/mesh/mesh.h"
#include "strictmin/report/stats.h"
#include "report/summary.h"  // private (src/): the CLI and the Python module
#include "strictmin/solvers/result.h"
#include "strictmin/solvers/timing.h"

namespace strictmin::cli {

// Exit codes (docs/formats.md).
constexpr int kExitSuccess = 0;
constexpr int kExitBadInput = 1;
constexpr int kExitNotConverged = 2;
constexpr int kExitInterrupted = 130;  // Ctrl-C or SIGTERM (128 + SIGINT, the shells' convention)

struct OutputOptions {
  std::string summary;     // --summary FILE or "-" (stdout)
  std::string distortion;  // --distortion FILE: one value per element
  bool quiet = false;
  int threads = 0;         // 0: all cores
};

void add_output_options(CLI::App& cmd, OutputOptions& out);

// Range validators for numeric flags (CLI11 names the flag in its message; NaN fails each).
CLI::Validator greater_than(double low);         // (low, inf)
CLI::Validator at_least(double low);             // [low, inf)
CLI::Validator open_range(double low, double high);  // (low, high)
CLI::Validator half_open_range(double low, double high);  // [low, high)
CLI::Validator less_than(double high);           // (-inf, high)

// Limits TBB and OpenBLAS to `threads` (0: leave the defaults). Keep the returned object alive.
std::shared_ptr<void> limit_threads(int threads);

// Writes the summary (pretty JSON) to a file (atomically) or stdout, and the distortion
// vector, one value per line in element order.
void write_outputs(const OutputOptions& out, const nlohmann::json& summary, const Eigen::VectorXd& distortion);

// One progress line on stderr for an iteration record: the label, the iteration, the
// maximum, then only the fields that apply to the solver (not NaN), the elapsed time.
void print_iteration(const std::string& label, const IterationRecord& r);
void print_local_global_progress(const IterationRecord& r, const std::string& indent);

// Bad input before any work: every output file's folder must exist (nothing is written
// when one cannot be, so no run leaves some outputs behind). Pairs of flag and path; empty
// paths and "-" are skipped. Throws InputError naming the flag and the path.
void check_output_paths(const std::vector<std::pair<std::string, std::string>>& outputs);
// The same for the common output options (--summary, --distortion).
void check_output_paths(const OutputOptions& out);
// Whether two paths name one file: the same name written another way (relative, with ..,
// through a link), or one file under two names (a hard link).
bool same_file(const std::string& a, const std::string& b);

// Whether the option (set by its add_ function, null before) was given on the command line:
// the refusals of flags that do not apply to the chosen measure or method.
inline bool given(const CLI::Option* option) { return option != nullptr && option->count() > 0; }
// Every output of a run at once, before any work: the checks above for the task's own
// outputs and the common ones, no two flags naming one file (the later write would replace
// the earlier), no output naming one of the run's inputs (`inputs`: {what, path}, e.g.
// {"the input mesh", a.mesh}; the write would destroy it), and the report folder (when given)
// not an existing file.
void check_run_outputs(const OutputOptions& out, const std::vector<std::pair<std::string, std::string>>& task_outputs,
                       const std::string& report_dir,
                       const std::vector<std::pair<std::string, std::string>>& inputs = {});
// gparam's map is per-corner vt (f v/vt): only .obj holds it; any other extension is refused
// before the solve (an .off or .ply would silently keep the input alone). param, whose map is
// one vt per vertex, writes other formats without it, as documented.
void check_uv_output_path(const std::string& path);
// A number for messages and file names, printf's %g with `significant` digits: as a user
// wrote it (-1e-10, 0.25), where std::to_string prints -0.000000 and 0.250000.
std::string shown_number(double value, int significant = 6);
// "3 flipped" ("3 flipped of 800" with the element count), or "flips not defined (surface)"
// for a negative count (a surface mapped in 3D: its 3x2 Jacobians have no orientation).
std::string flipped_phrase(int flipped, int elements = -1);

// The file name's extension in lower case (".obj"; empty when none).
std::string lowercase_extension(const std::string& path);

// Progress line on stderr unless quiet.
void progress(const OutputOptions& out, const std::string& line);

int exit_code_for(SolveStatus status);

// Writes a solve's map to PATH (-o) and returns PATH, the summary's `output`; "" when PATH is
// empty or the map's coordinates or UVs are not finite (a solve that failed numerically,
// status STATUS): such a map is not written, which a line on stderr says even under --quiet
// (no reader takes "nan"), and the run goes on to its summary and exit code.
std::string write_map(const std::string& path, const Mesh& map, SolveStatus status,
                      const MeshWriteOptions& options = {});

}  // namespace strictmin::cli
