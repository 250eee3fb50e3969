#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer run of a subset of the test
# suite (docs/fuzzing.md, "Sanitizer subset").
#
#   scripts/sanitize.sh [BUILD_DIR]        (default build-asan)
#
# Configures the top-level project with GCC, -fsanitize=address,undefined
# -fno-omit-frame-pointer -fno-sanitize-recover=undefined, -O1 -g, assertions
# on (Eigen's index checks included) and -DEVAS_WERROR=ON; builds only the test
# executables below and runs each with
#   ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
#   UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
# Exits 1 if any executable reports a sanitizer error, 2 if a test fails without
# one, 0 if all pass. Logs: BUILD_DIR/sanitize-logs/<test>.log.
#
# Environment: JOBS (build jobs, default 1), SANITIZE_TESTS (override the list,
# entries "name" or "name:gtest_filter").
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build-asan}"
jobs="${JOBS:-1}"

# Input parsing (scene, body file, pressure table, CalculiX, results), the force
# elements, every integrator and step control, the study driver and the system
# Jacobian. Left out: the engine-size tests (test_engine_*, test_validation_engine,
# test_coupled_bodies, test_stability ...) that take minutes without a sanitizer,
# and test_calculix's Cylinder.* suite, which meshes and solves with gmsh and ccx
# (external programs, not instrumented; ~40 s in Release).
default_tests="test_scene test_scene_elements test_body_file test_results test_gas_pressure
  test_calculix:Calculix* test_journal_bearing test_integrators_sdof test_step_control
  test_study test_system_jacobian"
tests="${SANITIZE_TESTS:-$default_tests}"

san="-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined"
t0=$(date +%s)
CC=gcc CXX=g++ cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Debug \
  -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" -DCMAKE_C_FLAGS_DEBUG="-O1 -g" \
  -DCMAKE_CXX_FLAGS="$san" -DCMAKE_C_FLAGS="$san" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" -DEVAS_WERROR=ON >/dev/null
targets=""
for t in $tests; do targets="$targets ${t%%:*}"; done
# gtest_discover_tests runs each executable at build time: with the sanitizer's
# options, so a report at start-up already stops the build.
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
# shellcheck disable=SC2086
cmake --build "$build" -j"$jobs" --target $targets
t1=$(date +%s)

logs="$build/sanitize-logs"
mkdir -p "$logs"
reports=0
failures=0
printf '%-24s %7s  %s\n' test seconds result
for t in $tests; do
  name="${t%%:*}"
  filter="*"
  [ "$name" != "$t" ] && filter="${t#*:}"
  s=$(date +%s)
  rc=0
  (cd "$build/tests" && "./$name" --gtest_filter="$filter") >"$logs/$name.log" 2>&1 || rc=$?
  e=$(date +%s)
  if grep -qE 'ERROR: (AddressSanitizer|LeakSanitizer)|runtime error:|SUMMARY: (Address|Undefined|Leak)' \
       "$logs/$name.log"; then
    result="SANITIZER REPORT (see $logs/$name.log)"
    reports=$((reports + 1))
    grep -m1 -E 'ERROR: (AddressSanitizer|LeakSanitizer)|runtime error:' "$logs/$name.log" | sed 's/^/    /'
  elif [ "$rc" -ne 0 ]; then
    result="FAILED, exit $rc, no sanitizer report (see $logs/$name.log)"
    failures=$((failures + 1))
  else
    result="ok"
  fi
  printf '%-24s %7d  %s\n' "$name" $((e - s)) "$result"
done
t2=$(date +%s)
echo "sanitize: build $((t1 - t0)) s (-j$jobs), run $((t2 - t1)) s;" \
     "$reports executable(s) with sanitizer reports, $failures failing without one"
[ "$reports" -eq 0 ] || exit 1
[ "$failures" -eq 0 ] || exit 2
