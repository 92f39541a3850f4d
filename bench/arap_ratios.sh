#!/bin/sh
# Issue 19's ratios, measured in one run (docs/performance.md, "ARAP at the cost of a few
# global solves"): on one mesh, the solver time of ARAP linf over one field-deviation linf
# solve, ARAP l2 over one L2 solve, ARAP relax over ARAP linf, from the summaries' solver_time_s.
# Usage: bench/arap_ratios.sh STRICTMIN MESH [param|deform] [extra flags, e.g. --handles H]
# Param meshes start from Tutte (fd: frames from Tutte); deform meshes from the L2 fd map.
# REPEAT=N (default 1): each run N times, the median time kept (this VM's speed drifts).
set -eu
bin=$1; mesh=$2; task=${3:-param}; shift 2; [ $# -gt 0 ] && shift
repeat=${REPEAT:-1}
run() {  # measure method -> "max median_seconds global_steps status"
  i=0; out=""
  while [ $i -lt "$repeat" ]; do
    out="$out$("$bin" "$task" "$mesh" "$@" -q --summary - | python3 -c '
import json, sys
s = json.load(sys.stdin)
print("%.6g %.3f %s %s" % (s["max_distortion"], s["solver_time_s"], s.get("local_global_iterations", 1), s["status"]))')
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
echo "run                max         solver_s  global_steps status   (median of $repeat)"
for n in fd_linf fd_l2 arap_linf arap_l2 arap_relax; do eval "echo \"$n \$$n\""; done
python3 - "$fd_linf" "$fd_l2" "$arap_linf" "$arap_l2" "$arap_relax" <<'PY'
import sys
t = [float(a.split()[1]) for a in sys.argv[1:]]
print("ARAP linf / one FD linf solve: %.2f (target <= 5)" % (t[2] / t[0]))
print("ARAP l2 / one L2 solve:        %.2f (target <= 10)" % (t[3] / t[1]))
print("ARAP relax / ARAP linf:        %.2f (target <= 1.5)" % (t[4] / t[2]))
PY
