#!/bin/sh
# Demo: run scenes/demo.yaml, export CSV, plot a coupling force and a marker
# displacement over time.   usage: scripts/demo.sh BUILD_DIR OUT_DIR
set -eu

if [ $# -ne 2 ]; then
  echo "usage: $0 BUILD_DIR OUT_DIR" >&2
  exit 1
fi
here=$(pwd)
case $1 in /*) build=$1 ;; *) build=$here/$1 ;; esac
case $2 in /*) out=$2 ;; *) out=$here/$2 ;; esac
root=$(cd "$(dirname "$0")/.." && pwd)
evas=$build/evas
if [ ! -x "$evas" ]; then
  echo "demo: $evas not found; build first (make build)" >&2
  exit 1
fi
mkdir -p "$out"

echo "== evas run scenes/demo.yaml"
"$evas" run "$root/scenes/demo.yaml" --out "$out" --csv --overwrite

if ! command -v gnuplot >/dev/null 2>&1; then
  echo "demo: gnuplot not found, no plot; results in $out" >&2
  exit 0
fi
if gnuplot -e "set terminal" 2>&1 | grep -q pngcairo; then
  term="pngcairo size 1000,800 font 'sans,10'"
else
  term="png size 1000,800"
fi

echo "== plotting $out/demo.png"
gnuplot <<GP
set terminal $term
set output "$out/demo.png"
set datafile separator ","
set grid
set key below horizontal
set multiplot layout 2,1 title "evas demo: flexible shaft spinning at 300 rad/s on a flexible frame hung on springs\\n(gravity drop + once-per-revolution dynamic-imbalance load)"
set ylabel "element force [N]"
set xlabel ""
plot "$out/results.csv" using 1:(column("bearing_left.fz[N]")) with lines lw 1.5 title "bearing\\\_left F_z (frame to shaft)", \
     ""                 using 1:(column("bearing_left.fy[N]")) with lines lw 1.5 title "bearing\\\_left F_y", \
     ""                 using 1:(column("mount_left.fz[N]")) with lines lw 1.5 title "mount\\\_left F_z (frame on ground)"
set ylabel "vertical displacement [mm]"
set key top right
set xlabel "time [s]"
plot "$out/results.csv" using 1:(1000*column("shaft_mid.pz[m]")) with lines lw 1.5 title "shaft mid-span", \
     ""                 using 1:(1000*(column("frame_right.pz[m]")+0.1)) with lines lw 1.5 title "frame right end"
unset multiplot
GP

echo
echo "demo results:"
echo "  $out/results.h5    (HDF5: /time, /channels/values, names, units, stats)"
echo "  $out/results.csv"
echo "  $out/summary.json"
echo "  $out/demo.png"
