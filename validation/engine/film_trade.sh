#!/bin/sh
# The validation engine's five main bearings with each film model (short, the
# paper's; finite, Butenschoen's closed form; reynolds, Reynolds' equation with
# the Swift-Stieber condition, tabulated), Case 1 and Case 2: whole-process wall
# time, each integrator's steps, and the main-bearing loads, orbits, minimum
# film and friction power against reynolds (validation/engine/film_trade.py;
# docs/elements-journal-bearing.md, "The films on the engine"). Every other
# integrator of the catalogue runs Case 1 with the short and reynolds films.
# FILM_TRADE_EXTRA adds films solved on the grid at each evaluation:
# reynolds-grid (72 x 8), reynolds-grid36 (36 x 4), reynolds-groove36 (36 x 4
# with a circumferential groove fed at 3 bar).
#   usage: validation/engine/film_trade.sh BUILD_DIR OUT_DIR [END_TIME]
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
tmp=$(mktemp -d "${TMPDIR:-/tmp}/evas-films.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
"$dir/scenes.sh" "$tmp" "$end"

# film FILM: the --param options giving the five main bearings that film
film() {
  for b in 1 2 3 4 5; do
    case $1 in
      reynolds) printf ' --param main%s.film=reynolds --param main%s.solve=table' "$b" "$b" ;;
      reynolds-grid) printf ' --param main%s.film=reynolds --param main%s.solve=grid' "$b" "$b" ;;
      reynolds-grid36) printf ' --param main%s.film=reynolds --param main%s.solve=grid --param main%s.grid_phi=36 --param main%s.grid_axial=4' "$b" "$b" "$b" "$b" ;;
      # a circumferential groove 4 mm wide at the mid-plane, fed at 3 bar (two lands of 15.5 mm)
      reynolds-groove36) printf ' --param main%s.film=reynolds --param main%s.solve=grid --param main%s.grid_phi=36 --param main%s.grid_axial=4 --param main%s.feed=circumferential-groove --param main%s.feed_width=0.004 --param main%s.supply_pressure=3e5' "$b" "$b" "$b" "$b" "$b" "$b" "$b" ;;
      *) printf ' --param main%s.film=%s' "$b" "$1" ;;
    esac
  done
}

# integrator NAME: its --integrator/--set options (the scene's ida; cvode; generalized-alpha
# adaptive; and, Case 1 with the short and reynolds films only, the rest of the catalogue at
# settings of the engine's work-precision diagram, validation/engine/work_precision.sh)
integrator() {
  case $1 in
    ida) ;;
    cvode) printf ' --integrator cvode --set rtol=1e-5 --set atol=1e-9' ;;
    ga) printf ' --integrator generalized-alpha --set step_control=adaptive --set rtol=3e-4 --set atol=3e-8 --set step=8e-6' ;;
    radau) printf ' --integrator radau --set step_control=adaptive --set step=1e-5 --set rtol=1e-4' ;;
    hht) printf ' --integrator hht-alpha --set alpha=-0.1 --set step=5e-6' ;;
    newmark) printf ' --integrator newmark --set step=5e-6' ;;
    bathe) printf ' --integrator bathe --set step=5e-6' ;;
    linacc) printf ' --integrator linear-acceleration --set iteration=effective-mass --set step=5e-6' ;;
    arkode) printf ' --integrator arkode --set linear_solver=second-order --set rtol=1e-4' ;;
    cd) printf ' --integrator central-difference --set step=2e-7' ;;
  esac
}
EXTRA_INTEGRATORS="radau hht newmark bathe linacc arkode cd"

[ "${FILM_TRADE_PLOT_ONLY:-}" ] || for c in 1 2; do
  for f in short finite reynolds ${FILM_TRADE_EXTRA:-}; do
    more=""
    [ "$c" = 1 ] && { [ "$f" = short ] || [ "$f" = reynolds ]; } && more=$EXTRA_INTEGRATORS
    for i in ida cvode ga $more; do
      d=$out/case$c/$f/$i
      rm -rf "$d"
      s=$(date +%s.%N)
      # shellcheck disable=SC2046
      "$evas" run "$tmp/case$c.yaml" --out "$d" --quiet $(film "$f") $(integrator "$i") \
        2> "$out/case$c-$f-$i.log" || echo "case $c, film $f, $i: failed (see $out/case$c-$f-$i.log)"
      e=$(date +%s.%N)
      echo "$s $e" | awk '{printf "%.3f\n", $2 - $1}' > "$d.wall" 2>/dev/null || true
      [ -f "$d/results.h5" ] && "$evas" export "$d/results.h5" --csv "$d/results.csv" > /dev/null
    done
  done
done
python3 "$dir/film_trade.py" "$out" > "$out/film_trade.md"
cat "$out/film_trade.md"

# The figure: main bearing 3's load and minimum film over the last cycle of Case 1
# (ida), one curve per film.
fig=$out/film_trade.png
plot=""
for f in short finite reynolds; do
  csv=$out/case1/$f/ida/results.csv
  [ -f "$csv" ] || continue
  # crank angle of the last cycle from 0, |F| [kN], h_min [um]
  awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) { if ($i ~ /^crank_angle\[/) a = i;
             if ($i ~ /^main3\.fx\[/) x = i; if ($i ~ /^main3\.fy\[/) y = i;
             if ($i ~ /^main3\.h_min\[/) h = i }; next }
           { n++; A[n] = $a; F[n] = sqrt($x * $x + $y * $y) / 1000; H[n] = $h * 1e6 }
           END { for (i = 1; i <= n; i++) if (A[i] >= A[n] - 720 - 1e-9)
                   printf "%.3f %.6g %.6g\n", A[i] - (A[n] - 720), F[i], H[i] }' \
    "$csv" > "$tmp/$f.dat"
done
if command -v gnuplot > /dev/null; then
  gnuplot <<GP
set terminal pngcairo size 1000,720 font ",11"
set output "$fig"
set multiplot layout 2,1 title "Validation engine, Case 1, main bearing 3, last cycle (0.20-0.24 s, not settled): the three film models"
set key top right
set grid
set xrange [0:720]
set xtics 90
set ylabel "load |F| [kN]"
set format x ""
plot "$tmp/short.dat" u 1:2 w l lw 2 t "short (Ocvirk, the paper's)", \
     "$tmp/finite.dat" u 1:2 w l lw 2 t "finite (Butenschoen)", \
     "$tmp/reynolds.dat" u 1:2 w l lw 2 dt 2 t "reynolds (Swift-Stieber, table of 72 x 8)"
set format x "%g"
set xlabel "crank angle in the cycle [deg]"
set ylabel "minimum film h_{min} [um]"
plot "$tmp/short.dat" u 1:3 w l lw 2 t "short", \
     "$tmp/finite.dat" u 1:3 w l lw 2 t "finite", \
     "$tmp/reynolds.dat" u 1:3 w l lw 2 dt 2 t "reynolds"
unset multiplot
GP
  echo "figure: $fig"
else
  echo "gnuplot not found: no figure (apt-get install gnuplot-nox)"
fi
