#include "common.h"

#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <iostream>

#include "strictmin/io/atomic_file.h"

// OpenBLAS's thread control, when CHOLMOD runs on OpenBLAS (weak: absent with other BLAS).
extern "C" void openblas_set_num_threads(int) __attribute__((weak));

namespace strictmin::cli {

void add_output_options(CLI::App& cmd, OutputOptions& out) {
  cmd.add_option("--summary", out.summary, "Write a JSON summary to FILE ('-' for stdout)")->type_name("FILE");
  cmd.add_option("--distortion", out.distortion, "Write each element's distortion to FILE, one per line, input order")
      ->type_name("FILE");
  cmd.add_flag("--quiet,-q", out.quiet, "No progress messages on stderr");
  cmd.add_option("--threads", out.threads, "Number of threads (default: all cores)")->check(CLI::NonNegativeNumber);
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
  if (!r.message.empty()) s["message"] = r.message;
}

void add_local_global_summary(nlohmann::json& s, const Result& r) {
  s["local_global_iterations"] = r.iterations;
  s["stop_reason"] = r.message;
  nlohmann::json history = nlohmann::json::array();
  for (const auto& h : r.history) history.push_back({{"iteration", h.iteration}, {"max", h.max_distortion}});
  s["history"] = history;
}

}  // namespace strictmin::cli
