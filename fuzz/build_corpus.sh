#!/usr/bin/env bash
# Seed corpus of the evas fuzz harnesses, built from the repository's own files
# into OUT/<harness>/ (docs/fuzzing.md). Never writes into the source tree.
#
#   fuzz/build_corpus.sh OUT [EVAS_BIN]
#
# EVAS_BIN (default build/evas) writes small truss body files for the body-file
# harness; without it that corpus holds only what can be made without evas.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
out="${1:?usage: fuzz/build_corpus.sh OUT [EVAS_BIN]}"
evas="${2:-$root/build/evas}"
mkdir -p "$out"
out="$(cd "$out" && pwd)"
case "$out/" in "$root"/fuzz/*|"$root"/scenes/*|"$root"/tests/*|"$root"/validation/*)
  echo "build_corpus.sh: refusing to write into the source tree ($out)" >&2; exit 2;; esac
for t in fuzz_scene fuzz_body_file fuzz_pressure_table fuzz_calculix_inp fuzz_calculix_frd \
         fuzz_calculix_dat fuzz_calculix_matrix; do mkdir -p "$out/$t"; done
ccx="$root/tests/data/calculix"

# --- scenes: repository scenes, test-suite scene strings, truss variants ----------
for f in "$root"/scenes/*.yaml "$root"/validation/engine/engine.yaml; do
  [ -f "$f" ] && cp "$f" "$out/fuzz_scene/$(basename "$(dirname "$f")")-$(basename "$f")"
done
python3 - "$root" "$out/fuzz_scene" <<'PY'
import glob, os, re, sys
root, dst = sys.argv[1], sys.argv[2]
n = 0
# Raw-string scenes of the test suite.
for src in sorted(glob.glob(os.path.join(root, "tests", "test_*.cpp"))):
    text = open(src, encoding="utf-8", errors="replace").read()
    for m in re.finditer(r'R"\((.*?)\)"', text, re.S):
        s = m.group(1)
        if "bodies:" in s and "name:" in s:
            n += 1
            with open(os.path.join(dst, "test-%s-%d.yaml" % (os.path.basename(src)[:-4], n)), "w") as f:
                f.write(s.lstrip("\n"))
# The validation engine with its two FE bodies replaced by generated truss beams
# and its node sets mapped onto the truss sets, so that markers, all element types
# and the output section are reached without body files.
eng = os.path.join(root, "validation", "engine", "engine.yaml")
if os.path.exists(eng):
    s = open(eng).read()
    s = re.sub(r"file: \.\./bodies/crankshaft\.h5",
               "generate: {type: truss-beam, segments: 8, length: 0.5, width: 0.1, area: 5e-4}\n"
               "    modes: {rigid: true, elastic: 4}", s)
    s = re.sub(r"file: \.\./bodies/block\.h5",
               "generate: {type: truss-beam, segments: 8, length: 0.5, width: 0.3, area: 2e-3}\n"
               "    modes: {rigid: true, elastic: 4}", s)
    s = re.sub(r"set: (?:journal|bore|pin|liner|mount)(\d)", r"set: section\1", s)
    s = s.replace("set: head", "set: section6").replace("set: flywheel", "set: end1")
    open(os.path.join(dst, "engine-truss.yaml"), "w").write(s)
    # Same, with the centre fits removed (the truss sets are small and regular).
    open(os.path.join(dst, "engine-truss-nocentre.yaml"), "w").write(
        re.sub(r", centre: \[[^\]]*\]", "", s))
# A minimal scene of each LOF kind.
base = """name: min
bodies:
  - name: b
    generate: {type: truss-beam, segments: 2, length: 0.2, width: 0.02}
    modes: {rigid: true, elastic: 2}
    lof: %s
markers:
  - {name: m, body: b, set: end1}
  - {name: g, ground: [0.2, 0, 0]}
elements:
  - {name: k, type: spring-damper, markers: [m, g], stiffness: [1e5, 1e5, 1e5]}
integrator: {name: generalized-alpha, step: 1e-4}
time: {start: 0, end: 0.001}
output: {grid: crank-angle, step: 1, crank_body: b, channels: [{marker: m}, {modal: b}]}
"""
for i, lof in enumerate(["{kind: fixed, origin: [0, 0, 0], velocity: [1, 0, 0]}",
                         "{kind: spin, axis: [1, 0, 0], speed_profile: [[0, 0], [0.001, 100]]}",
                         "{kind: tracking, interval: 1e-4, angular_velocity: [0, 0, 1]}"]):
    open(os.path.join(dst, "min-lof%d.yaml" % i), "w").write(base % lof)
PY

# --- pressure tables ----------------------------------------------------------------
cp "$root"/validation/data/*.txt "$out/fuzz_pressure_table/" 2>/dev/null || true
python3 - "$out/fuzz_pressure_table" <<'PY'
import math, os, sys
d = sys.argv[1]
with open(os.path.join(d, "small-bar.txt"), "w") as f:
    f.write("# unit: bar\n# small synthetic table\n")
    for a in range(0, 720, 10):
        f.write("%g\t%.4f\n" % (a, 1.0 + 80.0 * math.exp(-((a - 10) / 30.0) ** 2)))
with open(os.path.join(d, "small-mpa-wrap.txt"), "w") as f:
    f.write("# unit: MPa\n")
    for a in list(range(5, 720, 9)) + [725]:
        f.write("%g %g\n" % (a, 0.1 + (0.0 if a != 14 else 5.0)))
PY

# --- CalculiX ------------------------------------------------------------------------
cp "$ccx"/*.inp "$out/fuzz_calculix_inp/"
cp "$ccx"/*.dat "$out/fuzz_calculix_dat/"
# The first three modes of the block's .frd (the full file, ~160 kB, is above -max_len).
python3 - "$ccx/block_ev.frd" "$out/fuzz_calculix_frd/block_ev_3modes.frd" <<'PY'
import sys
lines, keep, modes = open(sys.argv[1]).read().splitlines(), [], 0
for l in lines:
    if l.startswith("  100C"):
        modes += 1
        if modes > 3:
            break
    keep.append(l)
open(sys.argv[2], "w").write("\n".join(keep + [" 9999"]) + "\n")
PY
sep='%%evas-part%%'
{ cat "$ccx/two_tets_mx.inp"; echo "$sep"; cat "$ccx/two_tets_mx.sti"; echo "$sep";
  cat "$ccx/two_tets_mx.mas"; echo "$sep"; cat "$ccx/two_tets_mx.dof"; } \
  > "$out/fuzz_calculix_matrix/two_tets_mx.txt"
{ cat "$ccx/two_tets_mx.inp"; echo "$sep"; echo "$sep";
  cat "$ccx/two_tets_mx.mas"; echo "$sep"; cat "$ccx/two_tets_mx.dof"; } \
  > "$out/fuzz_calculix_matrix/two_tets_mass_only.txt"

# --- body files: small truss bodies written by `evas body truss` --------------------------
if [ -x "$evas" ]; then
  "$evas" body truss "$out/fuzz_body_file/truss1.h5" --segments 1 --elastic 2 >/dev/null
  "$evas" body truss "$out/fuzz_body_file/truss2.h5" --segments 2 --elastic 3 \
    --damping-ratio 0.02 >/dev/null
  "$evas" body truss "$out/fuzz_body_file/truss1-norigid.h5" --segments 1 --elastic 1 \
    --no-rigid >/dev/null
else
  echo "build_corpus.sh: $evas not found: no body-file seeds (the harness starts from nothing)" >&2
fi
for t in "$out"/*/; do printf '  %-22s %3d seeds\n' "$(basename "$t")" "$(ls "$t" | wc -l)"; done
