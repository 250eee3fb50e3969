#!/usr/bin/env bash
# libFuzzer run of the evas input readers (docs/fuzzing.md).
#
#   scripts/fuzz.sh SECONDS_PER_TARGET [BUILD_DIR]     (default build-fuzz)
#
# Configures and builds fuzz/ with clang (ASan + UBSan + libFuzzer), builds the
# seed corpus from the repository's files into a temporary folder
# (fuzz/build_corpus.sh), runs every harness for SECONDS_PER_TARGET seconds and
# prints per target the executions, the coverage (cov: = covered edges) and what
# was found. Crash, leak, timeout and out-of-memory inputs are saved with their
# log (stack) in BUILD_DIR/fuzz-findings/; one whose stack top is inside
# libhdf5 goes to BUILD_DIR/fuzz-findings/hdf5/ ("in HDF5, not evas"): it does not
# fail the run, is added to the run's skip list and fuzzing of that target goes on
# for the rest of its time. Exit status: 1 if evas itself has a finding, else 0.
#
# Environment:
#   FUZZ_TARGETS      harnesses to run (default: all fuzz/fuzz_*.cpp)
#   JOBS              build jobs (default 1)
#   FUZZ_CORPUS_DIR   keep the grown corpus here across runs (default: temporary)
#   FUZZ_KEEP_GOING=1 libFuzzer fork mode, -ignore_crashes/timeouts/ooms: collects
#                     every finding of the time budget instead of stopping at the first
#   EVAS_BIN          evas executable for the body-file seeds (default build/evas)
#   FUZZ_NO_BUILD=1   run the harnesses already in BUILD_DIR (no configure/build)
set -euo pipefail
cd "$(dirname "$0")/.."
root="$(pwd)"
secs="${1:?usage: scripts/fuzz.sh SECONDS_PER_TARGET [BUILD_DIR]}"
build="${2:-build-fuzz}"
jobs="${JOBS:-1}"

# --- tools: clang with the libFuzzer runtime ---------------------------------------
# shellcheck source=scripts/clang_deps.sh
. scripts/clang_deps.sh

# --- build ----------------------------------------------------------------------------
if [ "${FUZZ_NO_BUILD:-0}" != 1 ]; then
  CC=clang CXX=clang++ cmake -S fuzz -B "$build" >/dev/null
  cmake --build "$build" -j"$jobs"
fi
build="$(cd "$build" && pwd)"

targets="${FUZZ_TARGETS:-$(cd fuzz && ls fuzz_*.cpp | sed 's/\.cpp$//')}"
max_len() {
  case "$1" in
    fuzz_scene | fuzz_calculix_inp | fuzz_calculix_dat) echo 16384 ;;
    fuzz_body_file) echo 32768 ;;
    *) echo 65536 ;;  # pressure table, .frd, matrix storage
  esac
}

