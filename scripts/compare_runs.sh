#!/bin/sh
# Compares two folders of scripts/reference_runs.sh: every results.csv (17
# significant digits, every row and channel), every exit code, and every
# summary.json and study table with the lines that measure the machine (wall
# times, peak memory, the scene's temporary path) left out. Exit 0 when all are equal.
#   usage: scripts/compare_runs.sh BEFORE_DIR AFTER_DIR
set -eu
if [ $# -ne 2 ]; then
  echo "usage: $0 BEFORE_DIR AFTER_DIR" >&2
  exit 1
fi
a=$1
b=$2
# lines of a summary or table that differ from run to run on the same code
machine='wall|peak_memory|"time_s"|seconds|"scene_path"'
strip() {
  case $1 in
    *.csv) # the columns whose header names a time of the machine
      awk -F, -v m="$machine" 'NR == 1 {for (i = 1; i <= NF; i++) drop[i] = ($i ~ m)}
        {line = ""; for (i = 1; i <= NF; i++) if (!drop[i]) line = line $i ","; print line}' "$1" ;;
    *) grep -v -E "$machine" "$1" || true ;;
  esac
}
differ=0
count=0
for f in $(cd "$a" && find . -name 'results.csv' -o -name '*.exit' -o -name 'summary.json' \
             -o -name 'study.csv' | sort); do
  count=$((count + 1))
  if [ ! -f "$b/$f" ]; then
    echo "missing in $b: $f"
    differ=1
    continue
  fi
  case $f in
    *summary.json | *study.csv)
      if [ "$(strip "$a/$f")" != "$(strip "$b/$f")" ]; then
        echo "differs: $f"
        differ=1
      fi ;;
    *)
      if ! cmp -s "$a/$f" "$b/$f"; then
        echo "differs: $f"
        differ=1
      fi ;;
  esac
done
echo "$count files compared: $([ $differ = 0 ] && echo 'all equal' || echo 'DIFFERENCES')"
exit $differ
