#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer run of a subset of the test
# suite and of the evas program (docs/fuzzing.md, "Sanitizer subset").
#
#   scripts/sanitize.sh [BUILD_DIR]        (default build-fuzz)
#
# Builds with clang in the fuzz/ project (the same instrumented library as the
# fuzzers, -O1 -gline-tables-only): the test executables below into
# BUILD_DIR/tests and the evas program, which test_bad_inputs (the bad-input
# catalogue, tests/data/bad) and test_run_faults run, so every evas process they
# start is sanitized too. Each test runs with
#   ASAN_OPTIONS=detect_leaks=1:log_path=...   UBSAN_OPTIONS=halt_on_error=1:log_path=...
# so that a report of any process, the test's own or a child's, lands in a file.
# Exits 1 if there is any sanitizer report, 2 if a test fails without one, 0 if
# all pass. Logs: BUILD_DIR/sanitize-logs/<test>.log and reports/.
#
# Environment: JOBS (build jobs, default 1), SANITIZE_TESTS (override the list,
# entries "name" or "name:gtest_filter").
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build-fuzz}"
jobs="${JOBS:-1}"

# shellcheck source=scripts/clang_deps.sh
. scripts/clang_deps.sh

# Input parsing (scene, body file, pressure table, CalculiX, results), the bad-input
# catalogue and the run faults through the evas program, the force elements, every
# integrator and step control, constrained systems and their test problems, the
# study driver and the system Jacobian. Left out: the engine-size tests
# (test_engine_*, test_validation_engine, test_coupled_bodies, test_stability ...)
# that take minutes without a sanitizer, and test_calculix's Cylinder.* suite,
# which meshes and solves with gmsh and ccx (external programs, not instrumented).
# Of test_problems and test_run_faults_output the longest runs are left out
# (slider crank to its end, the portable-build digits, Radau in every index;
# a second run into a locked folder, a study stopped by SIGTERM, the stalled
# steps): each took 20 to 40 s under the sanitizers and repeats code paths
# the subset's other tests cover; the plain suite (make test) runs them.
default_tests="test_scene test_scene_elements test_marker_fit test_body_file test_results
  test_gas_pressure test_calculix:Calculix* test_journal_bearing test_journal_bearing_rotor
  test_integrators_sdof test_step_control test_study test_system_jacobian test_bad_inputs
  test_run_faults
  test_run_faults_output:-RunFaults.SecondRunIntoTheSameFolderIsRefused:RunFaults.StudyStopsOnSigtermWithItsOutputs:RunFaults.StepsThatNoLongerAdvanceTimeEndTheRun
  test_joints test_dae_formulations test_ida_dae test_newmark_dae
  test_problems:-Problems.SliderCrankCompletes:Problems.DigitsAgreeWithThePortableBuild:Problems.RadauSolvesEveryIndex
  test_second_order_ls test_fast_nvector test_radau test_study_tasks
  test_arkode:-Arkode.RunsThePapersEngine test_amplification test_instability_named
  test_bathe:-Bathe.RunsThePapersEngine test_film_models:-FilmModels.ReynoldsGridConvergence
  test_film_feed:-FilmFeed.TwoAxialGroovesMatchLundThomsen
  test_film_cavitation:-FilmCavitation.MassConservingMatchesRaimondiBoyd
  test_study_sweep:StudySweep.ForkedWorkers*"
tests=""
for t in ${SANITIZE_TESTS:-$default_tests}; do
  [ -f "tests/${t%%:*}.cpp" ] && tests="$tests $t"
done
names=""
for t in $tests; do names="$names;${t%%:*}"; done

t0=$(date +%s)
CC=clang CXX=clang++ cmake -S fuzz -B "$build" -DEVAS_SANITIZE_TESTS="${names#;}" >/dev/null
# one goal (fuzz/CMakeLists.txt): the tests compile -j$jobs at a time
cmake --build "$build" -j"$jobs" --target evas_sanitize_tests
t1=$(date +%s)

logs="$build/sanitize-logs"
rm -rf "$logs"
mkdir -p "$logs/reports"
reports_dir="$(cd "$logs/reports" && pwd)"
export ASAN_OPTIONS="detect_leaks=1:log_path=$reports_dir/asan"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:log_path=$reports_dir/ubsan"
reports=0
failures=0
printf '%-24s %7s  %s\n' test seconds result
for t in $tests; do
  name="${t%%:*}"
  filter="*"
  [ "$name" != "$t" ] && filter="${t#*:}"
  before=$(ls "$reports_dir" | wc -l)
  s=$(date +%s)
  rc=0
  (cd "$build/tests" && "./$name" --gtest_filter="$filter") >"$logs/$name.log" 2>&1 || rc=$?
  e=$(date +%s)
  after=$(ls "$reports_dir" | wc -l)
  if [ "$after" -gt "$before" ]; then
    result="SANITIZER REPORT ($((after - before)) file(s) in $reports_dir)"
    reports=$((reports + 1))
    for f in $(ls -t "$reports_dir" | head -"$((after - before))"); do
      grep -m1 -E 'ERROR: (AddressSanitizer|LeakSanitizer)|runtime error:' "$reports_dir/$f" |
        sed 's/^/    /' || true
      mv "$reports_dir/$f" "$reports_dir/$name.$f"
    done
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