work="$(mktemp -d "${TMPDIR:-/tmp}/evas-fuzz-run.XXXXXX")"
trap 'rm -rf "$work"' EXIT
fuzz/build_corpus.sh "$work/seeds" "${EVAS_BIN:-$root/build/evas}"
corpus_root="${FUZZ_CORPUS_DIR:-$work/corpus}"
mkdir -p "$corpus_root"
case "$(cd "$corpus_root" && pwd)/" in "$root"/fuzz/* | "$root"/tests/* | "$root"/scenes/*)
  echo "fuzz.sh: FUZZ_CORPUS_DIR must be outside the source tree" >&2; exit 2 ;; esac
findings="$build/fuzz-findings"
mkdir -p "$findings/hdf5" "$work/tmp" "$work/art"

export ASAN_OPTIONS="detect_leaks=1:symbolize=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"

# The first frame of the report's stack that is not the sanitizer/fuzzer runtime
# or the C/C++ runtime, e.g. "in H5F__super_read (/usr/lib/.../libhdf5_serial.so.103+0x...)".
# libc's string functions are left out by name and by source (a symbolized
# "__memcpy_avx512_unaligned_erms string/../sysdeps/..." names no library, and
# ASan's own strdup, strlen, memcpy ... are frames of the fuzzer binary): the
# frame below them is the one that passed the bad pointer.
# A time-out's stack starts with libFuzzer's alarm handler (frames of the
# harness binary, often unsymbolized) and the signal frame in libc: what ran
# when the alarm came is below that frame.
stack_top() {
  grep -E '^ *#[0-9]+ 0x[0-9a-f]+ ' "$1" |
    if grep -qE 'ALARM: working on the last Unit|libFuzzer: timeout' "$1"; then
      awk '{ l[NR] = $0 } /libc\.so/ && !s { s = NR } END { for (i = s + 1; i <= NR; i++) print l[i] }'
    else cat; fi |
    grep -vE ' in (__interceptor_|__asan|__sanitizer|__ubsan|__lsan|fuzzer::|abort|raise|__GI_|malloc|calloc|realloc|free|operator new|operator delete|std::terminate|__cxa_|__gnu_cxx::__verbose|_Unwind|LLVMFuzzer|__libc|gsignal|__mem(cpy|move|set|cmp)|__str|(mem(cpy|move|set|cmp|chr)|bcmp|str(n?dup|n?len|n?cmp|n?cpy|n?cat|r?chr|casecmp))\b)|libclang_rt|compiler-rt|libc\.so|libstdc\+\+\.so|libgcc_s|sysdeps/' |
    head -1 | sed -E 's/^ *#[0-9]+ 0x[0-9a-f]+ //' || true
}
# One line: what the report says (first matching line).
# Where an out-of-memory input works when its memory is not one large
# allocation: the RSS watcher's report then names no allocation of the input,
# and the memory may be churned through rather than held (HDF5's metadata cache
# on a corrupt object header allocates and frees blocks of a few hundred kB
# in a loop, and the sanitizer's allocator does not return them in time). The
# input is run alone, and when its resident memory passes 1 GB its main
# thread's stack is taken with gdb, in the sanitizer's frame format.
sample_stack() {  # BIN INPUT OUT
  local pid rss i
  : >"$3"
  command -v gdb >/dev/null 2>&1 || { echo "(gdb missing: no stack sample)" >"$3"; return; }
  ASAN_OPTIONS="$ASAN_OPTIONS:detect_leaks=0" EVAS_FUZZ_SKIP=/dev/null TMPDIR="$work/tmp" \
    "$1" -rss_limit_mb=4096 -timeout=60 "$2" >/dev/null 2>&1 &
  pid=$!
  for i in $(seq 1 600); do
    sleep 0.1
    rss=$(awk '/^VmRSS/ { print $2 }' "/proc/$pid/status" 2>/dev/null || true)
    [ -n "$rss" ] || break
    if [ "$rss" -gt 1048576 ]; then
      gdb -p "$pid" -batch -ex "thread 1" -ex "bt 60" 2>/dev/null |
        sed -nE 's/^#([0-9]+) +(0x[0-9a-f]+ in .*)/    #\1 \2/p' >"$3" || true
      break
    fi
  done
  kill -9 "$pid" 2>/dev/null || true
  wait "$pid" 2>/dev/null || true
}

summary() {
  grep -m1 -E 'ERROR: (AddressSanitizer|LeakSanitizer|libFuzzer)|runtime error:|terminate called|ALARM: working on the last Unit|==[0-9]+== ?ERROR' "$1" |
    sed -E 's/^==[0-9]+==//' | cut -c1-160 || true
}

evas_findings=0
printf '%-22s %10s %7s  %s\n' target execs cov result
for t in $targets; do
  bin="$build/$t"
  corpus="$corpus_root/$t"
  mkdir -p "$corpus"
  skip="$work/skip-$t.txt"
  cat "fuzz/skip/$t.txt" >"$skip" 2>/dev/null || : >"$skip"
  log="$work/$t.log"
  : >"$log"
  start=$(date +%s)
  execs=0 cov=0 found="" hdf5=0
  while :; do
    left=$((secs - ($(date +%s) - start)))
    [ "$left" -ge 2 ] || break
    rm -f "$work/art/"*
    mode=()
    [ "${FUZZ_KEEP_GOING:-0}" = 1 ] && mode=(-fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1)
    set +e
    EVAS_FUZZ_SKIP="$skip" TMPDIR="$work/tmp" "$bin" "${mode[@]}" -max_total_time="$left" \
      -rss_limit_mb=2048 -max_len="$(max_len "$t")" -timeout=10 -print_final_stats=1 \
      -artifact_prefix="$work/art/" "$corpus" "$work/seeds/$t" >"$log.part" 2>&1
    rc=$?
    set -e
    cat "$log.part" >>"$log"
    # executions and coverage: the last status line ("#N ... cov: C" or fork mode "#N: cov: C")
    last=$(grep -E '^#[0-9]+:?[[:space:]].*cov: [0-9]+' "$log.part" | tail -1 || true)
    n=$(echo "$last" | sed -nE 's/^#([0-9]+).*/\1/p')
    c=$(echo "$last" | sed -nE 's/.*cov: ([0-9]+).*/\1/p')
    n2=$(sed -nE 's/^stat::number_of_executed_units: ([0-9]+)/\1/p' "$log.part" | tail -1)
    [ -n "$n2" ] && n=$n2
    execs=$((execs + ${n:-0}))
    [ -n "$c" ] && [ "$c" -gt "$cov" ] && cov=$c
    shopt -s nullglob
    arts=("$work/art/"*)
    shopt -u nullglob
    if [ ${#arts[@]} -eq 0 ]; then
      if [ "$rc" -ne 0 ]; then
        evas_findings=$((evas_findings + 1))
        found="$found
    exit $rc without a saved input: $(summary "$log.part") (log: $build/$t.fuzz.log)"
      fi
      break
    fi
    again=0
    for a in "${arts[@]}"; do
      kind="$(basename "$a" | sed -E 's/-.*//')"   # crash, leak, timeout, oom, slow-unit
      [ "$kind" = slow ] && continue
      # Re-run the input alone for a clean report and stack. An out-of-memory
      # report names no allocation (the RSS watcher fires wherever the program
      # is), so an oom input is re-run with a malloc limit of 64 MB: the first
      # allocation that large stops it with its own stack, which tells whose it is.
      rlog="$a.log"
      limit=()
      [ "$kind" = oom ] && limit=(-malloc_limit_mb=64)
      ASAN_OPTIONS="$ASAN_OPTIONS:fast_unwind_on_malloc=0" EVAS_FUZZ_SKIP=/dev/null \
        TMPDIR="$work/tmp" timeout 60 "$bin" -rss_limit_mb=2048 "${limit[@]}" -timeout=10 \
        "$a" >"$rlog" 2>&1 || true
      top="$(stack_top "$rlog")"
      if [ "$kind" = oom ] && ! grep -q 'malloc(' "$rlog"; then
        # no allocation of its own exceeded the limit: where does the input work?
        sample_stack "$bin" "$a" "$rlog.sample"
        sampled="$(stack_top "$rlog.sample")"
        [ -n "$sampled" ] && top="$sampled (sampled at 1 GB resident)"
      fi
      [ -n "$top" ] || top="$(stack_top "$log.part")"
      what="$(summary "$rlog")"
      [ -n "$what" ] || what="$(summary "$log.part")"
      hash=$(python3 -c 'import sys
h=1469598103934665603
for b in open(sys.argv[1],"rb").read(): h=((h^b)*1099511628211)&0xFFFFFFFFFFFFFFFF
print("%016x"%h)' "$a")
      # An identifier evas leaves open is not a leak (HDF5's id table holds it), so a
      # leak allocated inside libhdf5 is HDF5's own, like a crash there.
      if echo "$top" | grep -q 'libhdf5'; then
        dst="$findings/hdf5/$t-$kind-$hash"
        hdf5=$((hdf5 + 1))
        echo "$hash  # $kind in HDF5: $top" >>"$skip"
        again=1
      else
        dst="$findings/$t-$kind-$hash"
        evas_findings=$((evas_findings + 1))
        found="$found
    $kind: $what
      stack top: ${top:-?}
      input: $dst"
      fi
      cp "$a" "$dst"
      cp "$rlog" "$dst.log"
      cat "$log.part" >"$dst.fuzz.log"
    done
    [ "$again" = 1 ] && [ -z "$found" ] && [ "${FUZZ_KEEP_GOING:-0}" != 1 ] || break
  done
  result="ok"
  [ "$hdf5" -gt 0 ] && result="ok; $hdf5 in HDF5, not evas ($findings/hdf5/)"
  [ -n "$found" ] && result="FOUND:$found"
  printf '%-22s %10d %7d  %s\n' "$t" "$execs" "$cov" "$result"
  cp "$log" "$build/$t.fuzz.log"
done
echo "fuzz: ${secs} s per target; findings (evas): $evas_findings; logs: $build/<target>.fuzz.log"
[ "$evas_findings" -eq 0 ]
