#!/bin/sh
# Builds the evas of 2026-11-24 (commit baefa5a, the code issue 12 measured its
# starting point with: 45,160 steps and 73 us per step at IDA rtol 1e-5 on
# Case 1) into BUILD/baseline, so that `make bench` runs it side by side with
# today's evas on the same machine. The source comes from this clone's history
# (git archive into BUILD/baseline/src; nothing is written into the source
# tree); a clone without that commit (a shallow one) skips the side-by-side
# table with a message. Built once: a second call finds BUILD/baseline/commit.
# Usage: bench/baseline.sh [BUILD]
set -eu
BUILD=${1:-build}
JOBS=${JOBS:-2}
COMMIT=baefa5aa1cbeb2cfaa2957fd27f9f34c359cc838
DIR=$BUILD/baseline
if [ -x "$DIR/build/evas" ] && [ "$(cat "$DIR/commit" 2>/dev/null)" = "$COMMIT" ]; then
  exit 0
fi
ROOT=$(cd "$(dirname "$0")/.." && pwd)
if ! git -C "$ROOT" cat-file -e "$COMMIT^{commit}" 2>/dev/null; then
  echo "baseline.sh: commit $COMMIT is not in this clone (shallow?); the side-by-side" \
       "table of docs/performance.md is skipped" >&2
  exit 0
fi
rm -rf "$DIR"
mkdir -p "$DIR/src"
git -C "$ROOT" archive "$COMMIT" | tar -x -C "$DIR/src"
# as it was built then: the portable x86-64 build, Release
cmake -S "$DIR/src" -B "$DIR/build" -DCMAKE_BUILD_TYPE=Release -DEVAS_WERROR=OFF >/dev/null
cmake --build "$DIR/build" -j"$JOBS" --target evas
echo "$COMMIT" > "$DIR/commit"
