#!/usr/bin/env bash
# A short fuzz run of the mesh and handle parsers (docs/fuzzing.md): builds the libFuzzer
# targets (fuzz/, the CMake option STRICTMIN_FUZZ) with clang into a build tree of their own
# and runs each from its seed corpus for a few seconds. Any crash, leak, sanitizer report,
# timeout or broken invariant fails the run; the input that did it is saved in the build
# tree's artifacts/ folder. Exits 77 (skipped) when clang or libFuzzer is not installed
# (Debian: clang and libclang-rt-14-dev, installed by scripts/setup.sh).
# Usage: bash scripts/fuzz_smoke.sh [--build-dir DIR] [--seconds S] [TARGET...]
#   defaults: build-fuzz/, 5 s per target, all four targets (fuzz_obj fuzz_off fuzz_medit fuzz_handles)
# Run by ctest as fuzz_smoke (tests/CMakeLists.txt) with the build tree under build/.
set -euo pipefail
usage="usage: bash scripts/fuzz_smoke.sh [--build-dir DIR] [--seconds S] [TARGET...]"
root=$(cd "$(dirname "$0")/.." && pwd)
build=$root/build-fuzz
seconds=${STRICTMIN_FUZZ_SECONDS:-5}
targets=()
# The arguments first, in the caller's folder: a relative --build-dir is the caller's, not the
# repository's.
while [ $# -gt 0 ]; do
  case "$1" in
    -h|--help) echo "$usage"; exit 0 ;;
    --build-dir|--seconds)
      if [ $# -lt 2 ] || [ -z "$2" ]; then echo "fuzz_smoke: $1: missing value" >&2; echo "$usage" >&2; exit 1; fi
      if [ "$1" = --seconds ]; then seconds=$2; else build=$2; fi
      shift 2 ;;
    -*) echo "fuzz_smoke: $1: unknown option" >&2; echo "$usage" >&2; exit 1 ;;
    *) targets+=("$1"); shift ;;
  esac
done
case "$seconds" in
  ''|*[!0-9]*) echo "fuzz_smoke: --seconds $seconds (or STRICTMIN_FUZZ_SECONDS): not a whole number of seconds" >&2; exit 1 ;;
esac
case "$build" in /*) ;; *) build=$PWD/$build ;; esac
[ ${#targets[@]} -gt 0 ] || targets=(fuzz_obj fuzz_off fuzz_medit fuzz_handles)
cd "$root"

cxx=$(command -v clang++ || command -v clang++-14 || true)
if [ -z "$cxx" ]; then
  echo "fuzz_smoke: skipped: clang++ not found (Debian: apt-get install clang libclang-rt-14-dev)" >&2
  exit 77
fi
if ! echo 'extern "C" int LLVMFuzzerTestOneInput(const unsigned char*, unsigned long) { return 0; }' |
    "$cxx" -x c++ -fsanitize=fuzzer -o /dev/null - 2>/dev/null; then
  echo "fuzz_smoke: skipped: $cxx cannot link libFuzzer (Debian: apt-get install libclang-rt-14-dev)" >&2
  exit 77
fi

cmake -S . -B "$build" -DSTRICTMIN_FUZZ=ON -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build" -j2 --target "${targets[@]}" >/dev/null

failed=0
for target in "${targets[@]}"; do
  name=${target#fuzz_}
  work="$build/corpus/$name"  # new inputs go here; the seeds in fuzz/corpus stay as they are
  mkdir -p "$work" "$build/artifacts"
  log="$build/$target.log"
  if "$build/fuzz/$target" "$work" "fuzz/corpus/$name" -dict="fuzz/$name.dict" -max_total_time="$seconds" \
      -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$build/artifacts/$target-" >"$log" 2>&1; then
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
    echo "fuzz_smoke: $target: ${runs:-?} inputs in ${seconds} s, no crash" >&2
  else
    failed=$((failed + 1))
    echo "fuzz_smoke: $target FAILED (log $log, input in $build/artifacts/):" >&2
    grep -E "ERROR|invariant|SUMMARY|Test unit written" "$log" | head -20 >&2 || tail -30 "$log" >&2
  fi
done
passed=$(( ${#targets[@]} - failed ))
echo "fuzz_smoke: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
