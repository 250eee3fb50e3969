#!/bin/sh
# A fixed set of runs whose results must not change under a refactoring: the
# validation engine's five scenes with their own integrator, Case 1 and Case 2
# with every integrator and iteration, the demo, the jointed beam, the DAE test
# problems in every formulation and a one-case study. Compare two such folders
# with scripts/compare_runs.sh (docs/architecture.md, "No behaviour change").
#   usage: scripts/reference_runs.sh BUILD_DIR OUT_DIR [END_TIME]
# END_TIME (s) of the engine runs, default 0.02 (a third of a cycle at 3000 rpm).
set -eu
if [ $# -lt 2 ]; then
  echo "usage: $0 BUILD_DIR OUT_DIR [END_TIME]" >&2
  exit 1
fi
here=$(pwd)
case $1 in /*) build=$1 ;; *) build=$here/$1 ;; esac
case $2 in /*) out=$2 ;; *) out=$here/$2 ;; esac
end=${3:-0.02}
root=$(cd "$(dirname "$0")/.." && pwd)
evas=$build/evas
mkdir -p "$out"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/evas-reference.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
"$root/validation/engine/scenes.sh" "$tmp" "$end"

# evas run into out/NAME; a failed run (exit 2) is a result too
run() {
  name=$1
  shift
  code=0
  "$evas" run "$@" --out "$out/$name" --csv --quiet --overwrite > "$out/$name.log" 2>&1 || code=$?
  echo "$code" > "$out/$name.exit"
  echo "  $name: exit $code"
}

echo "== engine scenes with their own integrator"
for c in 1 2 3 4 5; do run "case$c" "$tmp/case$c.yaml"; done

echo "== Case 1 and Case 2 with every integrator and iteration"
for c in 1 2; do
  s=$tmp/case$c.yaml
  run "case$c-ida-klu" "$s" --integrator ida --rtol 1e-5 --set linear_solver=klu
  run "case$c-ida-second-order" "$s" --integrator ida --rtol 1e-5 --set linear_solver=second-order
  run "case$c-cvode" "$s" --integrator cvode --rtol 1e-5
  run "case$c-cvode-adams" "$s" --integrator cvode --rtol 1e-4 --set method=adams --set max_steps=2000
  for it in default fixed-point anderson effective-mass newton; do
    run "case$c-ga-$it" "$s" --integrator generalized-alpha --step 1e-5 --set iteration=$it
    run "case$c-la-$it" "$s" --integrator linear-acceleration --step 1e-5 --set iteration=$it
  done
  run "case$c-ga-adaptive" "$s" --integrator generalized-alpha --set step_control=adaptive --rtol 1e-4
  run "case$c-la-adaptive" "$s" --integrator linear-acceleration --set iteration=effective-mass \
    --set step_control=adaptive --rtol 1e-4
  run "case$c-la-fixed" "$s" --integrator linear-acceleration --step 2e-5 --set step_control=fixed
  run "case$c-radau" "$s" --integrator radau --step 2e-5
  run "case$c-radau-adaptive" "$s" --integrator radau --set step_control=adaptive --rtol 1e-5
done

echo "== demo and jointed beam"
run demo "$root/scenes/demo.yaml"
run hinged-beam "$root/scenes/hinged_beam.yaml"
for f in index-3 index-2 ggl index-1 penalty; do
  run "hinged-beam-$f" "$root/scenes/hinged_beam.yaml" --integrator ida --set formulation=$f
done
run hinged-beam-ga "$root/scenes/hinged_beam.yaml" --integrator generalized-alpha --step 1e-4

echo "== DAE test problems"
for p in andrews car-axis pendulum; do
  for f in ggl index-2 index-1 index-3 penalty; do
    for r in 1e-4 1e-8; do
      code=0
      "$evas" problem "$p" --formulation $f --rtol $r --overwrite --out "$out/problem-$p-$f-$r" \
        > "$out/problem-$p-$f-$r.log" 2>&1 || code=$?
      echo "$code" > "$out/problem-$p-$f-$r.exit"
    done
  done
  for i in generalized-alpha linear-acceleration radau; do
    code=0
    "$evas" problem "$p" --integrator $i --overwrite --out "$out/problem-$p-$i" \
      > "$out/problem-$p-$i.log" 2>&1 || code=$?
    echo "$code" > "$out/problem-$p-$i.exit"
  done
done
echo "  problems done"

echo "== a study"
"$evas" study work-precision "$root/scenes/demo.yaml" --t-end 0.02 --out "$out/study" --quiet \
  --case "ida rtol=1e-4,1e-6" --case "generalized-alpha step=1e-4" > "$out/study.log" 2>&1 ||
  echo "  study: exit $?"
echo "reference runs in $out"
