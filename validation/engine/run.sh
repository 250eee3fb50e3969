#!/bin/sh
# The paper's validation: Case 1 (soft mounts) against Case 2 (rigid ground),
# main-bearing loads over crank angle and their order spectra, and both cases
# without the thrust bearing and the belt (docs/validation.md).
#   usage: validation/engine/run.sh BUILD_DIR OUT_DIR [END_TIME]
# END_TIME (s) shortens the run (CI uses a short one; the default is the scene's 0.24 s:
# six cycles, the spectra use the last two).
set -eu
if [ $# -lt 2 ]; then
  echo "usage: $0 BUILD_DIR OUT_DIR [END_TIME]" >&2
  exit 1
fi
here=$(pwd)
case $1 in /*) build=$1 ;; *) build=$here/$1 ;; esac
case $2 in /*) out=$2 ;; *) out=$here/$2 ;; esac
end=${3:-}
dir=$(cd "$(dirname "$0")" && pwd)
evas=$build/evas
mkdir -p "$out"

# The scenes go to a temporary folder (nothing is written into the source tree).
tmp=$(mktemp -d "${TMPDIR:-/tmp}/evas-validation.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
"$dir/scenes.sh" "$tmp" "$end"
case1=$tmp/case1.yaml
case2=$tmp/case2.yaml
case3=$tmp/case3.yaml
case4=$tmp/case4.yaml
case5=$tmp/case5.yaml
case6=$tmp/case6.yaml
case7=$tmp/case7.yaml

# spectra DIR CYCLES: the order spectrum of every main-bearing load of DIR's
# results over its last CYCLES cycles, as DIR/spectrum_main<b>.<fx|fy>.csv
spectra() {
  for b in 1 2 3 4 5; do
    for ch in fx fy; do
      "$evas" spectrum "$1/results.h5" --channel main$b.$ch --max-order 12 --cycles "$2" \
        --csv "$1/spectrum_main$b.$ch.csv" > /dev/null
    done
  done
}

for c in 1 2 3 4 5 6 7; do
  echo "== case $c"
  eval scene=\$case$c
  /usr/bin/time -f "case $c: %e s wall, %M kB peak" "$evas" run "$scene" --out "$out/case$c" --csv --overwrite
  spectra "$out/case$c" 2
done

# Order table: amplitude [kN] of each main bearing's load, Case 1 / Case 2.
orders="0.5 1 1.5 2 3 4 6"
# order_table DIR1 DIR2: each main-bearing channel's amplitude [kN] at each
# order, DIR1's / DIR2's spectra, as a Markdown table
order_table() {
  printf "| channel |"
  for o in $orders; do printf " order %s |" "$o"; done
  printf "\n|---|"
  for o in $orders; do printf "%s" "---|"; done
  printf "\n"
  for b in 1 2 3 4 5; do
    for ch in fx fy; do
      printf "| main%s.%s |" "$b" "$ch"
      for o in $orders; do
        a1=$(awk -F, -v o="$o" 'NR > 1 && $1 == o {printf "%.1f", $2 / 1000}' "$1/spectrum_main$b.$ch.csv")
        a2=$(awk -F, -v o="$o" 'NR > 1 && $1 == o {printf "%.1f", $2 / 1000}' "$2/spectrum_main$b.$ch.csv")
        printf " %s / %s |" "$a1" "$a2"
      done
      printf "\n"
    done
  done
}
order_table "$out/case1" "$out/case2" > "$out/orders.md"
echo "order table (kN, Case 1 / Case 2): $out/orders.md"

# The converged basis (converged.yaml; docs/engine-bodies.md, "A converged
# basis"): its bodies built once into $out/bodies (about 1.5 and 3 min, 1.3 GB
# peak), Cases 1 and 2 on them, their order table beside the paper's basis and
# the difference of the main-bearing loads (whole last cycle, and its engine
# orders up to 12) relative to each channel's half peak-to-peak. Only with
# CONVERGED=1 (`make validate` sets it; `make demo` leaves it out: the bodies
# take 4-5 min to build).
if [ "${CONVERGED:-0}" = 1 ]; then
bodies=$out/bodies
mkdir -p "$bodies"
for b in crank_conv block_conv; do
  if [ ! -f "$bodies/$b.h5" ]; then
    /usr/bin/time -f "body $b: %e s wall, %M kB peak" "$evas" modal build \
      "$dir/../bodies/convergence/$b.yaml" --out "$bodies" > "$bodies/$b.log"
  fi
done
for c in 1 2; do
  eval scene=\$case$c
  /usr/bin/time -f "case $c, converged basis: %e s wall, %M kB peak" "$evas" run "$scene" \
    --param crank.file="$bodies/crank_conv.h5" --param block.file="$bodies/block_conv.h5" \
    --out "$out/case$c-converged" --csv --overwrite
  spectra "$out/case$c-converged" 2
done
order_table "$out/case1-converged" "$out/case2-converged" > "$out/orders_converged.md"
echo "order table on the converged basis (kN, Case 1 / Case 2): $out/orders_converged.md"
{
  for c in 1 2; do
    echo "Case $c, converged basis against the paper's, whole last cycle:"
    python3 "$dir/bearing_difference.py" "$out/case$c-converged/results.csv" "$out/case$c/results.csv"
    echo
    echo "Case $c, orders up to 12:"
    python3 "$dir/bearing_difference.py" --orders 12 "$out/case$c-converged/results.csv" \
      "$out/case$c/results.csv"
    echo
  done
} > "$out/converged_difference.md"
echo "the paper's basis against the converged one: $out/converged_difference.md"
fi

# The steady cycles of Case 1 and Case 2 (evas periodic, docs/periodic.md):
# the same order table on them, and the change from the six-cycle runs' last
# two cycles in % of the channel's largest order.
for c in 1 2 6 7; do
  eval scene=\$case$c
  /usr/bin/time -f "case $c, steady cycle: %e s wall" "$evas" periodic "$scene" \
    --out "$out/case$c-steady" --csv --overwrite --quiet
  spectra "$out/case$c-steady" 1
done
{
  printf "| channel |"
  for o in $orders; do printf " order %s |" "$o"; done
  printf "\n|---|"
  for o in $orders; do printf "%s" "---|"; done
  printf "\n"
  for b in 1 2 3 4 5; do
    for ch in fx fy; do
      printf "| main%s.%s |" "$b" "$ch"
      for o in $orders; do
        for c in 1 2; do
          st=$out/case$c-steady/spectrum_main$b.$ch.csv
          tr=$out/case$c/spectrum_main$b.$ch.csv
          peak=$(awk -F, 'NR > 1 && $2 > m {m = $2} END {print m}' "$tr")
          a=$(awk -F, -v o="$o" 'NR > 1 && $1 == o {print $2}' "$st")
          t=$(awk -F, -v o="$o" 'NR > 1 && $1 == o {print $2}' "$tr")
          awk -v a="$a" -v t="$t" -v p="$peak" -v c="$c" \
            'BEGIN {printf "%s%.1f (%+.1f %%)%s", (c == 1 ? " " : " / "), a / 1000,
                    100 * (a - t) / p, (c == 2 ? " |" : "")}'
        done
      done
      printf "\n"
    done
  done
} > "$out/orders_steady.md"
echo "order table on the steady cycles (kN, Case 1 / Case 2, change from the runs): $out/orders_steady.md"

# Case 2 three ways: stiff mounts, spherical joints, fixed joints at the pads;
# amplitudes [kN] and, for the joints, the difference to the stiff mounts in %
# of the channel's largest order.
{
  printf "| channel | order | mounts 1e9 N/m | spherical joints | fixed joints |\n"
  printf "|---|---|---|---|---|\n"
  for b in 1 2 3 4 5; do
    for ch in fx fy; do
      s2=$out/case2/spectrum_main$b.$ch.csv
      s3=$out/case3/spectrum_main$b.$ch.csv
      s4=$out/case4/spectrum_main$b.$ch.csv
      peak=$(awk -F, 'NR > 1 && $2 > m {m = $2} END {print m}' "$s2")
      for o in $orders; do
        a2=$(awk -F, -v o="$o" 'NR > 1 && $1 == o {print $2}' "$s2")
        a3=$(awk -F, -v o="$o" 'NR > 1 && $1 == o {print $2}' "$s3")
        a4=$(awk -F, -v o="$o" 'NR > 1 && $1 == o {print $2}' "$s4")
        awk -v c="main$b.$ch" -v o="$o" -v a="$a2" -v b="$a4" -v w="$a3" -v p="$peak" \
          'BEGIN {printf "| %s | %s | %.2f | %.2f (%+.1f %%) | %.2f (%+.1f %%) |\n", c, o,
                  a / 1000, b / 1000, 100 * (b - a) / p, w / 1000, 100 * (w - a) / p}'
      done
    done
  done
} > "$out/welded.md"
echo "order table (kN, Case 2 with stiff mounts, spherical joints, fixed joints): $out/welded.md"

# Case 1 with and without the element states: amplitudes [kN] and the
# difference in % of the channel's largest order.
{
  printf "| channel | order | Case 1 | with Maxwell mounts and clutch disk |\n"
  printf "|---|---|---|---|\n"
  for b in 1 2 3 4 5; do
    for ch in fx fy; do
      s1=$out/case1/spectrum_main$b.$ch.csv
      s5=$out/case5/spectrum_main$b.$ch.csv
      peak=$(awk -F, 'NR > 1 && $2 > m {m = $2} END {print m}' "$s1")
      for o in $orders; do
        a1=$(awk -F, -v o="$o" 'NR > 1 && $1 == o {print $2}' "$s1")
        a5=$(awk -F, -v o="$o" 'NR > 1 && $1 == o {print $2}' "$s5")
        awk -v c="main$b.$ch" -v o="$o" -v a="$a1" -v b="$a5" -v p="$peak" \
          'BEGIN {printf "| %s | %s | %.2f | %.2f (%+.1f %%) |\n", c, o, a / 1000, b / 1000,
                  100 * (b - a) / p}'
      done
    done
  done
} > "$out/states.md"
echo "order table (kN, Case 1 without / with element states): $out/states.md"

# Cases 1 and 2 with and without the thrust bearing and the belt (cases 6, 7):
# amplitudes [kN] and the change in % of the channel's largest order (without);
# order 0 is the mean load, where a constant belt tension acts first.
#   thrust_belt SUFFIX: the folders case<c>SUFFIX ("" the runs' last two
#   cycles, "-steady" the steady cycles)
thrust_belt() {
  sfx=$1
  printf "| channel | order | Case 1 without | Case 1 with | Case 2 without | Case 2 with |\n"
  printf "|---|---|---|---|---|---|\n"
  for b in 1 2 3 4 5; do
    for ch in fx fy; do
      for o in 0 $orders; do
        printf "| main%s.%s | %s |" "$b" "$ch" "$o"
        for pair in "6 1" "7 2"; do
          set -- $pair
          s0=$out/case$1$sfx/spectrum_main$b.$ch.csv
          s1=$out/case$2$sfx/spectrum_main$b.$ch.csv
          peak=$(awk -F, 'NR > 1 && $1 > 0 && $2 > m {m = $2} END {print m}' "$s0")
          a0=$(awk -F, -v o="$o" 'NR > 1 && $1 == o {print $2}' "$s0")
          a1=$(awk -F, -v o="$o" 'NR > 1 && $1 == o {print $2}' "$s1")
          awk -v a="$a0" -v b="$a1" -v p="$peak" \
            'BEGIN {printf " %.2f | %.2f (%+.2f, %+.1f %%) |", a / 1000, b / 1000, (b - a) / 1000,
                    100 * (b - a) / p}'
        done
        printf "\n"
      done
    done
  done
}
thrust_belt "" > "$out/thrust_belt.md"
thrust_belt -steady > "$out/thrust_belt_steady.md"
# what the two elements carry in Cases 1 and 2, over the last two cycles
for c in 1 2; do
  awk -F, -v c="$c" '
    NR == 1 {for (i = 1; i <= NF; i++) col[$i] = i; next}
    {row[NR] = $0; n = NR}
    END {
      from = n - 1439
      for (r = from; r <= n; r++) {
        split(row[r], v, ",")
        f = v[col["thrust.force[N]"]]; d = v[col["thrust.displacement[m]"]]
        if (f < 0) f = -f; if (d < 0) d = -d
        if (f > fm) fm = f; if (d > dm) dm = d
        px += v[col["belt.pulley0_fx[N]"]]; py += v[col["belt.pulley0_fy[N]"]]; k++
      }
      printf "Case %s: thrust bearing max |F| %.3g N, max |d| %.1f um (gap 50 um); ", c, fm, 1e6 * dm
      printf "belt load on the crank pulley, mean (y, z) = (%.0f, %.0f) N\n", px / k, py / k
    }' "$out/case$c/results.csv"
done | tee "$out/thrust_belt_loads.txt"
echo "order table (kN, Cases 1 and 2 without / with thrust bearing and belt): $out/thrust_belt.md"
echo "the same on the steady cycles: $out/thrust_belt_steady.md"

if ! command -v gnuplot >/dev/null 2>&1; then
  echo "validation: gnuplot not found, no plots; results in $out" >&2
  exit 0
fi
if gnuplot -e "set terminal" 2>&1 | grep -q pngcairo; then
  term="pngcairo size 1100,900 font 'sans,10'"
else
  term="png size 1100,900"
fi
gnuplot <<GP
set terminal $term
set output "$out/main_bearing_load.png"
set datafile separator ","
set grid
set key below horizontal
set multiplot layout 2,1 title "Main bearing 3 load, in-line four at 3000 rpm full load: soft mounts (Case 1) vs rigid ground (Case 2)"
set xlabel "crank angle [deg] (last 720 deg)"
set ylabel "F (bearing x = -z_G, vertical) [kN]"
n1 = system("wc -l < $out/case1/results.csv") - 1
n2 = system("wc -l < $out/case2/results.csv") - 1
stats "$out/case1/results.csv" every ::(n1-720)::(n1-720) using 2 nooutput
a1 = STATS_min
stats "$out/case2/results.csv" every ::(n2-720)::(n2-720) using 2 nooutput
a2 = STATS_min
plot "$out/case1/results.csv" every ::(n1-720) using (column(2)-a1):(column("main3.fx[N]")/1000) with lines lw 1.5 title "Case 1 soft mounts", \
     "$out/case2/results.csv" every ::(n2-720) using (column(2)-a2):(column("main3.fx[N]")/1000) with lines lw 1.5 dt 2 title "Case 2 rigid ground"
set xlabel "order (multiples of crank speed)"
set ylabel "amplitude [kN]"
set style fill solid 0.6
set boxwidth 0.2
plot "$out/case1/spectrum_main3.fx.csv" skip 1 using (\$1-0.1):(\$2/1000) with boxes title "Case 1", \
     "$out/case2/spectrum_main3.fx.csv" skip 1 using (\$1+0.1):(\$2/1000) with boxes title "Case 2"
unset multiplot
GP
echo "validation results: $out/case1, $out/case2, $out/case3 (fixed joints), $out/case4 (spherical joints), $out/case5 (element states), $out/case6, $out/case7 (Cases 1, 2 without thrust bearing and belt), $out/main_bearing_load.png"
