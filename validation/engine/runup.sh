#!/bin/sh
# The validation engine run up from 1000 to 4000 rpm in 2 s (the crank LOF's
# speed_profile; pistons, dynamometer and crank-angle grid follow it), with IDA
# and generalized-alpha, and its main-bearing loads as it passes 3000 rpm
# against the steady 3000 rpm run (docs/validation.md, "Run-up").
#   usage: validation/engine/runup.sh BUILD_DIR OUT_DIR
# Writes OUT_DIR/runup-ida, runup-ga, runup-ida-steady (from the steady cycle at
# 1000 rpm), steady-1000, steady-3000 (periodic states), steady (six steady
# cycles at 3000 rpm, from its periodic state; results) and OUT_DIR/runup.md.
set -eu
if [ $# -lt 2 ]; then
  echo "usage: $0 BUILD_DIR OUT_DIR" >&2
  exit 1
fi
here=$(pwd)
case $1 in /*) build=$1 ;; *) build=$here/$1 ;; esac
case $2 in /*) out=$2 ;; *) out=$here/$2 ;; esac
dir=$(cd "$(dirname "$0")" && pwd)
evas=$build/evas
mkdir -p "$out"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/evas-runup.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
"$dir/scenes.sh" "$tmp"

w0=104.71975511965977   # 1000 rpm [rad/s]
w1=418.87902047863906   # 4000 rpm
w=314.15926535897932    # 3000 rpm, where the loads are compared
ramp=2
sed -e "s|speed: 314.159}|speed_profile: [[0, $w0], [$ramp, $w1]]}|" \
    -e "s|^name: engine-case1|name: engine-runup|" \
    -e "s|end: 0.24}|end: $ramp}|" "$tmp/case1.yaml" > "$tmp/runup.yaml"
# the steady run at exactly the speed compared
sed -e "s|speed: 314.159}|speed: $w}|" "$tmp/case1.yaml" > "$tmp/steady.yaml"

/usr/bin/time -f "run-up, ida: %e s wall" "$evas" run "$tmp/runup.yaml" --out "$out/runup-ida" --csv --quiet --overwrite
/usr/bin/time -f "run-up, generalized-alpha: %e s wall" "$evas" run "$tmp/runup.yaml" \
  --integrator generalized-alpha --step 5e-6 --out "$out/runup-ga" --csv --quiet --overwrite
# the steady run from its periodic state, so that its last cycle is the steady cycle
# (a 0.24-s run from rest ends 1.2e-2 from it in the bearing loads)
"$evas" periodic "$tmp/steady.yaml" --out "$out/steady-3000" --quiet --overwrite
"$evas" run "$tmp/steady.yaml" --initial "$out/steady-3000/state.yaml" --out "$out/steady" \
  --csv --quiet --overwrite
# the same IDA run-up from the steady cycle at its first speed (evas periodic's
# state at 1000 rpm, docs/periodic.md) instead of from rest
"$evas" periodic "$tmp/case1.yaml" --param "crank.lof.speed=$w0" --out "$out/steady-1000" \
  --quiet --overwrite
/usr/bin/time -f "run-up from the steady cycle, ida: %e s wall" "$evas" run "$tmp/runup.yaml" \
  --initial "$out/steady-1000/state.yaml" --out "$out/runup-ida-steady" --csv --quiet --overwrite

py=python3
{
  echo "# Run-up 1000 -> 4000 rpm in $ramp s against the steady 3000 rpm run"
  echo
  for r in ida ga ida-steady; do
    echo "## runup-$r"
    echo
    "$py" "$dir/runup_compare.py" "$out/runup-$r/results.csv" "$out/steady/results.csv" \
      "$w0" "$w1" "$ramp" "$w"
    echo
  done
} > "$out/runup.md"
cat "$out/runup.md"
