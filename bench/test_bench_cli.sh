#!/bin/sh
# The benchmark programs' command lines (ctest bench_cli, bench/CMakeLists.txt): --help exits 0,
# bad input exits 1 with a message naming it (never an abort, exit 134). No solve is run.
# Usage: bench/test_bench_cli.sh BENCH_DIR (the folder of the built bench_* programs)
set -u
dir=${1:?usage: test_bench_cli.sh BENCH_DIR}
tmp=$(mktemp -d) || exit 1
trap 'rm -rf "$tmp"' EXIT
failed=0
# expect CODE WORD PROGRAM ARGS...: the exit code is CODE and the output names WORD.
expect() {
  code=$1; word=$2; program=$3; shift 3
  "$dir/$program" "$@" >"$tmp/out" 2>&1
  got=$?
  if [ "$got" -ne "$code" ] || ! grep -q -- "$word" "$tmp/out"; then
    echo "FAILED: $program $* -> exit $got (expected $code with '$word'):" >&2
    cat "$tmp/out" >&2
    failed=$((failed + 1))
  fi
}
for p in bench_gparam_linf bench_gparam_direct bench_gparam_relax bench_table1; do
  expect 0 usage "$p" --help
  expect 1 "--bogus" "$p" --bogus
done
expect 1 "missing.obj" bench_gparam_linf "$tmp/missing.obj"
expect 1 "missing.obj" bench_gparam_direct "$tmp/missing.obj"
expect 1 "missing.obj" bench_gparam_relax "$tmp/missing.obj" --start "$tmp/s.bin"
expect 1 "missing.obj" bench_table1 --out "$tmp/t.json" "$tmp/missing.obj"
export STRICTMIN_MOVING_RINGS=-1
expect 1 STRICTMIN_MOVING_RINGS bench_gparam_direct "$tmp/missing.obj"
unset STRICTMIN_MOVING_RINGS
expect 1 "--repeat" bench_gparam_relax m.obj --start "$tmp/s.bin" --repeat 0
expect 1 "--threads" bench_gparam_relax m.obj --start "$tmp/s.bin" --threads 99999999999
expect 1 "--sweeps" bench_gparam_relax m.obj --start "$tmp/s.bin" --sweeps
expect 1 "no folder" bench_gparam_relax m.obj --start "$tmp/nowhere/s.bin"
expect 1 "cannot open" bench_table1 --merge "$tmp/missing.json"
expect 1 "no JSON files" bench_table1 --merge
expect 1 "no folder" bench_table1 --out "$tmp/nowhere/t.json" "$tmp/missing.obj"
# Google Benchmark programs: the environment is checked before the first benchmark
# (--benchmark_list_tests runs none).
for p in bench_direct bench_linf; do
  expect 0 benchmark_filter "$p" --help
  STRICTMIN_LINF_VERBOSE=abc expect 1 "STRICTMIN_LINF_VERBOSE=abc" "$p" --benchmark_list_tests
  STRICTMIN_LINF_VERBOSE=3 expect 1 "STRICTMIN_LINF_VERBOSE=3" "$p" --benchmark_list_tests
  STRICTMIN_LINF_VERBOSE=1 expect 0 BM_ "$p" --benchmark_list_tests
done
STRICTMIN_DIRECT_MAX_STEPS=5x expect 1 STRICTMIN_DIRECT_MAX_STEPS bench_direct --benchmark_list_tests
STRICTMIN_MOVING_RINGS=-1 expect 1 STRICTMIN_MOVING_RINGS bench_direct --benchmark_list_tests
STRICTMIN_LINF_VERBOSE=x expect 1 STRICTMIN_LINF_VERBOSE bench_gparam_linf "$tmp/missing.obj"
[ "$failed" -eq 0 ] && echo "bench_cli: all passed"
[ "$failed" -eq 0 ]
