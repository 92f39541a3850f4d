#include "common.h"

#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <iostream>
#include <sstream>

#include "strictmin/io/atomic_file.h"

// OpenBLAS's thread control, when CHOLMOD runs on OpenBLAS (weak: absent with other BLAS).
extern "C" void openblas_set_num_threads(int) __attribute__((weak));

namespace strictmin::cli {

void add_output_options(CLI::App& cmd, OutputOptions& out) {
  cmd.add_option("--summary", out.summary, "Write a JSON summary to FILE ('-' for stdout)")->type_name("FILE");
  cmd.add_option("--distortion", out.distortion, "Write each element's distortion to FILE, one per line, input order")
      ->type_name("FILE");
  cmd.add_flag("--quiet,-q", out.quiet, "No progress messages on stderr");
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
        if (!std::isfinite(v) || !ok(v)) return "value " + text + " is out of range: must be " + range;
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

nlohmann::json number_or_null(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

void write_outputs(const OutputOptions& out, const nlohmann::json& summary, const Eigen::VectorXd& distortion) {
  if (!out.distortion.empty()) {
    write_file_atomically(out.distortion, [&](std::ostream& os) {
      char buf[64];
      for (Eigen::Index i = 0; i < distortion.size(); ++i) {
        std::snprintf(buf, sizeof buf, "%.17g\n", distortion(i));
        os << buf;
      }
    });
  }
  if (out.summary == "-") {
    std::cout << summary.dump(2) << std::endl;
  } else if (!out.summary.empty()) {
    write_file_atomically(out.summary, [&](std::ostream& os) { os << summary.dump(2) << '\n'; });
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

void progress(const OutputOptions& out, const std::string& line) {
  if (!out.quiet) std::cerr << line << std::endl;
}

int exit_code_for(SolveStatus status) { return status == SolveStatus::Solved ? kExitSuccess : kExitNotConverged; }

void add_distortion_summary(nlohmann::json& s, const DistortionStats& stats) {
  s["max_distortion"] = number_or_null(stats.max);
  s["max_element"] = stats.max_element;
  s["l2_distortion"] = number_or_null(stats.l2);
  s["mean_distortion"] = number_or_null(stats.mean);
  s["flipped"] = stats.flipped;
}

void add_status_summary(nlohmann::json& s, const Result& r) {
  s["status"] = status_name(r.status);
  s["usable"] = r.usable();
  s["stop_reason"] = r.message;
  if (!r.message.empty()) s["message"] = r.message;
}

void add_local_global_summary(nlohmann::json& s, const Result& r) {
  s["local_global_iterations"] = r.iterations;
  // The global steps' certified bound is for field deviation with their rotations fixed, not
  // for the ARAP / ASAP measure reported: it moves to its own key, lower_bound is null.
  if (s.contains("lower_bound")) {
    s["fd_step_lower_bound"] = s["lower_bound"];
    s["lower_bound"] = nullptr;
  }
  nlohmann::json history = nlohmann::json::array();
  for (const auto& h : r.history) history.push_back({{"iteration", h.iteration}, {"max", h.max_distortion}});
  s["history"] = history;
}

}  // namespace strictmin::cli
