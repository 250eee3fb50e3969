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
# (log_path = reports/<test>.asan, reports/<test>.ubsan), so that a report of any
# process, the test's own or a child's, lands in a file named after the test.
# Exits 1 if there is any sanitizer report, 2 if a test fails without one, 0 if
# all pass. Logs: BUILD_DIR/sanitize-logs/<test>.log and reports/.
#
# Environment: JOBS (build jobs and tests run at a time, default 1), SANITIZE_TESTS
# (override the list,
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
# the subset's other tests cover; the plain suite (make test) runs them. So do
# test_study_sweep (the engine's sweep twice, 142 s under the sanitizers: the
# worker processes are test_study_tasks' too) and the feeds' bearing command
# (FilmFeed.BearingCommandTakesTheFeed, 22 s: the command's code is
# FilmCavitation.BearingCommand's, the feeds' the in-process tests'), and of
# test_bearing_orbit the Reynolds film's orbit and the rod cycle at 1e-9 (78 s
# under the sanitizers: 20,000 steps of code the short film's orbits run).
# The list starts with the longest (seconds under the sanitizers in CI): two run
# side by side to the end instead of one long test running alone last.
default_tests="test_bad_inputs test_study_tasks test_film_models:-FilmModels.ReynoldsGridConvergence
  test_study test_run_faults test_film_cavitation:-FilmCavitation.MassConservingMatchesRaimondiBoyd
  test_problems:-Problems.SliderCrankCompletes:Problems.DigitsAgreeWithThePortableBuild:Problems.RadauSolvesEveryIndex
  test_run_faults_output:-RunFaults.SecondRunIntoTheSameFolderIsRefused:RunFaults.StudyStopsOnSigtermWithItsOutputs:RunFaults.StepsThatNoLongerAdvanceTimeEndTheRun
  test_calculix:Calculix* test_ida_dae test_second_order_ls test_journal_bearing_rotor
  test_scene_elements test_bearing_orbit:-BearingOrbit.ReynoldsFilmRidesAtTheEffectiveSpeedsEccentricity:BearingOrbit.RodCycleConvergesWithTheTolerance
  test_marker_fit test_journal_bearing test_bathe:-Bathe.RunsThePapersEngine test_film_feed:-FilmFeed.TwoAxialGroovesMatchLundThomsen:FilmFeed.BearingCommandTakesTheFeed
  test_scene test_results test_gas_pressure test_integrators_sdof test_step_control
  test_system_jacobian test_newmark_dae test_fast_nvector test_arkode:-Arkode.RunsThePapersEngine
  test_amplification test_instability_named test_body_file test_joints test_dae_formulations
  test_radau"
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

# One test executable, its reports in files named after it (log_path is a
# prefix: ASan and UBSan append the process id, so the test's own reports and
# those of every evas process it starts land beside each other). Writes one
# line "seconds exit-code" to $logs/$name.rc.
run_one() {
  local name="${1%%:*}" filter="*" s rc=0
  [ "$name" != "$1" ] && filter="${1#*:}"
  s=$(date +%s)
  (cd "$build/tests" &&
    ASAN_OPTIONS="detect_leaks=1:log_path=$reports_dir/$name.asan" \
      UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:log_path=$reports_dir/$name.ubsan" \
      "./$name" --gtest_filter="$filter") >"$logs/$name.log" 2>&1 || rc=$?
  echo "$(($(date +%s) - s)) $rc" >"$logs/$name.rc"
}

# $jobs tests at a time (the machine's cores; each test is one process apart
# from the evas programs it starts), the results printed in the list's order.
running=0
for t in $tests; do
  if [ "$running" -ge "$jobs" ]; then
    wait -n || true
    running=$((running - 1))
  fi
  run_one "$t" &
  running=$((running + 1))
done
wait || true

reports=0
failures=0
printf '%-24s %7s  %s\n' test seconds result
for t in $tests; do
  name="${t%%:*}"
  read -r secs rc <"$logs/$name.rc"
  found=$(cd "$reports_dir" && ls "$name".asan.* "$name".ubsan.* 2>/dev/null || true)
  if [ -n "$found" ]; then
    result="SANITIZER REPORT ($(echo "$found" | wc -l) file(s) in $reports_dir)"
    reports=$((reports + 1))
    for f in $found; do
      grep -m1 -E 'ERROR: (AddressSanitizer|LeakSanitizer)|runtime error:' "$reports_dir/$f" |
        sed 's/^/    /' || true
    done
  elif [ "$rc" -ne 0 ]; then
    result="FAILED, exit $rc, no sanitizer report (see $logs/$name.log)"
    failures=$((failures + 1))
  else
    result="ok"
  fi
  printf '%-24s %7d  %s\n' "$name" "$secs" "$result"
done
t2=$(date +%s)
echo "sanitize: build $((t1 - t0)) s (-j$jobs), run $((t2 - t1)) s (-j$jobs);" \
     "$reports executable(s) with sanitizer reports, $failures failing without one"
[ "$reports" -eq 0 ] || exit 1
[ "$failures" -eq 0 ] || exit 2
