#!/bin/sh
# qc and iso L-infinity maps from Tutte on the disk meshes of ../shared/data/disk
# (docs/measures.md, "No flips on the shared disks"): K or S, flipped triangles, status,
# solver time, frame iterations, level programs and interior-point iterations.
# Usage: bench/conformal_table.sh STRICTMIN [CAP_SECONDS=600] [MESH ...]
set -eu
if [ $# -lt 1 ] || [ "$1" = --help ] || [ "$1" = -h ]; then
  echo "usage: bench/conformal_table.sh STRICTMIN [CAP_SECONDS=600] [MESH ...]   (default: ../shared/data/disk/*.obj)" >&2
  [ $# -lt 1 ] && exit 1 || exit 0
fi
bin=$1; cap=${2:-600}; shift; [ $# -gt 0 ] && shift
if [ $# -eq 0 ]; then  # the shared disks, smallest first; one path a line, so spaces stay
  list=$(ls -S -r "$(dirname "$0")"/../../shared/data/disk/*.obj)
  set -f; IFS='
'
  # shellcheck disable=SC2086
  set -- $list
  unset IFS; set +f
fi
echo "| mesh (triangles) | qc: K, flipped, status, time | iso: S, flipped, status, time |"
echo "|---|---|---|"
for m in "$@"; do
  nf="?"; cells=""  # this mesh's triangle count (from a finished run) and cells
  for measure in qc iso; do
    r=$(timeout "$cap" "$bin" param "$m" --measure "$measure" --method linf -q --summary - 2>/dev/null | python3 -c '
import json, sys
s = json.load(sys.stdin)
print(s["elements"], "%.7g, %d, %s, %.1f s (%d frame iterations, %d programs, %d ipm)" % (
    s["max_distortion"], s["flipped"], s["status"], s["solver_time_s"], s["frame_iterations"],
    s["bisection_steps"], s["ipm_iterations"]))' || echo "0 not finished in ${cap} s")
    faces=${r%% *}; [ "$faces" != 0 ] && nf=$faces; cells="$cells | ${r#* }"
  done
  echo "| $(basename "$m" .obj) ($nf)$cells |"
done
