#!/bin/sh
# qc and iso L-infinity maps from Tutte on the disk meshes of ../shared/data/disk
# (docs/measures.md, "No flips on the shared disks"): K or S, flipped triangles, status,
# solver time, frame iterations, level programs and interior-point iterations.
# Usage: bench/conformal_table.sh STRICTMIN [CAP_SECONDS=600] [MESH ...]
set -eu
bin=$1; cap=${2:-600}; shift; [ $# -gt 0 ] && shift
meshes=${*:-$(ls -S -r "$(dirname "$0")"/../../shared/data/disk/*.obj)}
echo "| mesh (triangles) | qc: K, flipped, status, time | iso: S, flipped, status, time |"
echo "|---|---|---|"
for m in $meshes; do
  line="| $(basename "$m" .obj)"
  for measure in qc iso; do
    r=$(timeout "$cap" "$bin" param "$m" --measure "$measure" --method linf -q --summary - 2>/dev/null | python3 -c '
import json, sys
s = json.load(sys.stdin)
print(s["elements"], "%.7g, %d, %s, %.1f s (%d frame iterations, %d programs, %d ipm)" % (
    s["max_distortion"], s["flipped"], s["status"], s["solver_time_s"], s["frame_iterations"],
    s["bisection_steps"], s["ipm_iterations"]))' || echo "0 not finished in ${cap} s")
    faces=${r%% *}; [ "$faces" != 0 ] && nf=$faces; line="$line | ${r#* }"
  done
  echo "$line |" | sed "s/^| \([^ ]*\)/| \1 (${nf:-?})/"
done
