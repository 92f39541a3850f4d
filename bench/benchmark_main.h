#pragma once
// main() of a Google Benchmark program that reads environment variables: they are checked
// after the command line and before the first benchmark, so a bad value (STRICTMIN_*=abc)
// is "NAME: error: STRICTMIN_...=abc: not an integer ..." with exit 1, not a silent 0.
#include <benchmark/benchmark.h>

#include "args.h"

namespace strictmin::bench {

// Runs the registered benchmarks after CHECK_ENVIRONMENT(), which throws
// std::invalid_argument naming the variable (bench::env_int) on a bad value.
template <class CheckEnvironment>
int benchmark_main(const char* name, CheckEnvironment check_environment, int argc, char** argv) {
  return guarded_main(
      name,
      [&](int count, char** arguments) {
        benchmark::Initialize(&count, arguments);  // --help prints and exits 0 here
        if (benchmark::ReportUnrecognizedArguments(count, arguments)) return 1;
        check_environment();
        benchmark::RunSpecifiedBenchmarks();
        benchmark::Shutdown();
        return 0;
      },
      argc, argv);
}

}  // namespace strictmin::bench
