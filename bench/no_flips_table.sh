#!/bin/sh
# --no-flips from Tutte on every disk mesh of ../shared/data/disk (docs/performance.md):
# linf and relax ARAP with --no-flips, and linf without it, at most N local-global steps.
# Usage: bench/no_flips_table.sh STRICTMIN [N=10] [MESH ...]
set -eu
if [ $# -lt 1 ] || [ "$1" = --help ] || [ "$1" = -h ]; then
  echo "usage: bench/no_flips_table.sh STRICTMIN [N=10] [MESH ...]   (default: ../shared/data/disk/*.obj)" >&2
  [ $# -lt 1 ] && exit 1 || exit 0
fi
bin=$1; n=${2:-10}; shift; [ $# -gt 0 ] && shift
if [ $# -eq 0 ]; then  # the shared disks, smallest first; one path a line, so spaces stay
  list=$(ls -S -r "$(dirname "$0")"/../../shared/data/disk/*.obj)
  set -f; IFS='
'
  # shellcheck disable=SC2086
  set -- $list
  unset IFS; set +f
fi
echo "mesh faces | linf --no-flips: max flips_added s | relax --no-flips: max flips_added s | linf: max flips_added s"
for m in "$@"; do
  line="$(basename "$m")"
  faces="?"
  for args in "linf --no-flips" "relax --no-flips" "linf"; do
    # shellcheck disable=SC2086
    r=$("$bin" param "$m" --method $args --lg-iterations "$n" -q --summary - | python3 -c '
import json, sys
s = json.load(sys.stdin)
print(s["elements"], "%.6g %d %.1f" % (s["max_distortion"], s["flips_added"], s["solver_time_s"]))')
    faces=${r%% *}; line="$line | ${r#* }"
  done
  echo "$line ($faces faces)"
done
