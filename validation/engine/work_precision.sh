#!/bin/sh
# Work-precision of every integrator and iteration on the paper's engine
# (validation/engine/engine.yaml), Case 1 (soft mounts) and Case 2 (stiff
# mounts, 1e9 N/m: the block on rigid ground), full 0.24 s, by `evas study`.
#   usage: validation/engine/work_precision.sh BUILD_DIR OUT_DIR [CASES...]
# CASES: 1, 2 or both (default). Writes OUT_DIR/case1/study.{csv,md,h5,png} ...
# Takes about 10 minutes per case on one core (the paper's fixed point alone
# about 4 minutes); `make work-precision` copies the tables and figures into
# docs/work-precision/.
set -eu
if [ $# -lt 2 ]; then
  echo "usage: $0 BUILD_DIR OUT_DIR [1] [2]" >&2
  exit 1
fi
here=$(pwd)
case $1 in /*) build=$1 ;; *) build=$here/$1 ;; esac
case $2 in /*) out=$2 ;; *) out=$here/$2 ;; esac
shift 2
cases=${*:-1 2}
dir=$(cd "$(dirname "$0")" && pwd)
evas=$build/evas
# run from the project root with the scene given relative to it, so that the
# tables it writes (and docs/work-precision/ keeps) name no machine's paths
cd "$dir/../.."

for c in $cases; do
  case $c in
    1) params="" ;;
    2) params="--param mount*.k_x=[1e9] --param mount*.k_y=[1e9] --param mount*.k_z=[1e9] --param mount*.damping=[1e4,1e4,1e4]" ;;
    *) echo "$0: case must be 1 or 2, got '$c'" >&2; exit 1 ;;
  esac
  echo "== engine case $c"
  # shellcheck disable=SC2086
  "$evas" study work-precision validation/engine/engine.yaml $params --out "$out/case$c" \
    --channels 'main*.fx,main*.fy' --window last-cycles=1 --repeats 2 \
    --reference "ida rtol=1e-9 atol=1e-12" \
    --case "ida rtol=1e-3..1e-7/5" \
    --case "cvode rtol=1e-3..1e-6/4" \
    --case "cvode method=adams rtol=1e-4 max_steps=1000" \
    --case "generalized-alpha step=2e-5,1e-5,5e-6,2.5e-6" \
    --case "generalized-alpha step_control=adaptive rtol=1e-3..1e-5/3" \
    --case "linear-acceleration iteration=effective-mass step=2e-5,1e-5,5e-6,2.5e-6" \
    --case "linear-acceleration iteration=effective-mass step_control=adaptive rtol=1e-3,1e-4" \
    --case "linear-acceleration iteration=newton step=1e-5,5e-6" \
    --case "linear-acceleration iteration=anderson step=1e-5,5e-6" \
    --case "linear-acceleration iteration=fixed-point step=5e-7" \
    --case "radau step_control=adaptive step=1e-5 rtol=1e-3..1e-6/4" \
    --case "hht-alpha alpha=-0.1 step=2e-5,1e-5,5e-6,2.5e-6" \
    --case "newmark step=2e-5,1e-5,5e-6,2.5e-6" \
    --case "central-difference step=5e-6,2.5e-6" \
    --case "arkode linear_solver=second-order rtol=1e-3..1e-5/3" \
    --case "arkode table=ARKODE_ARK324L2SA_DIRK_4_2_3 imex=elements linear_solver=klu rtol=1e-4" \
    --case "bathe step=2e-5,1e-5,5e-6"
done
