#!/bin/sh
# The figure gallery (docs/figures/README.md): `evas plot` of every kind on the
# validation engine's Case 1 results (validation/engine/run.sh).
#   scripts/figures.sh BUILD_DIR RESULTS.h5 OUT_DIR
# `make demo` draws it into its output folder; `make docs` copies it to
# docs/figures/.
set -eu
if [ $# -ne 3 ]; then
  echo "usage: $0 BUILD_DIR RESULTS.h5 OUT_DIR" >&2
  exit 1
fi
evas=$1/evas
r=$2
out=$3
mkdir -p "$out"
plot() {
  kind=$1
  name=$2
  shift 2
  "$evas" plot "$kind" "$r" --out "$out/$name.png" "$@" > /dev/null
  echo "$out/$name.png"
}
plot channels bearing_loads --channel 'main*.fy' --cycles 1 \
  --title 'main-bearing loads: horizontal force on each journal (fy, bearing axes), last cycle'
plot polar polar_main3 --element main3
plot orbit orbit_main3 --element main3
plot film film_main3 --element main3
plot channels friction_power --channel 'main*.friction_power' --cycles 1 \
  --title 'main-bearing friction power (Petroff plus short-bearing film), last cycle'
plot channels crank_torsion --channel 'crank.angle_a' --channel 'crank.angle_b' \
  --channel 'crank.twist' --cycles 1 \
  --title 'crankshaft torsion relative to its LOF: front main journal (a), flywheel (b), twist b - a'
plot order order_main3_fy --channel main3.fy --cycles 2
plot spectrum spectrum_main3_fy --channel main3.fy --window flattop --from 0.08 --max-frequency 1500
plot channels surface_velocity --channel 'skin.vn_rms' --channel 'skin.vn_mean' --cycles 1 \
  --title 'normal velocity of the block side walls: area-weighted RMS and mean over the set, last cycle'
plot erp erp_side_walls --channel skin --from 0.08
