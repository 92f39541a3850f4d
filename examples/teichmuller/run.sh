#!/bin/sh
# Teichmueller-like maps (paper Figure 15, docs/measures.md): the square with its boundary
# fixed and two landmarks turned; qc L-infinity, qc strict (direct), ASAP strict (direct and
# relax), and a side-by-side report of their quasiconformal distortion.
#   examples/teichmuller/run.sh [STRICTMIN] [OUT] [N]
set -e
S=${1:-strictmin}
OUT=${2:-teichmuller_out}
N=${3:-24}
HERE=$(dirname "$0")
# The program by an absolute path: the runs below are made inside $OUT. A bare name
# (strictmin) is looked up on PATH.
case "$S" in
  */*) dir=$(cd "$(dirname "$S")" 2>/dev/null && pwd) || { echo "run.sh: $S: no such folder" >&2; exit 1; }
       S=$dir/$(basename "$S") ;;
  *) found=$(command -v "$S") || { echo "run.sh: $S: not found on PATH" >&2; exit 1; }
     S=$found ;;
esac
[ -x "$S" ] || { echo "run.sh: $S: not an executable program" >&2; exit 1; }
python3 "$HERE/make_square.py" "$N" "$OUT"
cd "$OUT"
"$S" deform square.obj --handles handles.txt --measure qc --method linf -o qc_linf.obj \
    --summary qc_linf.json --distortion qc_linf.txt -q || true
"$S" deform square.obj --handles handles.txt --measure qc --method direct --delta-k 1e-3 -o qc_direct.obj \
    --summary qc_direct.json --distortion qc_direct.txt -q || true
"$S" deform square.obj --handles handles.txt --measure asap --method direct -o asap_direct.obj \
    --summary asap_direct.json -q || true
"$S" deform square.obj --handles handles.txt --measure asap --method relax -o asap_relax.obj \
    --summary asap_relax.json -q || true
# The ASAP maps' quasiconformal distortion, for the same histogram.
"$S" eval square.obj asap_direct.obj --measure qc --summary asap_direct_qc.json --distortion asap_direct_qc.txt -q
"$S" eval square.obj asap_relax.obj --measure qc --summary asap_relax_qc.json --distortion asap_relax_qc.txt -q
# Exit 2 says some run is not `solved` (qc direct is almost-solved here): the report is written.
"$S" report report --scale 1 --run qc_linf.json --run qc_direct.json --run asap_direct_qc.json \
    --run asap_relax_qc.json -q || [ $? -eq 2 ]
echo "open $OUT/report/index.html"
