// strictmin: maps of triangle and tet meshes with the least worst-case distortion.
#include <CLI/CLI.hpp>
#include <dlfcn.h>

#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <string>

#include "commands.h"
#include "common.h"
#include "runtime/blas_kernels.h"
#include "strictmin/io/input_error.h"
#include "strictmin/solvers/interrupt.h"
#include "strictmin/version.h"

// OpenBLAS's own threads spin against CHOLMOD's and TBB's on small machines: one BLAS
// thread is never slower for our supernodal factorizations and often much faster (the 100k
// bar of bench_linf: 7.4 s against 11.1 s on 2 cores, docs/performance.md). Looked up at run
// time, so that any BLAS links; OPENBLAS_NUM_THREADS, when set, wins.
static void use_one_blas_thread() {
  if (std::getenv("OPENBLAS_NUM_THREADS")) return;
  if (void* f = dlsym(RTLD_DEFAULT, "openblas_set_num_threads")) reinterpret_cast<void (*)(int)>(f)(1);
}

// Ctrl-C (SIGINT) and SIGTERM: the first asks the solvers to stop at their next iteration
// (solvers/interrupt.h), before any output is written; a second one ends the process at once.
static std::atomic<bool> interrupt_requested{false};
extern "C" void on_interrupt(int) {
  if (interrupt_requested.exchange(true)) ::_exit(strictmin::cli::kExitInterrupted);
}

int main(int argc, char** argv) {
  strictmin::runtime::rerun_with_better_blas_kernels(argv);  // returns unless OpenBLAS fell back to Prescott
  use_one_blas_thread();
  CLI::App app{
      "strictmin: maps of triangle and tetrahedral meshes with the least possible worst-case distortion\n"
      "(L2, L-infinity and strict minimizers; Levi & Zorin 2014).\n\n"
      "Examples:\n"
      "  strictmin deform --example square --method linf --summary -\n"
      "  strictmin deform mesh.obj --handles handles.txt --method linf -o out.obj\n"
      "  strictmin eval rest.obj mapped.obj --measure arap\n"
      "  strictmin interp source.obj target.obj --t 0.25,0.5,0.75 --method linf -o frame\n"
      "  strictmin param disk.obj --method linf -o uv.obj\n"
      "  strictmin gparam closed.obj --method relax -o uv.obj --report R\n\n"
      "Exit codes: 0 success, 1 bad input, 2 solver did not reach its tolerance (result still written), 130 "
      "interrupted (Ctrl-C).",
      "strictmin"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "strictmin " + std::string(strictmin::version()));
  int exit_code = strictmin::cli::kExitSuccess;
  strictmin::cli::add_deform_command(app, exit_code);
  strictmin::cli::add_eval_command(app, exit_code);
  strictmin::cli::add_report_command(app, exit_code);
  strictmin::cli::add_demo_command(app, exit_code);
  strictmin::cli::add_interp_command(app, exit_code);
  strictmin::cli::add_param_command(app, exit_code);
  strictmin::cli::add_gparam_command(app, exit_code);
  strictmin::cli::add_quads_command(app, exit_code);
  std::signal(SIGINT, on_interrupt);
  std::signal(SIGTERM, on_interrupt);
  const strictmin::InterruptScope interrupts(interrupt_requested);
  try {
    app.parse(argc, argv);
    if (interrupt_requested) {  // after the last check: every output was written, completely
      std::cerr << "strictmin: interrupted after the outputs were written" << std::endl;
      return strictmin::cli::kExitInterrupted;
    }
  } catch (const strictmin::Interrupted&) {
    // Outputs are written after their solve: this run's are not (interp's earlier frames and
    // demo's earlier sections are, complete).
    std::cerr << "strictmin: interrupted: the solve stopped before its outputs were written" << std::endl;
    return strictmin::cli::kExitInterrupted;
  } catch (const CLI::RequiredError& e) {
    // "A subcommand is required" also answers a mistyped command or option before any command:
    // name what was given instead.
    if (argc > 1 && app.get_subcommands().empty()) {
      std::string names;
      for (const CLI::App* sub : app.get_subcommands({})) names += (names.empty() ? "" : ", ") + sub->get_name();
      const std::string given = argv[1];
      std::cerr << "strictmin: error: " << (given.rfind("-", 0) == 0 ? "unknown option '" : "unknown command '")
                << given << "' (commands: " << names << "; strictmin --help)" << std::endl;
      return strictmin::cli::kExitBadInput;
    }
    const int code = app.exit(e);
    return code == 0 ? 0 : strictmin::cli::kExitBadInput;
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : strictmin::cli::kExitBadInput;
  } catch (const strictmin::InputError& e) {
    std::cerr << "strictmin: error: " << e.what() << std::endl;
    return strictmin::cli::kExitBadInput;
  } catch (const std::bad_alloc&) {
    std::cerr << "strictmin: error: out of memory" << std::endl;
    return strictmin::cli::kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "strictmin: error: " << e.what() << std::endl;
    return strictmin::cli::kExitBadInput;
  }
  return exit_code;
}
