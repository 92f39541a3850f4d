#!/bin/sh
# Issue 19's ratios, measured in one run (docs/performance.md, "ARAP at the cost of a few
# global solves"): on one mesh, the solver time of ARAP linf over one field-deviation linf
# solve, ARAP l2 over one L2 solve, ARAP relax over ARAP linf, from the summaries' solver_time_s.
# Usage: bench/arap_ratios.sh STRICTMIN MESH [param|deform] [extra flags, e.g. --handles H]
# Param meshes start from Tutte (fd: frames from Tutte); deform meshes from the L2 fd map.
# REPEAT=N (default 1): each run N times, the median time kept (this VM's speed drifts).
set -eu
usage="usage: bench/arap_ratios.sh STRICTMIN MESH [param|deform] [extra flags]   (REPEAT=N, N >= 1)"
case "${1:-}" in -h|--help) echo "$usage"; exit 0 ;; esac
[ $# -ge 2 ] || { echo "$usage" >&2; exit 1; }
bin=$1; mesh=$2; task=${3:-param}; shift 2; [ $# -gt 0 ] && shift
repeat=${REPEAT:-1}
case "$repeat" in
  ''|*[!0-9]*|0|00*) echo "arap_ratios.sh: REPEAT=$repeat: not an integer >= 1" >&2; exit 1 ;;
esac
run() {  # measure method -> "max median_seconds global_steps status" (seconds in full precision)
  i=0; out=""
  while [ $i -lt "$repeat" ]; do
    out="$out$("$bin" "$task" "$mesh" "$@" -q --summary - | python3 -c '
import json, sys
s = json.load(sys.stdin)
print("%.6g %r %s %s" % (s["max_distortion"], s["solver_time_s"], s.get("local_global_iterations", 1), s["status"]))')
"
    i=$((i + 1))
  done
  printf '%s' "$out" | python3 -c '
import sys
rows = [l.split() for l in sys.stdin.read().splitlines() if l.strip()]
rows.sort(key=lambda r: float(r[1]))
print(" ".join(rows[len(rows) // 2]))'
}
fd_linf=$(run --measure fd --method linf "$@")
fd_l2=$(run --measure fd --method l2 "$@")
arap_linf=$(run --measure arap --method linf "$@")
arap_l2=$(run --measure arap --method l2 "$@")
arap_relax=$(run --measure arap --method relax "$@")
# The table shows seconds to 3 decimals; the ratios are of the full-precision times.
python3 - "$repeat" "$fd_linf" "$fd_l2" "$arap_linf" "$arap_l2" "$arap_relax" <<'PY'
import sys
repeat, rows = sys.argv[1], [a.split() for a in sys.argv[2:]]
names = ["fd_linf", "fd_l2", "arap_linf", "arap_l2", "arap_relax"]
print("run        max         solver_s  global_steps status   (median of %s)" % repeat)
for name, (mx, s, steps, status) in zip(names, rows):
    print("%-10s %-11s %8.3f  %-12s %s" % (name, mx, float(s), steps, status))
t = [float(r[1]) for r in rows]


def ratio(a, b):
    return "%.2f" % (t[a] / t[b]) if t[b] > 0 else "n/a (%s took 0 s)" % names[b]


print("ARAP linf / one FD linf solve: %s (target <= 5)" % ratio(2, 0))
print("ARAP l2 / one L2 solve:        %s (target <= 10)" % ratio(3, 1))
print("ARAP relax / ARAP linf:        %s (target <= 1.5)" % ratio(4, 2))
PY
