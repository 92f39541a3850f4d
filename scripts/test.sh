#!/usr/bin/env bash
# Builds (if needed) and runs every test: GoogleTest suites and the Python end-to-end and
# CVXOPT cross-check tests, through ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
[ -d build ] || bash scripts/setup.sh
cmake --build build -j"$(nproc)"
ctest --test-dir build --output-on-failure -j"$(nproc)" "$@"
